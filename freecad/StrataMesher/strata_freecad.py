"""Strata in FreeCAD: a hybrid boundary-layer mesh of a Part shape as a FEM mesh object.

    import strata_freecad
    mesh = strata_freecad.mesh_shape(doc, doc.Body, layers=10, first_height=0.01, growth=1.2)
    mesh.FemMesh.PrismCount, mesh.FemMesh.Groups        # one face group per Strata patch

mesh_shape() adds a "Fem::FemMeshObjectPython" (a Fem::FemMeshObject, like FreeCAD's own
Gmsh and Netgen meshers make) whose properties are Strata's options, runs Strata on the shape
and stores the mesh in its FemMesh: hexahedra, prisms, pyramids and tetrahedra as volumes, the
boundary faces as faces, and one face group per patch (named as Strata names the patch:
surface_1..., farfield, or the names of the input), as FEM and CfdOF-style workflows expect.
run(obj) meshes an existing object again after its properties changed (the task panel's Mesh
button). Lengths are in the shape's units, millimetres in FreeCAD.

This module needs no GUI (freecadcmd imports it); the command and task panel are in
strata_freecad_gui.
"""

import os
import tempfile

import FreeCAD
import Fem

import strata

__all__ = ["mesh_shape", "run", "make_mesh_object", "to_femmesh", "options_of", "OPTIONS", "SMESH_ORDER"]

# The options a mesh object carries as properties: (Strata keyword, property group, kind).
# Defaults and help come from strata.keywords() (the C++ Params structs), so they are never
# retyped here. kind: "length" → App::PropertyLength (a quantity in mm, FreeCAD's length
# unit and the unit of the BREP Strata reads); a tuple → App::PropertyEnumeration with those
# choices (Strata still checks the value); None → the type of the default.
OPTIONS = [
    ("size", "Surface", "length"),
    ("size_min", "Surface", "length"),
    ("curvature_points", "Surface", None),
    ("quads", "Surface", None),
    ("layers", "Boundary layers", None),
    ("distribution", "Boundary layers", ("auto", "geometric", "thickness", "tanh")),
    ("first_height", "Boundary layers", "length"),
    ("growth", "Boundary layers", None),
    ("thickness", "Boundary layers", "length"),
    ("yplus", "Boundary layers", None),
    ("reynolds", "Boundary layers", None),
    ("reference_length", "Boundary layers", "length"),
    ("max_aspect_ratio", "Boundary layers", None),
    ("step_quality", "Boundary layers", None),
    ("farfield", "Farfield", ("sphere", "box")),
    ("farfield_size", "Farfield", None),
    ("farfield_divisions", "Farfield", None),
    ("tet_growth", "Farfield", None),
    ("max_volume", "Farfield", None),
]

# Node order of each volume in FreeCAD's mesh (SMESH's SMDS) from Strata's (Gmsh's) order.
# Strata's cells have the bottom face's right-hand normal pointing to the top (det > 0 for
# a tetrahedron 0-1-2-3). SMESH's SMDS_VolumeTool calls a volume forward when the bottom
# face's normal points away from the last node (all face normals external), the opposite:
# so the bottom face is reversed, and a prism's and a hexahedron's top with it so that node i
# of the top stays above node i of the bottom. (FreeCAD's own Abaqus writer applies exactly the
# inverse permutations for C3D4, C3D6 and C3D8; tests/freecad checks both criteria.)
SMESH_ORDER = {
    "tetrahedron": (0, 2, 1, 3),
    "pyramid": (0, 3, 2, 1, 4),
    "prism": (0, 2, 1, 3, 5, 4),
    "hexahedron": (0, 3, 2, 1, 4, 7, 6, 5),
}


def _property_name(keyword):
    # FreeCAD's property style: first_height -> FirstHeight
    return "".join(part.capitalize() for part in keyword.split("_"))


def _keywords():
    table = {k["name"]: k for k in strata.keywords("mesh")}
    missing = [name for name, _, _ in OPTIONS if name not in table]
    if missing:
        raise RuntimeError(f"strata_freecad: the strata package has no keyword {missing} (an older build?)")
    return table


def _add_properties(obj):
    table = _keywords()
    if "Part" not in obj.PropertiesList:
        obj.addProperty("App::PropertyLink", "Part", "Strata", "The Part object (or body) whose shape is meshed")
    if "PatchKinds" not in obj.PropertiesList:
        # strata's patches keyword: {patch name: wall | symmetry | farfield | other}; empty:
        # Strata's own assignment (every CAD face a wall, a generated farfield).
        obj.addProperty("App::PropertyMap", "PatchKinds", "Strata",
                        "Patch kinds, e.g. surface_2 = symmetry (wall, symmetry, farfield or other); "
                        "strata keyword patches")
    if "MeshFile" not in obj.PropertiesList:
        obj.addProperty("App::PropertyFileIncluded", "MeshFile", "Strata",
                        "The mesh as MED, saved in the document: FreeCAD 0.20 saves a FemMesh as UNV, "
                        "which drops pyramids; the mesh is read back from this file on opening")
        obj.setEditorMode("MeshFile", 2)  # hidden
    if "Report" not in obj.PropertiesList:
        obj.addProperty("App::PropertyString", "Report", "Strata", "Strata's summary of the last run")
        obj.setEditorMode("Report", 1)  # read-only
    for name, group, kind in OPTIONS:
        prop = _property_name(name)
        if prop in obj.PropertiesList:
            continue
        k = table[name]
        default = k["default"]
        doc = f"{k['doc']} (strata keyword {name}; {k['param'] or 'option'}; default {default!r})"
        if kind == "length":
            obj.addProperty("App::PropertyLength", prop, group, doc)
            setattr(obj, prop, float(default))
        elif isinstance(kind, tuple):
            obj.addProperty("App::PropertyEnumeration", prop, group, doc)
            choices = list(kind) if default in kind else [default] + list(kind)
            setattr(obj, prop, choices)
            setattr(obj, prop, default)
        elif isinstance(default, bool):
            obj.addProperty("App::PropertyBool", prop, group, doc)
            setattr(obj, prop, default)
        elif isinstance(default, int):
            obj.addProperty("App::PropertyInteger", prop, group, doc)
            setattr(obj, prop, default)
        elif isinstance(default, float):
            obj.addProperty("App::PropertyFloat", prop, group, doc)
            setattr(obj, prop, default)
        else:
            obj.addProperty("App::PropertyString", prop, group, doc)
            setattr(obj, prop, str(default))


def options_of(obj):
    """The strata.mesh keywords an object's properties hold."""
    out = {}
    for name, _, kind in OPTIONS:
        value = getattr(obj, _property_name(name))
        if kind == "length":
            value = float(value.getValueAs("mm"))
        out[name] = value
    out["patches"] = dict(obj.PatchKinds) or None
    return out


def _set_options(obj, options):
    options = dict(options)
    if "patches" in options:
        obj.PatchKinds = {str(k): str(v) for k, v in (options.pop("patches") or {}).items()}
    known = {name: kind for name, _, kind in OPTIONS}
    unknown = sorted(set(options) - set(known))
    if unknown:
        raise TypeError(f"strata_freecad: unknown option(s) {unknown}; known: {sorted(known)}")
    for name, value in options.items():
        prop = _property_name(name)
        if known[name] == "length":
            setattr(obj, prop, FreeCAD.Units.Quantity(float(value), FreeCAD.Units.Length))
        else:
            setattr(obj, prop, value)


class Stateless:
    """A proxy with nothing to save: FreeCAD 0.20 pickles proxies with __getstate__ and
    __setstate__, newer versions with dumps and loads."""

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps = __getstate__
    loads = __setstate__


class StrataMesh(Stateless):
    """Proxy of a Fem::FemMeshObjectPython meshed by Strata (like FreeCAD's MeshGmsh)."""

    Type = "Fem::StrataMesh"

    def __init__(self, obj):
        obj.Proxy = self
        _add_properties(obj)

    def onDocumentRestored(self, obj):
        _add_properties(obj)  # options added by a newer Strata appear with their defaults
        # FreeCAD 0.20 stores the FemMesh property as UNV, whose SMESH driver has no pyramids:
        # the mesh as saved by run() in MED (every type, the groups) replaces what UNV kept.
        if obj.MeshFile and os.path.isfile(obj.MeshFile):
            obj.FemMesh = Fem.read(obj.MeshFile)

    def execute(self, obj):
        # As with FreeCAD's Gmsh mesher, a recompute keeps the mesh; meshing is explicit
        # (run(), the task panel's Mesh button): a hybrid mesh can take minutes.
        return None


def make_mesh_object(doc, part, name="StrataMesh"):
    """A new Strata mesh object for \\p part (a document object with a Shape), not meshed yet."""
    obj = doc.addObject("Fem::FemMeshObjectPython", name)
    StrataMesh(obj)
    obj.Part = part
    if FreeCAD.GuiUp:
        import strata_freecad_gui

        strata_freecad_gui.ViewProviderStrataMesh(obj.ViewObject)
    return obj


def to_femmesh(mesh):
    """A Fem.FemMesh from a strata.Mesh: nodes 1..n (Strata's node i is FreeCAD's i+1), the
    volumes in FreeCAD's node order (SMESH_ORDER), then the boundary faces, and one face group
    per patch. Returns (femmesh, {patch: [element ids]})."""
    fm = Fem.FemMesh()
    points = mesh.points.tolist()
    for i, (x, y, z) in enumerate(points):
        fm.addNode(x, y, z, i + 1)
    element = 0
    for kind, order in SMESH_ORDER.items():
        block = mesh.cells[kind]
        if block is None or len(block) == 0:
            continue
        block = (block[:, list(order)] + 1).tolist()
        for nodes in block:
            element += 1
            fm.addVolume(nodes, element)
    # Boundary faces keep Strata's orientation: right-hand normal out of the domain.
    groups = {}
    for patch in mesh.patch_names:
        ids = []
        for shape, block in mesh.faces(patch).items():
            if block is None or len(block) == 0:
                continue
            for nodes in (block + 1).tolist():
                element += 1
                fm.addFace(nodes, element)
                ids.append(element)
        group = fm.addGroup(patch, "Face")
        if ids:
            fm.addGroupElements(group, ids)
        groups[patch] = ids
    return fm, groups


def _shape_of(part):
    if part is None:
        raise ValueError("strata_freecad: the mesh object has no Part to mesh (set its Part property)")
    shape = getattr(part, "Shape", None)
    if shape is None or shape.isNull():
        raise ValueError(f"strata_freecad: {part.Label} has no shape to mesh")
    return shape


def _summary(m):
    r = m.report
    cells = ", ".join(f"{r['cells'].get(k, 0)} {k}" for k in ("hexahedron", "prism", "pyramid", "tetrahedron"))
    patches = ", ".join(m.patch_names)
    sj = r["quality"]["min_scaled_jacobian"]["all"]
    chosen = r.get("automatic_first_height")
    first = (f"; first height {chosen['first_height']:.3g} mm chosen (none asked: the layers reach "
             f"{r['thickness']:.3g} mm, 2 % of the walls' length)" if chosen and chosen["thickness_share"] > 0
             else f"; first height {chosen['first_height']:.3g} mm chosen (none asked)" if chosen else "")
    return (f"{cells}; {len(m.points)} nodes; min scaled Jacobian {sj:.3g}; "
            f"patches: {patches}{first}")


def run(obj, progress=None):
    """Mesh \\p obj's Part with the options in its properties; the result goes into obj.FemMesh.
    progress: callable(stage, fraction) as strata.mesh takes it. Returns the strata.Mesh."""
    shape = _shape_of(obj.Part)
    # Strata reads CAD files, not FreeCAD's in-memory shapes: the shape goes through a BREP,
    # OpenCASCADE's own format, which both FreeCAD and Gmsh (Strata's CAD reader) use
    # natively, so nothing is translated or healed on the way (a STEP round trip would) and
    # the faces keep their order; the file is deleted after the run. Lengths stay in FreeCAD's
    # millimetres (a BREP has no unit).
    with tempfile.TemporaryDirectory(prefix="strata_freecad_") as tmp:
        path = os.path.join(tmp, "shape.brep")
        shape.exportBrep(path)
        m = strata.mesh(path, progress=progress, **options_of(obj))
    fm, _ = to_femmesh(m)
    obj.FemMesh = fm
    with tempfile.TemporaryDirectory(prefix="strata_freecad_") as tmp:
        med = os.path.join(tmp, "strata_mesh.med")
        fm.write(med)
        obj.MeshFile = med  # copied into the document (see onDocumentRestored)
    obj.Report = _summary(m)
    FreeCAD.Console.PrintMessage(f"Strata: {obj.Label}: {obj.Report}\n")
    return m


def mesh_shape(doc, obj, name="StrataMesh", progress=None, **options):
    """Mesh the shape of \\p obj (a Part feature or a body) in \\p doc with Strata and return
    the new FEM mesh object (a Fem::FemMeshObject). options: strata.mesh keywords among
    OPTIONS (layers, first_height, growth, size, farfield, farfield_size, ...) and patches
    ({patch name: kind}, as strata.mesh takes it); the rest keep
    Strata's defaults. The strata.Mesh of the run is kept as the object's Proxy.result."""
    mesh_obj = make_mesh_object(doc, obj, name)
    try:
        _set_options(mesh_obj, options)
        mesh_obj.Proxy.result = run(mesh_obj, progress)
    except BaseException:
        doc.removeObject(mesh_obj.Name)
        raise
    doc.recompute()
    return mesh_obj
