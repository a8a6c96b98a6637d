"""The Gmsh-window action, headless: ONELAB parameters set as a user would in the panel, the
button's action called without a display, the hybrid mesh then in the open model and the
report in Gmsh's message log."""

import os
import shutil
import subprocess
import sys

import gmsh
import pytest

import strata
from strata import gmsh_gui
from conftest import TEST_DATA

PRISM, TET = 6, 4


@pytest.fixture
def session():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.logger.start()
    yield
    gmsh.logger.stop()
    gmsh.finalize()


def elements(dim):
    types, tags, _ = gmsh.model.mesh.getElements(dim)
    return {int(t): len(tg) for t, tg in zip(types, tags)}


def test_panel_defaults_are_the_keywords_defaults(session):
    gmsh_gui.open_model(os.path.join(TEST_DATA, "cad_unit_sphere.geo"))
    gmsh_gui.define_parameters()
    options = gmsh_gui.options_from_parameters()
    defaults = {k["name"]: k["default"] for k in strata.keywords("gmsh")}
    for keyword, value in options.items():
        if keyword != "growth":  # the ratio its 0 stands for
            assert value == defaults[keyword], keyword
    assert defaults["growth"] == 0 and options["growth"] == 1.2
    assert options["first_height"] == 0  # chosen from the walls
    assert gmsh.onelab.getString(gmsh_gui.BUTTON)[1] == gmsh_gui.ACTION_NAME


def test_one_click_with_the_panels_defaults_gives_a_mesh_checkmesh_passes(session):
    # The unit sphere as the window opens it, the button pressed with nothing changed.
    gmsh_gui.open_model(os.path.join(TEST_DATA, "cad_unit_sphere.geo"))
    gmsh_gui.define_parameters()
    report = gmsh_gui.run_action()
    chosen = report["automatic_first_height"]
    assert chosen["walls_length"] == pytest.approx(2.0, rel=0.02)
    # 20 layers at 1.2 reach 2 % of the sphere's diameter
    assert chosen["first_height"] == pytest.approx(0.04 * 0.2 / (1.2 ** 20 - 1), rel=0.02)
    assert report["layers"] == 20 and report["first_height"] == pytest.approx(chosen["first_height"])
    assert report["thickness"] == pytest.approx(0.04, rel=0.02)
    assert elements(3).get(PRISM, 0) > 0 and report["quality"]["openfoam"]["check_mesh_ok"]
    assert all(c["full_nodes"] == c["nodes"] for c in report["patches"])
    log = "\n".join(gmsh.logger.get())
    assert "Strata: first height" in log and "none asked" in log, log


def test_action_meshes_the_open_model_with_the_panel_values(session):
    gmsh_gui.open_model(os.path.join(TEST_DATA, "cad_unit_sphere.geo"))
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.4)
    gmsh_gui.define_parameters()
    # the user edits the panel
    gmsh.onelab.setNumber("Strata/1Layers", [3])
    gmsh.onelab.setNumber("Strata/2First height", [0.01])
    gmsh.onelab.setNumber("Strata/4Farfield/2Size (x body)", [4])
    gmsh.onelab.setString("Strata/4Farfield/1Shape", ["box"])
    stages = []
    report = gmsh_gui.run_action(progress=lambda s, f: stages.append(s))
    cells = elements(3)
    triangles = report["patches"]
    assert cells.get(PRISM, 0) > 0 and cells.get(TET, 0) > 0
    assert report["layers"] == 3 and abs(report["first_height"] - 0.01) < 1e-12
    assert "tetrahedra" in stages and triangles
    log = "\n".join(gmsh.logger.get())
    assert "Strata:" in log and "coverage" in log and "min scaled Jacobian" in log
    assert "OpenFOAM checkMesh would say Mesh OK" in log, log
    assert "coverage" in gmsh.onelab.getString(gmsh_gui.RESULT)[0]
    gmsh_gui.show_volume()  # headless too: only options


def test_action_reports_errors_in_the_console(session):
    gmsh_gui.open_model(os.path.join(TEST_DATA, "cad_unit_sphere.geo"))
    gmsh_gui.define_parameters()
    gmsh.onelab.setNumber("Strata/1Layers", [0])
    with pytest.raises(strata.InputError, match="layers"):
        gmsh_gui.run_action()
    assert "failed" in gmsh.onelab.getString(gmsh_gui.RESULT)[0]
    assert elements(3) == {}


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="needs xvfb-run (Debian's xvfb)")
def test_real_window_under_xvfb(tmp_path):
    # The real FLTK window on a virtual display: the button pressed once (--run), the graphics
    # saved by Gmsh itself (--screenshot), the process closing cleanly.
    png = tmp_path / "window.png"
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(strata.__file__)))
    run = subprocess.run(
        ["xvfb-run", "-a", "-s", "-screen 0 1280x900x24", sys.executable, "-m", "strata.gmsh_gui",
         os.path.join(TEST_DATA, "cad_unit_sphere.geo"), "--run", "--screenshot", str(png)],
        env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    assert "Strata: time" in run.stdout and "coverage" in run.stdout
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 5000  # a drawn mesh, not a blank area


def test_a_geo_script_that_runs_commands_is_not_opened(tmp_path):
    evil = tmp_path / "evil.geo"
    evil.write_text('Point(1) = {0, 0, 0};\nSystemCall "touch %s";\n' % (tmp_path / "pwned"))
    assert gmsh_gui.main([str(evil)]) == 1
    assert not (tmp_path / "pwned").exists()
