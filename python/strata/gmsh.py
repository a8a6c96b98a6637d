"""Strata on the model of Python's own gmsh module, in this process.

    import gmsh, strata.gmsh
    gmsh.initialize()
    gmsh.model.occ.addSphere(0, 0, 0, 1); gmsh.model.occ.synchronize()
    gmsh.model.mesh.generate(2)
    report = strata.gmsh.mesh_current_model(layers=10, first_height=1e-3)
    gmsh.write("sphere_hybrid.msh")

Debian's python3-gmsh loads the same libgmsh.so.4.8 that Strata is linked against, so both
see one Gmsh state: Strata reads the model's surface mesh and puts the hybrid volume back into
it (strata::mesh_current_gmsh_model: one discrete volume with a physical group "fluid", one
discrete surface and 2D physical group per patch). A model whose surfaces are all CAD has its
walls meshed again finer where the layers would step at a gap or fan at a sharp edge, as
strata.mesh does on a CAD file (step_quality=0 and max_aspect_ratio=0 keep the model's mesh). TetGen runs from libtet loaded privately
(dlopen with RTLD_DEEPBIND, hybrid/src/tetgen_library.cpp), not from the modified copy of it
inside libgmsh: tests/python/test_gmsh_inprocess.py checks both in one process.
"""

import gmsh as _gmsh  # noqa: F401  the top-level gmsh module (absolute import): Strata shares its Gmsh

from . import _checked_timeout, _document, _note_gmsh_user, _signature, _strata, keywords

__all__ = ["mesh_current_model"]

_SIGNATURE = None


def mesh_current_model(**kwargs):
    bound = _SIGNATURE.bind(**kwargs)  # TypeError for an unknown keyword
    given = dict(bound.arguments)
    progress = given.pop("progress", None)
    if progress is not None and not callable(progress):
        raise TypeError(f"progress={progress!r}: expected a callable(stage, fraction) or None")
    timeout = _checked_timeout(given.pop("timeout", None))
    _note_gmsh_user()
    return _strata.mesh_current_gmsh_model(given, progress, timeout)


def _setup():
    import inspect

    global _SIGNATURE
    params = _signature("gmsh", [])
    params.append(inspect.Parameter("progress", inspect.Parameter.KEYWORD_ONLY, default=None))
    params.append(inspect.Parameter("timeout", inspect.Parameter.KEYWORD_ONLY, default=None))
    _SIGNATURE = inspect.Signature(params)
    mesh_current_model.__signature__ = _SIGNATURE
    mesh_current_model.__doc__ = _document(
        "gmsh",
        "mesh_current_model(...) -> dict: replace the current Gmsh model's surface mesh (its triangles and "
        "quadrangles, one patch per 2D physical group) by a hybrid volume mesh built on it; returns the report "
        "(OUT.report.json's keys: cells and quality per type, coverage per patch, times, provenance; no nodes, "
        "and re-meshed patches by number). gmsh.initialize() first: "
        "strata.InputError otherwise. If meshing fails, the model is left as it was. timeout=SECONDS: "
        "TimeoutError at the first check after that long (at least every 0.1 s; TetGen's child process is "
        "killed), the model left as it was.")


_setup()