"""Strata: near-body hybrid meshes for viscous CFD, from Python.

    import strata
    m = strata.mesh("sphere.stl", layers=10, first_height=1e-3, growth=1.2)
    m.points            # (n, 3) float64, a read-only view into the mesh
    m.prisms, m.tets    # (n, 6), (n, 4) node ids; m.cells: every type
    m.patch_names, m.faces("farfield")["triangle"]
    m.report["quality"]["min_scaled_jacobian"], m.report["patches"]   # OUT.report.json's keys
    m.write("sphere.cgr")   # or output="sphere.cgr" in the call
    strata.mesh("sphere.stl", layers=10, first_height=1e-3, output="case", foam_case=True)  # an OpenFOAM case

surface(), layers() and mesh() are the strata program's subcommands. Their keywords are the
Params structs' fields (strata.keywords() lists each with its default and the C++ parameter
it sets); every default is the library's own. progress=callable(stage, fraction) is called as
the stages run; Ctrl-C cancels at the next check (strata.Cancelled, a KeyboardInterrupt);
timeout=seconds raises TimeoutError at the first check after that long (a design loop's guard;
checks come at least every 0.1 s, and TetGen's child process is killed; Gmsh's own surface
meshing makes none, so there it acts when Gmsh returns), and nothing is written.
Errors raise strata.InputError (also a ValueError), TopologyError, BackendError, OutputError
(also an OSError: a full disk, a quota; the previous output is as it was), all strata.Error (a
RuntimeError), with Strata's message in keyword names.

strata.gmsh.mesh_current_model(...) meshes the model of Python's own gmsh module in place;
python3 -m strata.gmsh_gui MODEL opens Gmsh's window with Strata's options (strata-gmsh);
strata.gmsh_onelab makes Strata a ONELAB solver of the gmsh program itself (strata-gmsh-onelab).
"""

import inspect as _inspect
import sys as _sys

from . import _strata
from ._strata import (  # noqa: F401  (re-exported)
    BackendError,
    Cancelled,
    Error,
    InputError,
    Mesh,
    OutputError,
    Surface,
    TopologyError,
)

__all__ = [
    "surface", "layers", "mesh", "keywords", "Mesh", "Surface",
    "Error", "InputError", "TopologyError", "BackendError", "OutputError", "Cancelled",
]


def keywords(function=None):
    """The keywords as dicts (name, default, param, takes, doc); of one function if given
    ("surface", "layers", "mesh" or "gmsh")."""
    table = _strata.keywords()
    if function is None:
        return table
    return [k for k in table if function in k["takes"]]


def _note_gmsh_user():
    # A Python user who initialised Gmsh (import gmsh; gmsh.initialize()) shares the process's
    # one Gmsh with Strata's readers: record it so they neither initialise it again nor
    # finalise it at the end (which would drop the user's models).
    if "gmsh" in _sys.modules:
        _strata.note_gmsh_user()


def _signature(function, leading):
    params = list(leading)
    for k in keywords(function):
        params.append(_inspect.Parameter(k["name"], _inspect.Parameter.KEYWORD_ONLY, default=k["default"]))
    return params


def _document(function, summary):
    lines = [summary, "", "Keywords (default; the C++ parameter it sets):"]
    for k in keywords(function):
        param = f"; {k['param']}" if k["param"] else ""
        lines.append(f"  {k['name']}={k['default']!r}{param}: {k['doc']}")
    return "\n".join(lines)


def _checked_timeout(timeout):
    """timeout as given, after checking it is None or a number of seconds >= 0. The extension
    module keeps the deadline: it is checked at every progress report and between them (every
    50 ms while a stage polls for Ctrl-C, every 0.1 s while TetGen runs in its child process)."""
    if timeout is None:
        return None
    if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not timeout >= 0:
        raise ValueError(f"timeout={timeout!r}: expected None or a number of seconds >= 0")
    return timeout


def _pipeline(name, summary):
    run = getattr(_strata, name)
    leading = [
        _inspect.Parameter("input", _inspect.Parameter.POSITIONAL_OR_KEYWORD),
    ]
    trailing = [
        _inspect.Parameter("output", _inspect.Parameter.KEYWORD_ONLY, default=None),
        _inspect.Parameter("msh_version", _inspect.Parameter.KEYWORD_ONLY, default="4.1"),
        _inspect.Parameter("binary", _inspect.Parameter.KEYWORD_ONLY, default=False),
        _inspect.Parameter("progress", _inspect.Parameter.KEYWORD_ONLY, default=None),
        _inspect.Parameter("timeout", _inspect.Parameter.KEYWORD_ONLY, default=None),
    ]
    signature = _inspect.Signature(_signature(name, leading) + trailing)
    defaults = {k["name"]: k["default"] for k in keywords(name)}

    def function(*args, **kwargs):
        bound = signature.bind(*args, **kwargs)  # TypeError for an unknown or missing argument
        given = dict(bound.arguments)
        input_ = given.pop("input")
        output = given.pop("output", None)
        msh_version = given.pop("msh_version", "4.1")
        binary = given.pop("binary", False)
        if not isinstance(binary, bool):
            raise TypeError(f"binary={binary!r}: expected True (a binary .msh) or False")
        progress = given.pop("progress", None)
        if progress is not None and not callable(progress):
            raise TypeError(f"progress={progress!r}: expected a callable(stage, fraction) or None")
        timeout = _checked_timeout(given.pop("timeout", None))
        options = {k: v for k, v in given.items() if k in defaults}
        _note_gmsh_user()
        return run(input_, options, None if output is None else str(output), msh_version, binary, progress, timeout)

    function.__name__ = function.__qualname__ = name
    function.__signature__ = signature
    function.__doc__ = _document(name, summary)
    return function


surface = _pipeline(
    "surface",
    "surface(input, ...) -> Surface: read CAD (.step .iges .brep .geo) or a surface mesh (.stl .msh), "
    "or a list of them as one surface; check, orient, assign patch kinds. output: also write it.")
layers = _pipeline(
    "layers",
    "layers(input, ...) -> Mesh: the boundary-layer prisms and hexahedra marched from the walls, "
    "validated. output: also write it (and OUTPUT.report.json, the coverage).")
mesh = _pipeline(
    "mesh",
    "mesh(input, ...) -> Mesh: the whole pipeline: surface, boundary layers, pyramids, tetrahedra "
    "to the farfield; one validated hybrid mesh. output: also write it (.cgr with its .bc map, "
    ".msh, .vtk, .su2, ...) and OUTPUT.report.json; with foam_case=True, output is an OpenFOAM case "
    "directory (its constant/polyMesh and a simpleFoam start round it).")
