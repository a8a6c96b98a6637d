"""strata_freecad inside FreeCAD's own interpreter, headless:  freecadcmd tests/freecad/test_freecad.py

Run by CTest (tests/CMakeLists.txt, FreeCAD.MeshShape) with STRATA_BUILD_PYTHON (the build
tree's package, as tests/python/conftest.py uses BUILD_DIR) and STRATA_FREECAD_MOD (the
repository's freecad/StrataMesher); without them, the installed strata and module are used.
freecadcmd's exit status does not report a failing script, so this one ends the process itself:
status 0 and the line "strata_freecad tests: OK" only when every check passed.
"""

import os
import re
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
for var in ("STRATA_FREECAD_MOD", "STRATA_BUILD_PYTHON"):
    if os.environ.get(var):
        sys.path.insert(0, os.environ[var])
sys.path.insert(0, HERE)  # freecad_checks beside this script

import freecad_checks  # noqa: E402
from freecad_checks import check  # noqa: E402

import numpy as np  # noqa: E402

import FreeCAD  # noqa: E402
import Fem  # noqa: E402
import Part  # noqa: E402

import strata  # noqa: E402
import strata_freecad  # noqa: E402

HEMISPHERE_CYLINDER = os.path.join(ROOT, "examples", "data", "hemisphere_cylinder_halfdomain.stp")
# quads: quadrilaterals on the wall, so hexahedra in the layers and pyramids over their tops;
# prisms where triangles stay, tetrahedra to the farfield: all four volume types.
OPTIONS = dict(layers=2, first_height=0.01, growth=1.2, quads=True, farfield_size=3.0, farfield_divisions=4)


# --- FreeCAD's orientation conventions, used as witnesses ---------------------------------

# SMESH's SMDS_VolumeTool (bundled in FreeCAD) lists each linear volume's faces, in FreeCAD's
# node order, such that every face's right-hand normal points out of a correctly oriented
# volume (its tables Tetra_F, Pyramid_F, Penta_FE, Hexa_FE: "FORWARD -> EXTERNAL").
SMESH_EXTERNAL_FACES = {
    4: [(0, 1, 2), (0, 3, 1), (1, 3, 2), (0, 2, 3)],
    5: [(0, 1, 2, 3), (0, 4, 1), (1, 4, 2), (2, 4, 3), (3, 4, 0)],
    6: [(0, 1, 2), (3, 5, 4), (0, 2, 5, 3), (1, 4, 5, 2), (0, 3, 4, 1)],
    8: [(0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (3, 2, 6, 7), (0, 3, 7, 4), (1, 5, 6, 2)],
}


def smesh_volume(xyz):
    """Signed volume of linear volumes in FreeCAD's (SMESH's) convention: the divergence
    theorem over SMESH's external faces, each face a fan of triangles from its centroid
    (exact for flat faces, and closes up for warped quads). Positive = the volume is oriented
    as FreeCAD's SMESH expects. xyz: (n, k, 3) coordinates in FreeCAD's node order."""
    vol = np.zeros(len(xyz))
    for face in SMESH_EXTERNAL_FACES[xyz.shape[1]]:
        f = xyz[:, list(face)]
        c = f.mean(axis=1)
        for i in range(len(face)):
            a, b = f[:, i], f[:, (i + 1) % len(face)]
            vol += np.einsum("ij,ij->i", c, np.cross(a, b)) / 6.0  # tetrahedron (0, c, a, b)
    return vol


def smds_forward(xyz):
    """SMDS_VolumeTool::Set's own test: forward when the bottom face's normal (first 3 nodes,
    or 4) points away from the last node. A cheap test: for a prism or hexahedron in SMESH's
    order the last node sits diagonally across a side face from the first, so thin layer cells
    on a curved wall can fail it while valid; used here on single cells only."""
    k = xyz.shape[1]
    base = {4: 3, 5: 4, 6: 3, 8: 4}[k]
    b = xyz[:, :base]
    normal = np.zeros((len(xyz), 3))
    for i in range(base):
        normal += np.cross(b[:, i] - b[:, 0], b[:, (i + 1) % base] - b[:, 0])
    up = xyz[:, -1] - xyz[:, 0]
    return np.einsum("ij,ij->i", normal, up) < 0


def corner_jacobians(xyz, kind):
    """det of the three edges at every corner of cells in Abaqus' (= Gmsh's, VTK's) order:
    all positive for a valid element. xyz: (n, k, 3)."""
    corners = {
        "C3D4": [(0, 1, 2, 3), (1, 2, 0, 3), (2, 0, 1, 3), (3, 0, 2, 1)],
        "C3D6": [(0, 1, 2, 3), (1, 2, 0, 4), (2, 0, 1, 5), (3, 5, 4, 0), (4, 3, 5, 1), (5, 4, 3, 2)],
        "C3D8": [(0, 1, 3, 4), (1, 2, 0, 5), (2, 3, 1, 6), (3, 0, 2, 7),
                 (4, 7, 5, 0), (5, 4, 6, 1), (6, 5, 7, 2), (7, 6, 4, 3)],
    }[kind]
    out = []
    for o, a, b, c in corners:
        e1, e2, e3 = xyz[:, a] - xyz[:, o], xyz[:, b] - xyz[:, o], xyz[:, c] - xyz[:, o]
        out.append(np.einsum("ij,ij->i", np.cross(e1, e2), e3))
    return np.array(out).T


def femmesh_volumes(fm):
    """{node count: (ids, (n, k, 3) coordinates)} of the FemMesh's volumes, as FreeCAD stores them."""
    nodes = fm.Nodes
    by_count = {}
    for vid in fm.Volumes:
        ids = fm.getElementNodes(vid)
        by_count.setdefault(len(ids), []).append(ids)
    out = {}
    for k, rows in by_count.items():
        out[k] = np.array([[tuple(nodes[i]) for i in row] for row in rows])
    return out


def abaqus_elements(fm):
    """FreeCAD's own Abaqus writer (FemMesh.writeABAQUS, what its CalculiX solver runs on):
    {type: (n, k, 3) coordinates} in Abaqus' node order, which it derives from SMESH's."""
    nodes = fm.Nodes
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "mesh.inp")
        fm.writeABAQUS(path, 1, False)  # highest-dimension elements only, no groups
        text = open(path).read()
    out = {}
    for block in re.split(r"^\*Element,", text, flags=re.M)[1:]:
        kind = re.match(r"\s*TYPE=(\w+)", block).group(1)
        rows = []
        for line in block.splitlines()[1:]:
            if not line or line.startswith("*"):
                break
            rows.append([int(v) for v in line.split(",") if v.strip()][1:])
        out.setdefault(kind, []).extend(rows)
    return {k: np.array([[tuple(nodes[i]) for i in row] for row in rows]) for k, rows in out.items()}


# --- tests ----------------------------------------------------------------------------------

def test_imports():
    # inside freecadcmd: the module and the package under test (the build tree's when CTest runs)
    if os.environ.get("STRATA_BUILD_PYTHON"):
        expected = os.path.realpath(os.path.join(os.environ["STRATA_BUILD_PYTHON"], "strata"))
        check(os.path.realpath(os.path.dirname(strata.__file__)) == expected, f"strata from {strata.__file__}")
    check(sys.version_info[:2] == (3, 11), f"FreeCAD's Python is {sys.version}")


def test_reorder_on_single_cells():
    # One cell of each type, in Strata's order with positive volume, through to_femmesh: every
    # one forward for SMDS; added unpermuted (Strata's order as is) each would be reversed, so
    # the criterion can fail.
    cells = {
        "tetrahedron": [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)],
        "pyramid": [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)],
        "prism": [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1)],
        "hexahedron": [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],
    }
    for kind, pts in cells.items():
        pts = np.array(pts, float)
        reordered = pts[list(strata_freecad.SMESH_ORDER[kind])][None]
        exact = {"tetrahedron": 1 / 6, "pyramid": 1 / 3, "prism": 1 / 2, "hexahedron": 1.0}[kind]
        check(abs(smesh_volume(reordered)[0] - exact) < 1e-12, f"{kind}: SMESH volume {smesh_volume(reordered)}")
        check(abs(smesh_volume(pts[None])[0] + exact) < 1e-12, f"{kind}: Strata's order not negative for SMESH")
        check(smds_forward(reordered).all(), f"{kind}: not forward after SMESH_ORDER")
        check(not smds_forward(pts[None]).any(), f"{kind}: Strata's order is forward too (criterion cannot fail)")


def test_mesh_shape_hemisphere_cylinder():
    doc = FreeCAD.newDocument("StrataTest")
    shape = Part.read(HEMISPHERE_CYLINDER)
    body = doc.addObject("Part::Feature", "HemisphereCylinder")
    body.Shape = shape
    doc.recompute()

    obj = strata_freecad.mesh_shape(doc, body, **OPTIONS)
    check(obj.isDerivedFrom("Fem::FemMeshObject"), obj.TypeId)
    check(obj.Part == body and obj.Layers == 2 and abs(obj.FirstHeight.Value - 0.01) < 1e-12, "properties")
    fm = obj.FemMesh
    result = obj.Proxy.result

    # The same shape through strata.mesh directly (its BREP, the same options): the counts
    # FreeCAD holds are Strata's, cell for cell, face for face.
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "shape.brep")
        shape.exportBrep(path)
        direct = strata.mesh(path, **OPTIONS)
    cells = direct.report["cells"]
    print("strata.mesh:", cells, "patches", direct.patch_names)
    check(result.report["cells"] == cells, f"run {result.report['cells']} != direct {cells}")
    for kind in ("hexahedron", "prism", "pyramid", "tetrahedron"):
        check(cells[kind] > 0, f"the case has no {kind}: not every type tested")
    check(fm.HexaCount == cells["hexahedron"], f"hexahedra {fm.HexaCount} != {cells['hexahedron']}")
    check(fm.PrismCount == cells["prism"], f"prisms {fm.PrismCount} != {cells['prism']}")
    check(fm.PyramidCount == cells["pyramid"], f"pyramids {fm.PyramidCount} != {cells['pyramid']}")
    check(fm.TetraCount == cells["tetrahedron"], f"tetrahedra {fm.TetraCount} != {cells['tetrahedron']}")
    check(fm.VolumeCount == sum(cells.values()), "volume count")
    check(fm.NodeCount == len(direct.points), f"nodes {fm.NodeCount} != {len(direct.points)}")

    # One face group per patch, named after it, with the patch's faces.
    names = {fm.getGroupName(g): g for g in fm.Groups}
    check(sorted(names) == sorted(direct.patch_names), f"groups {sorted(names)} != {direct.patch_names}")
    check("farfield" in names, "no farfield group")
    total = 0
    for patch in direct.patch_names:
        n = sum(len(b) for b in direct.faces(patch).values() if b is not None)
        g = names[patch]
        check(fm.getGroupElementType(g) == "Face", f"group {patch} holds {fm.getGroupElementType(g)}")
        check(len(fm.getGroupElements(g)) == n, f"group {patch}: {len(fm.getGroupElements(g))} faces, Strata {n}")
        total += n
    check(fm.FaceCount == total, f"faces {fm.FaceCount} != {total}")
    print("FemMesh:", fm.HexaCount, "hexahedra,", fm.PrismCount, "prisms,", fm.PyramidCount, "pyramids,",
          fm.TetraCount, "tetrahedra,", fm.FaceCount, "faces in", len(names), "groups")

    # Orientation, two witnesses from FreeCAD's own code: every volume as FreeCAD stores it has
    # a positive volume over SMESH's external faces, and the total is Strata's; every element
    # FreeCAD's Abaqus writer produces (tetrahedra, prisms, hexahedra; it writes no pyramids)
    # has a positive Jacobian at every corner.
    volumes = femmesh_volumes(fm)
    check(sorted(volumes) == [4, 5, 6, 8], f"volume node counts {sorted(volumes)}")
    total_volume = 0.0
    for k, xyz in volumes.items():
        v = smesh_volume(xyz)
        check((v > 0).all(), f"{(v <= 0).sum()} of {len(xyz)} {k}-node volumes not positive for SMESH")
        total_volume += v.sum()
    check(abs(total_volume - direct.report["quality"]["cell_volume"]) < 1e-6 * total_volume,
          f"volume {total_volume} != Strata's {direct.report['quality']['cell_volume']}")
    inp = abaqus_elements(fm)
    check(sorted(inp) == ["C3D4", "C3D6", "C3D8"], f"Abaqus types {sorted(inp)}")
    check(len(inp["C3D4"]) == cells["tetrahedron"] and len(inp["C3D6"]) == cells["prism"]
          and len(inp["C3D8"]) == cells["hexahedron"], "Abaqus element counts")
    for kind, xyz in inp.items():
        det = corner_jacobians(xyz, kind)
        check((det > 0).all(), f"{kind}: {(det <= 0).any(axis=1).sum()} elements with a non-positive corner")

    # run() again after a property change: the mesh follows.
    before = (fm.VolumeCount, fm.HexaCount, fm.PrismCount)
    obj.Layers = 3
    rerun = strata_freecad.run(obj)
    check(obj.FemMesh.VolumeCount == sum(rerun.report["cells"].values()), "rerun not stored")
    check(obj.FemMesh.HexaCount == rerun.report["cells"]["hexahedron"] == before[1] // 2 * 3,
          f"3 layers: {obj.FemMesh.HexaCount} hexahedra, 2 layers had {before[1]}")
    check("hexahedron" in obj.Report and "farfield" in obj.Report, obj.Report)

    now, name = obj.FemMesh, obj.Name
    counts = (now.HexaCount, now.PrismCount, now.PyramidCount, now.TetraCount, now.FaceCount, len(now.Groups))
    # The document saves and reopens with its options (the proxy restores from strata_freecad).
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "strata.FCStd")
        doc.saveAs(path)
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(path)
        again = doc.getObject(name)
        check(again.Layers == 3 and again.Growth == 1.2, "options after reopening")
        # every type, pyramids too (FreeCAD 0.20's own UNV storage drops them), and the groups
        fm = again.FemMesh
        reopened = (fm.HexaCount, fm.PrismCount, fm.PyramidCount, fm.TetraCount, fm.FaceCount, len(fm.Groups))
        check(reopened == counts, f"after reopening {reopened}, before {counts}")
        check(isinstance(again.Proxy, strata_freecad.StrataMesh), f"proxy {again.Proxy!r}")
        FreeCAD.closeDocument(doc.Name)


def test_defaults_and_errors():
    doc = FreeCAD.newDocument("StrataDefaults")
    box = doc.addObject("Part::Box", "Box")
    doc.recompute()
    obj = strata_freecad.make_mesh_object(doc, box)
    defaults = {k["name"]: k["default"] for k in strata.keywords("mesh")}
    opts = strata_freecad.options_of(obj)
    for name, _, _ in strata_freecad.OPTIONS:
        check(opts[name] == defaults[name], f"{name}: property default {opts[name]!r} != strata's {defaults[name]!r}")
    try:
        strata_freecad.mesh_shape(doc, box, layer=3)
    except TypeError as e:
        check("layer" in str(e), str(e))
    else:
        raise AssertionError("an unknown option was accepted")
    check(len([o for o in doc.Objects if o.TypeId == "Fem::FemMeshObjectPython"]) == 1, "failed object left behind")
    try:
        strata_freecad.mesh_shape(doc, box, layers=2, growth=-1.0)
    except strata.InputError as e:
        print("expected error:", e)
    else:
        raise AssertionError("growth=-1 was accepted")
    FreeCAD.closeDocument(doc.Name)


def test_one_click_with_the_defaults():
    # What pressing Mesh gives with the panel as it opens: a box, and the hemisphere-cylinder air
    # domain with only its patches' kinds set (its outflow plane renamed, as the CLI's --patch
    # surface_3=other:outlet does). The first height is chosen from the walls, the body inside
    # its domain is meshed at its own twentieth, not the domain's.
    doc = FreeCAD.newDocument("StrataOneClick")
    box = doc.addObject("Part::Box", "Box")  # 10 mm
    domain = doc.addObject("Part::Feature", "HemisphereCylinder")
    domain.Shape = Part.read(HEMISPHERE_CYLINDER)
    doc.recompute()
    for part, patches, walls_length in ((box, None, 10.0),
                                        (domain, {"surface_1": "farfield", "surface_2": "symmetry",
                                                  "surface_3": "other:outlet"}, 10.0)):
        obj = strata_freecad.make_mesh_object(doc, part)
        if patches:
            obj.PatchKinds = patches
        check(obj.FirstHeight.Value == 0.0 and obj.Size.Value == 0.0, "the panel's defaults changed")
        m = strata_freecad.run(obj)
        report = m.report
        check("first height" in obj.Report and "chosen" in obj.Report, obj.Report)
        if patches:
            groups = {obj.FemMesh.getGroupName(g) for g in obj.FemMesh.Groups}
            check("outlet" in m.patch_names and "surface_3" not in m.patch_names, f"patches {m.patch_names}")
            check("outlet" in groups, f"FEM groups {sorted(groups)}")
        chosen = report["automatic_first_height"]
        print(part.Name, "first height", chosen, "cells", report["cells"])
        check(abs(chosen["walls_length"] - walls_length) < 1e-5 * walls_length, f"walls {chosen}")
        check(abs(report["thickness"] - 0.02 * chosen["walls_length"]) < 1e-9, f"thickness {report['thickness']}")
        check(report["quality"]["openfoam"]["check_mesh_ok"], f"{part.Name}: {report['quality']['openfoam']}")
        walls = [c for c in report["patches"]]
        nodes = sum(c["nodes"] for c in walls)
        full = sum(c["full_nodes"] for c in walls)
        check(nodes > 100, f"{part.Name}: only {nodes} wall nodes")
        check(full >= 0.95 * nodes, f"{part.Name}: every layer on {full} of {nodes} wall nodes")
    FreeCAD.closeDocument(doc.Name)


def main():
    tests = [test_imports, test_reorder_on_single_cells, test_defaults_and_errors, test_mesh_shape_hemisphere_cylinder,
             test_one_click_with_the_defaults]
    freecad_checks.run(tests, "strata_freecad tests")


main()
