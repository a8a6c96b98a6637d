"""Strata next to Python's own gmsh module in one process, on one libgmsh.

Debian's libgmsh carries a modified TetGen under libtet's symbol names (docs PLATFORM.md);
Strata loads libtet privately (dlopen, RTLD_DEEPBIND). These tests prove, in a process that
imported gmsh (python3-gmsh, loading libgmsh.so.4.8 with ctypes) and had Gmsh mesh in 3D:
strata.gmsh.mesh_current_model puts prisms and tetrahedra into the very model Python sees;
Gmsh's own 3D meshers still work after Strata's TetGen ran; and Strata's TetGen output is
identical to that of a process that never loaded gmsh."""

import os
import subprocess
import sys

import gmsh
import numpy as np
import pytest

import strata
import strata.gmsh
from conftest import SPHERE_STL

PRISM, TET, PYRAMID, HEX, TRIANGLE = 6, 4, 7, 5, 2  # Gmsh element types


@pytest.fixture
def session():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    yield
    gmsh.finalize()


def sphere_surface(name="sphere", h=0.3):
    gmsh.model.add(name)
    gmsh.model.occ.addSphere(0, 0, 0, 1.0)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.model.mesh.generate(2)


def count(dim):
    types, tags, _ = gmsh.model.mesh.getElements(dim)
    return {int(t): len(tg) for t, tg in zip(types, tags)}


def gmsh_box_tets(algorithm):
    """Gmsh's own 3D mesher on a unit box: the number of tetrahedra, after checking that they
    are all of one orientation and fill the box's volume."""
    gmsh.model.add(f"box_{algorithm}")
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.2)
    gmsh.option.setNumber("Mesh.Algorithm3D", algorithm)
    gmsh.model.mesh.generate(3)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = np.zeros((int(max(tags)) + 1, 3))
    xyz[tags.astype(int)] = coords.reshape(-1, 3)
    _, nodes = gmsh.model.mesh.getElementsByType(TET)
    t = xyz[nodes.astype(int).reshape(-1, 4)]
    vol = np.einsum("ij,ij->i", np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), t[:, 3] - t[:, 0]) / 6
    assert (vol > 0).all() or (vol < 0).all()
    assert abs(abs(vol.sum()) - 1.0) < 1e-9
    gmsh.model.remove()
    return len(vol)


def test_mesh_current_model_puts_prisms_and_tets_into_pythons_model(session):
    sphere_surface()
    before = count(2)[TRIANGLE]
    report = strata.gmsh.mesh_current_model(layers=3, first_height=0.01, growth=1.2, farfield_size=5)
    cells = count(3)  # read back through Python's gmsh module
    assert cells.get(PRISM, 0) == 3 * before, cells  # every wall triangle gets its 3 prisms
    assert cells.get(TET, 0) > 0 and sum(report["cells"].values()) == sum(cells.values())
    assert report["quality"]["min_scaled_jacobian"]["all"] > 0
    assert "sphere" in gmsh.model.list()
    names = {gmsh.model.getPhysicalName(d, t) for d, t in gmsh.model.getPhysicalGroups()}
    assert {"fluid", "farfield"} <= names


def test_gmsh_3d_meshers_before_and_after_strata_tetgen(session):
    # Gmsh's Delaunay (1) before and after Strata's TetGen ran: the same mesh. HXT (10) varies
    # from run to run by itself (threads): it must still fill the box with valid tetrahedra.
    delaunay, hxt = gmsh_box_tets(1), gmsh_box_tets(10)
    sphere_surface()
    strata.gmsh.mesh_current_model(layers=2, first_height=0.01, farfield_size=5)
    assert count(3).get(TET, 0) > 0
    assert gmsh_box_tets(1) == delaunay > 0
    assert gmsh_box_tets(10) > 0 and hxt > 0


def test_tetgen_after_gmsh_meshed_in_3d_matches_a_process_without_gmsh(session, tmp_path):
    # Gmsh meshes in 3D first (its own TetGen copy and HXT get used), then Strata's TetGen.
    assert gmsh_box_tets(1) > 0 and gmsh_box_tets(10) > 0
    here = strata.mesh(SPHERE_STL, layers=3, first_height=1e-3, farfield_size=5)
    # the same run in a fresh interpreter that never imports gmsh
    ref = tmp_path / "ref.npz"
    code = ("import sys, numpy; sys.path.insert(0, sys.argv[1]); import strata; "
            "assert 'gmsh' not in sys.modules; "
            "m = strata.mesh(sys.argv[2], layers=3, first_height=1e-3, farfield_size=5); "
            "numpy.savez(sys.argv[3], points=m.points, tets=m.tets, prisms=m.prisms)")
    subprocess.run([sys.executable, "-c", code, os.path.dirname(os.path.dirname(strata.__file__)),
                    SPHERE_STL, str(ref)], check=True)
    other = np.load(ref)
    assert len(here.tets) > 0
    assert np.array_equal(here.tets, other["tets"]) and np.array_equal(here.prisms, other["prisms"])
    assert np.array_equal(here.points, other["points"])


def test_strata_readers_leave_the_users_gmsh_initialised(session):
    # strata.mesh reads the STL through Gmsh; it must neither re-initialise nor finalise the
    # Gmsh the user initialised from Python.
    gmsh.model.add("mine")
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    strata.mesh(SPHERE_STL, layers=2, first_height=1e-3, farfield_size=5)
    assert "mine" in gmsh.model.list()
    gmsh.model.setCurrent("mine")
    assert len(gmsh.model.getEntities(3)) == 1


def test_without_initialize_is_an_input_error():
    with pytest.raises(strata.InputError, match="initiali"):
        strata.gmsh.mesh_current_model(layers=2, first_height=0.01)


def test_failure_leaves_the_model_as_it_was(session):
    sphere_surface()
    before = count(2)
    with pytest.raises(strata.InputError):
        strata.gmsh.mesh_current_model(layers=2, first_height=-0.01)  # a negative first height
    assert count(2) == before and count(3) == {}


def test_timeout_leaves_the_model_as_it_was(session):
    # The same limit as strata.mesh(timeout=): 0 s has passed at the first check; the model
    # keeps its surface and gets no volume. A bad limit is refused before anything runs.
    sphere_surface()
    before = count(2)
    with pytest.raises(TimeoutError, match=r"stopped by timeout=0 s in stage \w+"):
        strata.gmsh.mesh_current_model(layers=2, first_height=0.01, farfield_size=5, timeout=0)
    assert count(2) == before and count(3) == {}
    with pytest.raises(ValueError, match="timeout="):
        strata.gmsh.mesh_current_model(layers=2, first_height=0.01, timeout=-1)
    report = strata.gmsh.mesh_current_model(layers=2, first_height=0.01, farfield_size=5, timeout=600)
    assert count(3).get(PRISM, 0) == 2 * before[TRIANGLE] and sum(report["cells"].values()) > 0
