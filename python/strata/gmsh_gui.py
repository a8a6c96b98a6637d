"""Strata inside Gmsh's window.

    python3 -m strata.gmsh_gui MODEL        (or: strata-gmsh MODEL)

Opens MODEL (.geo, .step, .brep, .stl, .msh: anything Gmsh opens) in Gmsh's FLTK window with
Strata's options in the ONELAB panel on the left (layers, first height, growth, farfield,
tetrahedra) and a "Strata: hybrid mesh" button. The button meshes the surface if the model has
no surface mesh yet, runs strata.gmsh.mesh_current_model on the open model with the panel's
values, shows the hybrid mesh, and writes the coverage report to Gmsh's message console.

The GUI only reads the panel and calls run_action(); run_action() works without a display
(tests/python/test_gmsh_gui.py sets the ONELAB parameters and calls it headless).
"""

import argparse
import json
import math
import sys

import gmsh

from . import InputError, _strata, keywords
from . import gmsh as strata_gmsh

# The panel: ONELAB name -> keyword of strata.gmsh.mesh_current_model. The numeric prefix
# orders the panel (Gmsh does not show it); each default is the keyword's default (the C++
# Params struct's): a first height of 0 is chosen from the walls (the layers reach 2 % of their
# length, said in the console), and the growth shows the ratio its 0 stands for.
PANEL = [
    ("Strata/1Layers", "layers"),
    ("Strata/2First height", "first_height"),
    ("Strata/3Growth", "growth"),
    ("Strata/4Farfield/1Shape", "farfield"),
    ("Strata/4Farfield/2Size (x body)", "farfield_size"),
    ("Strata/5Tetrahedra/1Radius-edge bound", "radius_edge"),
    ("Strata/5Tetrahedra/2Size growth", "tet_growth"),
    ("Strata/5Tetrahedra/3Max dihedral (deg)", "max_dihedral"),
    ("Strata/5Tetrahedra/4Refine", "refine"),
    ("Strata/5Tetrahedra/5Improve below (scaled Jacobian)", "tet_improve"),
]
RESULT = "Strata/9Result"
BUTTON = "ONELAB/Button"
ACTION = "ONELAB/Action"
ACTION_NAME = "strata"  # what Gmsh puts in ONELAB/Action when the button is pressed

_CHOICES = {"farfield": ["sphere", "box"]}


def _keyword_table():
    return {k["name"]: k for k in keywords("gmsh")}


def parameter_definitions():
    """Strata's ONELAB parameters for the open model, as dicts with the keys of ONELAB's JSON
    (gmsh.onelab.set): one per PANEL entry with its default, and the read-only Result."""
    table = _keyword_table()
    params = []
    for name, keyword in PANEL:
        k = table[keyword]
        default = k["default"]
        p = {"name": name, "attributes": {"Help": k["doc"]}}
        if keyword == "growth" and default == 0:
            default = _strata.DEFAULT_GROWTH
        if isinstance(default, bool):
            p.update(type="number", values=[int(default)], choices=[0, 1])
        elif isinstance(default, str):
            p.update(type="string", values=[default], choices=_CHOICES.get(keyword, [default]))
        else:
            p.update(type="number", values=[default])
            if isinstance(default, int):
                p.update(min=1, max=200, step=1)
        params.append(p)
    params.append(result_parameter(""))
    return params


def result_parameter(text):
    """The read-only Result parameter (a dict, as in parameter_definitions) holding text."""
    return {"type": "string", "name": RESULT, "values": [text], "readOnly": True, "attributes": {"Kind": "multiline"}}


def define_parameters():
    """Put Strata's parameters into the ONELAB database (defaults: the keywords') and the button."""
    gmsh.onelab.set(json.dumps(parameter_definitions()))
    gmsh.onelab.setString(BUTTON, ["Strata: hybrid mesh", ACTION_NAME])
    gmsh.onelab.set(json.dumps({"type": "string", "name": ACTION, "values": [""], "visible": False}))


def options_from_parameters(get_number=None, get_string=None):
    """The keywords of mesh_current_model from the ONELAB parameters, read with get_number and
    get_string (name -> values; by default gmsh.onelab's, the database of this process)."""
    get_number = get_number or gmsh.onelab.getNumber
    get_string = get_string or gmsh.onelab.getString
    table = _keyword_table()
    options = {}
    for name, keyword in PANEL:
        default = table[keyword]["default"]
        if isinstance(default, str):
            values = get_string(name)
        else:
            values = get_number(name)
        if len(values) == 0:
            raise InputError(f"ONELAB parameter '{name}' is missing: call define_parameters() first")
        value = values[0]
        if isinstance(default, bool):
            value = bool(value)
        elif isinstance(default, int):
            if value != int(value):
                raise InputError(f"{name} = {value}: expected a whole number")
            value = int(value)
        elif isinstance(default, float):
            value = float(value)
        options[keyword] = value
    return options


def coverage_lines(report):
    """The report as lines for Gmsh's message console."""
    cells = sum(report["cells"].values())
    q = report["quality"]
    sj = q["min_scaled_jacobian"]
    lines = [f"Strata: {cells} cells, min scaled Jacobian {sj['all']:.3g} ({q['worst_cell']['all']})"]
    for kind in ("hexahedron", "prism", "pyramid", "tetrahedron"):
        if kind in sj:
            lines.append(f"Strata:   {kind:12s} min scaled Jacobian {sj[kind]:.3g}")
    chosen = report.get("automatic_first_height")
    if chosen:
        lines.append(f"Strata: first height {chosen['first_height']:.3g}, none asked: the layers reach "
                     f"{100 * chosen['thickness_share']:.3g} % of the walls' length {chosen['walls_length']:.4g}"
                     if chosen["thickness_share"] > 0 else
                     f"Strata: first height {chosen['first_height']:.3g}, none asked: the layers reach the thickness")
    lines.append(f"Strata: coverage, {report['layers']} layers asked, {report['thickness']:.4g} thick "
                 f"(first {report['first_height']:.3g}):")
    for c in report["patches"]:
        full = c["full_nodes"] / c["nodes"] if c["nodes"] else 1.0
        lines.append(f"Strata:   {c['name']:20s} {c['nodes']:7d} nodes, {100 * full:5.1f}% full, "
                     f"mean {c['mean_layers']:.1f} layers, min {c['min_layers']}, "
                     f"thickness {100 * c['mean_share']:.1f}%")
    foam = q["openfoam"]
    lines.append(f"Strata: OpenFOAM checkMesh would {'say Mesh OK' if foam['check_mesh_ok'] else 'fail it'}: "
                 f"non-orthogonality max {foam['max_non_orthogonality_deg']:.3g} deg, "
                 f"skewness max {foam['max_skewness']:.3g}, aspect ratio max {foam['max_aspect_ratio']:.4g}")
    lines += [f"Strata:   {line}" for line in foam["failures"]]
    t = report["times"]
    lines.append(f"Strata: time {t['total']:.2f} s (layers {t['layers']:.2f}, pyramids {t['pyramids']:.2f}, "
                 f"tetrahedra {t['tetrahedra']:.2f}, validation {t['validation']:.2f})")
    return lines


def _has_surface_mesh():
    types, _, _ = gmsh.model.mesh.getElements(2)
    return len(types) > 0


def result_text(lines):
    """The Result parameter's text: the report's lines without their "Strata: " prefix."""
    return "\n".join(line.replace("Strata: ", "", 1) for line in lines)


def mesh_open_model(options, progress=None, log=None):
    """Strata on the open model with options (mesh_current_model's keywords), after meshing its
    surface if it has no surface mesh yet; log (default: Gmsh's logger) says so. The report."""
    log = log or gmsh.logger.write
    if not _has_surface_mesh():
        log("Strata: the model has no surface mesh; meshing it in 2D first")
        gmsh.model.mesh.generate(2)
    return strata_gmsh.mesh_current_model(progress=progress, **options)


def run_action(progress=None):
    """The button's action on the current model: surface mesh if there is none, then the hybrid
    mesh with the ONELAB parameters. Writes the report to Gmsh's console and the Result
    parameter; returns it. Strata's errors are written there too, then raised."""
    try:
        report = mesh_open_model(options_from_parameters(), progress)
    except Exception as e:  # shown to the user in the window, then raised to the caller
        try:
            gmsh.logger.write(f"Strata: {e}", "error")
        except Exception:
            pass  # Gmsh 4.8's Python API raises after logging an error; it is in the console
        gmsh.onelab.setString(RESULT, [f"failed: {e}"])
        raise
    lines = coverage_lines(report)
    for line in lines:
        gmsh.logger.write(line)
    gmsh.onelab.setString(RESULT, [result_text(lines)])
    return report


def volume_view_options():
    """The Gmsh options that show the new volume mesh as a user would look into it: the cells cut
    by the model's mid-plane (z), coloured by type (prisms, pyramids, tetrahedra), seen from the
    cut side. (name, value) pairs."""
    xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(-1, -1)
    mid = 0.5 * (zmin + zmax) if math.isfinite(zmin + zmax) else 0.0
    return [("Mesh.SurfaceFaces", 0), ("Mesh.VolumeFaces", 1), ("Mesh.VolumeEdges", 1),
            ("Mesh.ColorCarousel", 0),  # by element type
            ("Mesh.Clip", 1), ("General.ClipWholeElements", 1), ("General.ClipOnlyDrawIntersectingVolume", 1),
            ("General.Clip0A", 0), ("General.Clip0B", 0), ("General.Clip0C", -1), ("General.Clip0D", mid)]


def show_volume():
    """Show the new volume mesh cut by the mid-plane (volume_view_options)."""
    for option, value in volume_view_options():
        gmsh.option.setNumber(option, value)


def open_model(path, trust_geo=False):
    """Open path in Gmsh; a .geo script is checked first (Strata's check: no shell commands, no
    files written) unless trust_geo."""
    if path.lower().endswith(".geo") and not trust_geo:
        _strata.check_geo_script(path)
    gmsh.open(path)


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="strata-gmsh", description="Open MODEL in Gmsh's window with Strata's options in the ONELAB panel "
        "and a 'Strata: hybrid mesh' button.")
    parser.add_argument("model", help="anything Gmsh opens: .geo, .step, .brep, .stl, .msh")
    parser.add_argument("--run", action="store_true", help="press the button once the window is open")
    parser.add_argument("--trust-geo", action="store_true",
                        help="open a .geo script even where it runs commands or writes files")
    parser.add_argument("--screenshot", metavar="PNG",
                        help="with --run: save the graphics area as PNG when the mesh is shown, then close")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    if args.screenshot and not args.run:
        parser.error("--screenshot needs --run")
    gmsh.initialize()
    try:
        try:
            open_model(args.model, args.trust_geo)
        except InputError as e:  # a .geo script that runs commands or writes files
            print("strata-gmsh: error:", str(e).replace("trust_geo=True", "--trust-geo"), file=sys.stderr)
            return 1
        gmsh.option.setNumber("Solver.AutoMesh", 0)  # Gmsh's own Run would mesh the model in 3D
        define_parameters()
        # A panel wide enough for the parameters' names, and the message console open: the
        # report goes there.
        for option, value in (("General.MenuWidth", 330), ("General.GraphicsWidth", 860),
                              ("General.GraphicsHeight", 620), ("General.MessageHeight", 170),
                              ("General.ShowMessagesOnStartup", 1)):
            gmsh.option.setNumber(option, value)
        gmsh.fltk.initialize()
        if args.run:
            gmsh.onelab.setString(ACTION, [ACTION_NAME])
        while gmsh.fltk.isAvailable():
            action = gmsh.onelab.getString(ACTION)
            if ACTION_NAME in action:
                gmsh.onelab.setString(ACTION, [""])
                try:
                    run_action()
                    show_volume()
                except Exception:  # already in the console; the window stays open
                    if args.screenshot:
                        raise
                gmsh.fltk.update()
                gmsh.graphics.draw()
                if args.screenshot:
                    gmsh.write(args.screenshot)
                    break
            gmsh.fltk.wait()
    finally:
        gmsh.finalize()
    return 0


if __name__ == "__main__":
    sys.exit(main())
