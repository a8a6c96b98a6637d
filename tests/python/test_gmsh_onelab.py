"""Strata as a ONELAB solver of stock Gmsh (strata.gmsh_onelab, scripts/strata-gmsh-onelab).

Gmsh is the ONELAB server in every test here, never a stand-in: Python's gmsh module running
the client with gmsh.onelab.run (libgmsh's own server code, headless), and the `gmsh` program's
window under Xvfb, clicked with xdotool as a user would. Each runs in a process of its own with a
temporary HOME, where Gmsh reads the registration and puts its socket."""

import contextlib
import json
import os
import shutil
import subprocess
import sys
import time

import pytest

from strata import gmsh_gui, gmsh_onelab, onelab
from conftest import BUILD_PYTHON, ROOT, TEST_DATA

CLIENT = os.path.join(ROOT, "scripts", "strata-gmsh-onelab")
PRISM, TET = 6, 4

# A headless Gmsh holding MODEL that runs the client once per action (gmsh.onelab.run, as
# Gmsh's Run button does: "NAME/Action" set, then the client launched), after setting the
# ONELAB parameters SET; it prints what the database, the log and the models hold.
SERVER = r"""
import json, sys, gmsh
model, client, actions, settings = sys.argv[1], sys.argv[2], json.loads(sys.argv[3]), json.loads(sys.argv[4])
gmsh.initialize(readConfigFiles=False)
gmsh.option.setNumber("General.Terminal", 0)
gmsh.option.setNumber("General.AbortOnError", 0)  # as in the gmsh program (the API raises on errors)
gmsh.logger.start()
gmsh.open(model)
for name, value in settings.get("options", {}).items():  # as a user sets them in the window
    gmsh.option.setNumber(name, value)
out = {"after": {}, "options": {}}
for action in actions:
    for name, value in settings.get(action, {}).items():
        (gmsh.onelab.setString if isinstance(value, str) else gmsh.onelab.setNumber)(name, [value])
    gmsh.onelab.setString("Strata/Action", [action])
    gmsh.onelab.run("Strata", client)
    out["after"][action] = json.loads(gmsh.onelab.get(), strict=False)["onelab"]["parameters"]  # raw line breaks
    out["options"][action] = {o: gmsh.option.getNumber(o) for o in ("Solver.AutoMesh", "Mesh.Clip")}
out["log"] = gmsh.logger.get()
out["models"] = {}
for m in gmsh.model.list():
    gmsh.model.setCurrent(m)
    cells = {str(t): len(e) for t, e in zip(*gmsh.model.mesh.getElements(3)[:2])}
    faces = {gmsh.model.getPhysicalName(2, g): sum(len(gmsh.model.mesh.getElements(2, s)[1][0])
             for s in gmsh.model.getEntitiesForPhysicalGroup(2, g)) for _, g in gmsh.model.getPhysicalGroups(2)}
    out["models"][m] = {"cells": cells, "faces": faces}
print(json.dumps(out))
gmsh.finalize()
"""


def _env(home, **more):
    env = dict(os.environ, HOME=str(home), PYTHONPATH=BUILD_PYTHON, **more)
    env.pop("GMSH_HOME", None)
    return env


def run_server(tmp_path, actions, settings=None):
    model = tmp_path / "cad_unit_sphere.geo"
    shutil.copy(os.path.join(TEST_DATA, "cad_unit_sphere.geo"), model)
    run = subprocess.run([sys.executable, "-c", SERVER, str(model), CLIENT, json.dumps(actions),
                          json.dumps(settings or {})], env=_env(tmp_path), capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    return json.loads(run.stdout.splitlines()[-1])


def values(parameters):
    return {p["name"]: p["values"][0] for p in parameters if p["values"]}


def test_a_parameter_goes_over_the_socket_as_onelab_h_writes_it():
    # onelab::string::toChar() of Gmsh 4.8 for this parameter, byte for byte
    p = {"type": "string", "name": "Strata/4Farfield/1Shape", "values": ["box"], "choices": ["sphere", "box"]}
    body = onelab.encode(p)
    assert body == b"1.3\0string\0Strata/4Farfield/1Shape\0\0\x0031\x001\x000\x000\x000\x001\0box\0generic\x002\0sphere\0box\0"
    assert onelab.decode(body)["values"] == ["box"] and onelab.decode(body)["choices"] == ["sphere", "box"]
    n = {"type": "number", "name": "Strata/1Layers", "values": [20], "min": 1, "max": 200, "step": 1,
         "attributes": {"Help": "number of layers"}, "readOnly": True}
    back = onelab.decode(onelab.encode(n))
    assert (back["values"], back["min"], back["max"], back["step"]) == ([20.0], 1.0, 200.0, 1.0)
    assert back["attributes"] == {"Help": "number of layers"} and back["readOnly"] and back["visible"]
    with pytest.raises(ValueError, match="neither number nor string"):
        onelab.encode({"type": "region", "name": "x", "values": []})


def test_gmsh_runs_strata_and_merges_the_hybrid_mesh_it_asked_for(tmp_path):
    settings = {"options": {"Mesh.MeshSizeMax": 0.15},
                "compute": {"Strata/1Layers": 3, "Strata/2First height": 0.01, "Strata/4Farfield/1Shape": "box"}}
    out = run_server(tmp_path, ["initialize", "check", "compute", "check"], settings)
    # initialize: the panel, with strata-gmsh's parameters and defaults
    defined = values(out["after"]["initialize"])
    panel = [name for name, _ in gmsh_gui.PANEL]
    assert set(panel) <= set(defined) and defined["Strata/1Layers"] == 20
    assert defined["Strata/4Farfield/1Shape"] == "sphere" and defined["Strata/9Result"] == ""
    # compute: the panel's values as the user left them, a hybrid mesh merged into a model of its own
    after = values(out["after"]["compute"])
    assert after["Strata/1Layers"] == 3 and after["Strata/4Farfield/1Shape"] == "box"
    assert "coverage, 3 layers asked" in after["Strata/9Result"]
    merged = out["models"]["cad_unit_sphere_strata"]
    assert merged["cells"][str(TET)] > 0 and merged["cells"][str(PRISM)] == 3 * merged["faces"]["surface_1"]
    assert set(merged["faces"]) == {"surface_1", "farfield"}
    assert merged["faces"]["surface_1"] > 1000  # the window's size (320 triangles at Gmsh's default)
    assert out["models"]["cad_unit_sphere"]["cells"] == {}  # Gmsh's own 3D meshing stayed off
    assert out["options"]["compute"] == {"Solver.AutoMesh": 0.0, "Mesh.Clip": 1.0}, out["options"]
    assert (tmp_path / "cad_unit_sphere_strata.msh").stat().st_size > 0
    log = "\n".join(out["log"])
    assert "Strata - coverage, 3 layers asked" in log and f"Strata - wrote {tmp_path}/cad_unit_sphere_strata.msh" in log
    assert "OpenFOAM checkMesh would say Mesh OK" in log
    # a later check keeps the user's values
    assert values(out["after"]["check"])["Strata/1Layers"] == 3


def test_strata_errors_go_to_gmshs_console_and_gmsh_carries_on(tmp_path):
    out = run_server(tmp_path, ["check", "compute"], {"compute": {"Strata/1Layers": 0}})
    errors = [line for line in out["log"] if line.startswith("Error") and "Strata - " in line]
    assert errors and "layers" in errors[0], out["log"]
    assert values(out["after"]["compute"])["Strata/9Result"].startswith("failed:")
    assert list(out["models"]) == ["cad_unit_sphere"] and not (tmp_path / "cad_unit_sphere_strata.msh").exists()


def gmsh_solvers(home):
    """Solver.Name/Executable0..9 as Gmsh reads them at start-up from HOME."""
    code = ("import gmsh, json; gmsh.initialize(); print(json.dumps([[gmsh.option.getString(f'Solver.{k}{i}') "
            "for k in ('Name', 'Executable')] for i in range(10)])); gmsh.finalize()")
    run = subprocess.run([sys.executable, "-c", code], env=_env(home), capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and "Error" not in run.stdout, run.stdout + run.stderr
    return [tuple(s) for s in json.loads(run.stdout.splitlines()[-1])]


def test_registration_adds_strata_to_gmshs_solvers_and_keeps_the_others(tmp_path):
    (tmp_path / ".gmshrc").write_text('Solver.Name0 = "GetDP";\nSolver.Name1 = "Foo";\nSolver.Executable1 = "/bin/foo";\n')
    (tmp_path / ".gmsh-options").write_text("General.Terminal = 1;")  # the user's own, no final newline
    gmsh_onelab.register(CLIENT, str(tmp_path))
    gmsh_onelab.register(CLIENT, str(tmp_path))  # again: one registration
    options = (tmp_path / ".gmsh-options").read_text()
    assert options.startswith("General.Terminal = 1;\n") and options.count(gmsh_onelab.BEGIN) == 1
    assert gmsh_solvers(tmp_path)[:3] == [("GetDP", ""), ("Foo", "/bin/foo"), ("Strata", CLIENT)]
    # where Gmsh's session remembers Strata (it saves its solvers at exit), it stays: no duplicate
    (tmp_path / ".gmshrc").write_text('Solver.Name1 = "Foo";\nSolver.Name3 = "Strata";\nSolver.Executable3 = "/old";\n')
    solvers = gmsh_solvers(tmp_path)
    assert solvers[1] == ("Foo", "") and solvers[3] == ("Strata", CLIENT) and [s[0] for s in solvers].count("Strata") == 1
    assert gmsh_onelab.unregister(str(tmp_path)) == [str(tmp_path / ".gmsh-options"), str(tmp_path / ".gmshrc")]
    assert (tmp_path / ".gmsh-options").read_text() == "General.Terminal = 1;\n"
    assert [s[0] for s in gmsh_solvers(tmp_path)] == ["GetDP", "Foo"] + [""] * 8
    assert gmsh_onelab.unregister(str(tmp_path)) == []


@contextlib.contextmanager
def virtual_display():
    """An Xvfb display of its own (its number from -displayfd): ':N'."""
    read, write = os.pipe()
    xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0", "1280x900x24", "-nolisten", "tcp"],
                            pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write)
    try:
        number = os.read(read, 32).decode().strip()
        assert number.isdigit(), "Xvfb did not start"
        yield ":" + number
    finally:
        os.close(read)
        xvfb.terminate()
        xvfb.wait(10)


def wait_for(condition, what, timeout, screenshot):
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"{what}: not after {timeout} s; the window: {screenshot()}")
        time.sleep(0.2)


@pytest.mark.skipif(not all(shutil.which(p) for p in ("Xvfb", "xdotool", "gmsh")),
                    reason="needs Debian's xvfb, xdotool and gmsh")
def test_stock_gmsh_window_lists_strata_and_runs_it(tmp_path):
    home = tmp_path / "home"
    home.mkdir()
    (home / ".gmsh-options").write_text("General.Terminal = 1;\n")  # Gmsh's console on its stdout too
    gmsh_onelab.register(CLIENT, str(home))
    model = tmp_path / "cad_unit_sphere.geo"
    shutil.copy(os.path.join(TEST_DATA, "cad_unit_sphere.geo"), model)
    log = tmp_path / "gmsh.log"
    with virtual_display() as display, open(log, "w") as out:
        env = _env(home, DISPLAY=display)
        window = subprocess.Popen(["gmsh", str(model)], cwd=tmp_path, env=env, stdout=out, stderr=subprocess.STDOUT)
        try:
            click_through_the_window(env, log, tmp_path, window)
        finally:
            if window.poll() is None:
                window.terminate()
            window.wait(20)
    check_the_window_s_results(tmp_path, home, log.read_text())


def click_through_the_window(env, log, tmp_path, window):
    def xdotool(*args):
        return subprocess.run(["xdotool", *args], env=env, capture_output=True, text=True, timeout=60).stdout

    def screenshot():
        try:
            from PIL import ImageGrab
            ImageGrab.grab(xdisplay=env["DISPLAY"]).save(tmp_path / "window.png")
            return tmp_path / "window.png"
        except Exception as e:  # the failure is reported either way
            return f"no screenshot ({e})"

    def ran(times):
        return lambda: log.read_text().count("Done running 'Strata'") >= times

    geometry = dict(line.split("=") for line in xdotool("search", "--sync", "--onlyvisible", "--name", "^Gmsh",
                                                          "getwindowgeometry", "--shell").split())
    x, y, h = int(geometry["X"]), int(geometry["Y"]), int(geometry["HEIGHT"])
    # Gmsh 4.8's tree at its default font: rows 16 pixels apart, from Modules at y + 35
    xdotool("mousemove", "--sync", str(x + 34), str(y + 83), "click", "1")    # Modules > Solver: open
    xdotool("mousemove", "--sync", str(x + 77), str(y + 115), "click", "1")   # > Strata: Gmsh runs the client
    wait_for(ran(2), "Strata's client run by Gmsh (initialize, check)", 60, screenshot)
    xdotool("mousemove", "--sync", str(x + 120), str(y + h - 39), "click", "1")  # the panel's Run button
    wait_for(ran(3), "Strata's compute", 120, screenshot)
    wait_for(lambda: (tmp_path / "cad_unit_sphere.db").exists(), "Gmsh's ONELAB database", 30, screenshot)
    xdotool("mousemove", "--sync", str(x + 400), str(y + 300), "key", "ctrl+q")  # quit: Gmsh saves its session
    wait_for(lambda: window.poll() is not None, "Gmsh closing", 30, screenshot)


def read_database(path):
    """The parameters in a ONELAB database Gmsh saved (onelab::parameter::toFile)."""
    data, params = path.read_bytes(), {}
    i = data.index(b"\n") + 1
    while i < len(data):
        space = data.index(b" ", i)
        size = int(data[i:space])
        p = onelab.decode(data[space + 1:space + 1 + size])
        params[p["name"]] = p
        i = space + 1 + size + 1
    return params


def check_the_window_s_results(tmp_path, home, log):
    assert "Info    : Strata - coverage, 20 layers asked" in log, log[-3000:]
    assert f"Strata - wrote {tmp_path}/cad_unit_sphere_strata.msh" in log
    assert f"Reading '{tmp_path}/cad_unit_sphere_strata.msh'" in log  # merged into the window
    database = read_database(tmp_path / "cad_unit_sphere.db")  # saved by Gmsh after the run
    assert database["Strata/1Layers"]["values"] == [20.0] and "Strata" in database["Strata/1Layers"]["clients"]
    assert "coverage, 20 layers asked" in database["Strata/9Result"]["values"][0]
    assert database["Strata/Action"]["values"] == ["compute"]
    import gmsh
    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(tmp_path / "cad_unit_sphere_strata.msh"))
        types, tags, _ = gmsh.model.mesh.getElements(3)
        cells = {int(t): len(e) for t, e in zip(types, tags)}
        groups = {gmsh.model.getPhysicalName(2, g): g for _, g in gmsh.model.getPhysicalGroups(2)}
        wall_triangles = sum(len(gmsh.model.mesh.getElements(2, s)[1][0])
                             for s in gmsh.model.getEntitiesForPhysicalGroup(2, groups["surface_1"]))
    finally:
        gmsh.finalize()
    assert cells[TET] > 0 and cells[PRISM] == 20 * wall_triangles  # every wall triangle, 20 layers
    session = (home / ".gmshrc").read_text()  # Gmsh remembers Strata among its solvers ...
    assert 'Solver.Name1 = "Strata";' in session
    gmsh_onelab.unregister(str(home))  # ... until it is unregistered
    assert "Strata" not in (home / ".gmshrc").read_text() and "Strata" not in (home / ".gmsh-options").read_text()
