"""strata.surface / layers / mesh: keywords from the Params structs, NumPy views, the report,
errors as Python exceptions, progress and Ctrl-C."""

import inspect
import json
import math
import os
import signal

import numpy as np
import pytest

import strata
from conftest import BUILD_PYTHON, EXAMPLES, SPHERE_STL, TEST_DATA

SMALL = dict(layers=4, first_height=1e-3, growth=1.2)


def test_imports_from_the_build_tree():
    # conftest puts BUILD_DIR/python first: the package under test is the one just built
    assert os.path.realpath(os.path.dirname(strata.__file__)) == os.path.realpath(os.path.join(BUILD_PYTHON, "strata"))


def test_keywords_and_defaults_come_from_the_params_structs():
    sig = inspect.signature(strata.mesh)
    # DistributionParams{}: 20 layers, growth 0 (= 1.2); TetFillParams{}: radius_edge 1.5, growth 0.3;
    # FarfieldParams{}: sphere, 20 diagonals. Keyword-only, as the C++ names them.
    assert sig.parameters["layers"].default == 20
    assert sig.parameters["growth"].default == 0.0
    assert sig.parameters["radius_edge"].default == 1.5
    assert sig.parameters["tet_growth"].default == 0.3
    assert sig.parameters["farfield"].default == "sphere"
    assert sig.parameters["farfield_size"].default == 20.0
    assert sig.parameters["layers"].kind is inspect.Parameter.KEYWORD_ONLY
    params = {k["name"]: k["param"] for k in strata.keywords()}
    assert params["first_height"] == "DistributionParams::first_height"
    assert params["max_dihedral"] == "TetFillParams::max_dihedral"
    # surface() takes no layer keywords, layers() no tetrahedra keywords
    assert "layers" not in inspect.signature(strata.surface).parameters
    assert "radius_edge" not in inspect.signature(strata.layers).parameters
    assert "radius_edge" in strata.mesh.__doc__


def test_unknown_keyword_is_a_type_error():
    with pytest.raises(TypeError):
        strata.mesh(SPHERE_STL, layer=4)
    with pytest.raises(TypeError, match="layers"):
        strata.mesh(SPHERE_STL, layers="four")


def test_mesh_sphere_arrays_and_report(tmp_path):
    stages = []
    out = tmp_path / "sphere.msh"
    m = strata.mesh(SPHERE_STL, output=str(out), progress=lambda s, f: stages.append((s, f)), **SMALL)
    assert out.exists() and (tmp_path / "sphere.msh.report.json").exists()
    pts = m.points
    assert pts.shape[1] == 3 and pts.dtype == np.float64 and not pts.flags.writeable
    assert m.prisms.shape[1] == 6 and m.tets.shape[1] == 4 and len(m.prisms) > 0 and len(m.tets) > 0
    assert m.cells["prism"] is not None and m.cells["tetrahedron"].shape == m.tets.shape
    for block in (m.tets, m.prisms):
        assert block.min() >= 0 and block.max() < len(pts)
    # the views share the mesh's memory and keep it alive
    base = m.points
    del m
    assert np.isfinite(base).all()
    m = strata.mesh(SPHERE_STL, **SMALL)
    # first layer: prism bottom-to-top edge = first height (1e-3) to within the smoothing
    p = m.prisms[:, [0, 3]]
    h = np.linalg.norm(m.points[p[:, 1]] - m.points[p[:, 0]], axis=1)
    assert 0.5e-3 < np.median(h) < 2e-3
    r = m.report
    assert r["cells"]["prism"] == len(m.prisms) and r["cells"]["tetrahedron"] == len(m.tets)
    q = r["quality"]
    assert 0 < q["min_scaled_jacobian"]["all"] <= q["min_scaled_jacobian"]["prism"] <= 1
    assert abs(q["cell_volume"] - q["boundary_volume"]) < 1e-6 * q["boundary_volume"]
    # OpenFOAM checkMesh's figures (tests/openfoam/check_figures.sh compares them with checkMesh)
    foam = q["openfoam"]
    assert 0 < foam["max_non_orthogonality_deg"] < 70 and 0 < foam["max_skewness"] < 4, foam
    assert foam["check_mesh_ok"] and foam["failures"] == [] and foam["negative_pyramids"] == 0, foam
    assert r["layers"] == 4 and r["patches"], r["patches"]
    for c in r["patches"]:
        assert c["nodes"] > 0 and 0 <= c["full_nodes"] <= c["nodes"]
    assert set(r["times"]) >= {"surface", "layers", "pyramids", "tetrahedra", "validation", "write"}
    # the tetrahedra improved after TetGen: never a worse worst, fewer below the bound
    ti = r["tet_improve"]
    assert ti["below"] == 0.2 and ti["min_after"] >= ti["min_before"] > 0, ti
    assert ti["below_after"] <= ti["below_before"], ti
    assert q["min_scaled_jacobian"]["tetrahedron"] <= ti["min_after"] + 1e-12, ti
    # patches: the sphere's wall and the generated farfield, with their boundary faces
    assert "farfield" in m.patch_names
    assert m.patch_kinds[m.patch_names.index("farfield")] == "farfield"
    ff = m.faces("farfield")["triangle"]
    assert len(ff) > 0 and ff.shape[1] == 3
    assert len(m.face_patch) == len(m.face_offsets) - 1
    assert sum(len(a) for a in m.faces().values()) == len(m.face_patch)
    # progress: every stage, fractions in [0, 1]
    names = [s for s, _ in stages]
    for stage in ("surface", "layers", "pyramids", "tetrahedra", "validation", "writing"):
        assert stage in names
    assert all(0.0 <= f <= 1.0 for _, f in stages)


def _same(a, b, at="report"):
    """a (the report dict) and b (its JSON) hold the same tree: the same keys in the same order,
    the same values (a number JSON cannot write, null)."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), (at, list(a), b)
        for k in a:
            _same(a[k], b[k], at + "/" + k)
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), at
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, "%s/%d" % (at, i))
    elif isinstance(a, float) and not math.isfinite(a):
        assert b is None, at
    else:
        assert a == b and isinstance(a, bool) == isinstance(b, bool), (at, a, b)


def test_the_report_dict_and_the_json_are_one_tree(tmp_path):
    # One builder (frontend/report.h) makes the report: the dict and OUT.report.json hold the
    # same keys and values, whatever a new field is; only the time of writing the files (known
    # after the JSON is written) is the dict's alone.
    for run, name in ((strata.mesh, "m.msh"), (strata.layers, "l.msh")):
        out = tmp_path / name
        r = run(SPHERE_STL, output=str(out), **SMALL).report
        with open(str(out) + ".report.json") as f:
            written = json.load(f)
        assert r["times"].pop("write") >= 0
        _same(r, written)
        assert {"fan_plane_nodes", "unsmoothed_nodes", "layer_stats", "surface"} <= set(written)
        p = written["provenance"]
        assert p["inputs"] == [SPHERE_STL] and p["options"]["layers"] == 4 and "sweeps" not in p["options"]
        assert p["strata_version"] and p["git_commit"]


def test_coverage_lists_the_short_nodes_with_their_positions():
    # Two spheres whose gap is a tenth of the layers: the columns facing it get fewer layers
    # (proximity), each listed with where and why, as in OUT.report.json.
    geo = os.path.join(os.path.dirname(SPHERE_STL), "two_spheres_narrow_gap.geo")
    lm = strata.layers(geo, size=0.05, layers=30, first_height=1e-4, growth=1.2)
    cov = lm.report
    short = cov["short_nodes"]
    assert short, "no short node beside the gap"
    assert len(short) == sum(sum(c["short"].values()) for c in cov["patches"])
    assert {n["reason"] for n in short} == {"proximity"}
    for n in short:
        assert len(n["position"]) == 3 and 0.0 < n["share"] < 1.0 and 0 <= n["layers"] <= 30
        # on the wall: a point of one of the spheres (radius 0.5, centres 0 and 1.0118 on x)
        d = min(np.linalg.norm(np.subtract(n["position"], c)) for c in ((0, 0, 0), (1.0118, 0, 0)))
        assert abs(d - 0.5) < 0.01, n
    assert cov["no_fan_nodes"] == []
    # The whole wall: short for proximity alone, so every layer wherever no proximity limit binds.
    w = cov["coverage"]
    assert w["all_layers_share"] < 1.0 and w["unbound_nodes"] < w["nodes"]
    assert w["unbound_all_layers_share"] == 1.0
    assert w["own_reason_nodes"] == len(short) and w["neighbour_nodes"] == 0


def test_the_whole_walls_coverage_agrees_with_its_patches_and_short_nodes():
    # The ONERA M6 from CAD in 11 patches, layers too thick for its tip: nodes short for their
    # own reason and for their neighbours, nodes on two patches counted once for the wall.
    report = strata.layers(os.path.join(EXAMPLES, "onera_m6_sharp_te.stp"), size=60, layers=10, first_height=0.5,
                           growth=1.2).report
    w, patches, short = report["coverage"], report["patches"], report["short_nodes"]
    assert len(patches) > 5
    assert w["faces"] == sum(p["faces"] for p in patches)
    for key in ("nodes", "full_nodes", "all_layers", "unbound_nodes", "unbound_all_layers"):
        assert max(p[key] for p in patches) <= w[key] <= sum(p[key] for p in patches), key
    assert w["nodes"] < sum(p["nodes"] for p in patches)  # a node on two patches once
    assert w["min_layers"] == min(p["min_layers"] for p in patches)
    assert w["min_share"] == min(p["min_share"] for p in patches)
    # Each short node once, with its reason; the rest full.
    assert len(short) == w["nodes"] - w["full_nodes"] > 0
    for reason, n in w["short"].items():
        assert n == sum(1 for s in short if s["reason"] == reason), reason
    assert w["all_layers"] == w["nodes"] - sum(1 for s in short if s["layers"] < report["layers"])
    # The mean share: the short nodes' own, the others about 1 (smoothing moves them a little).
    full = w["full_nodes"]
    assert w["mean_share"] == pytest.approx((sum(s["share"] for s in short) + full) / w["nodes"], abs=0.02)
    assert w["neighbour_nodes"] == w["short"]["neighbours"] > 0
    assert w["own_reason_nodes"] + w["neighbour_nodes"] == len(short)
    assert w["all_layers_share"] == pytest.approx(w["all_layers"] / w["nodes"])
    assert w["unbound_all_layers_share"] == pytest.approx(w["unbound_all_layers"] / w["unbound_nodes"])


def test_surface_and_layers(tmp_path):
    s = strata.surface(SPHERE_STL)
    assert s.points.shape == (s.report["nodes"], 3)
    assert s.report["triangles"] == len(s.faces()["triangle"]) > 0
    assert s.patch_kinds == ["wall"]
    lm = strata.layers(SPHERE_STL, **SMALL)
    assert len(lm.prisms) == 4 * s.report["triangles"]  # every column full on a sphere
    assert len(lm.tets) == 0 and lm.report["layers"] == 4
    assert len(lm.report["layer_stats"]) == 4


def test_patches_keyword(tmp_path):
    s = strata.surface(os.path.join(TEST_DATA, "cad_box_groups.geo"))
    name = s.patch_names[0]
    s2 = strata.surface(os.path.join(TEST_DATA, "cad_box_groups.geo"), patches={name: "symmetry"})
    assert s2.patch_kinds[s2.patch_names.index(name)] == "symmetry"
    with pytest.raises(strata.InputError, match="nosuch"):
        strata.surface(os.path.join(TEST_DATA, "cad_box_groups.geo"), patches={"nosuch": "wall"})


def test_patches_keyword_renames_too():
    box = os.path.join(TEST_DATA, "cad_box_groups.geo")
    first, second = strata.surface(box).patch_names[:2]
    s = strata.surface(box, patches={first: "wall:sides", second: "wall:sides"})
    assert s.patch_names[0] == "sides" and first not in s.patch_names and second not in s.patch_names
    with pytest.raises(strata.InputError, match=r"patches .*'a b'.*must start with a letter"):
        strata.surface(box, patches={first: "wall:a b"})


def test_cad_walls_are_meshed_finer_for_the_first_layers_aspect_ratio():
    # The unit box under a first layer of 5e-5: its prisms would be near 1900 in OpenFOAM's
    # aspect ratio (checkMesh fails above 1000); layers() and mesh() mesh its walls finer,
    # surface() (no layers) and max_aspect_ratio=0 leave them.
    box = os.path.join(TEST_DATA, "cad_box_groups.geo")
    r = strata.layers(box, layers=2, first_height=5e-5).report
    walls = r["surface"]["walls"]
    assert walls["surfaces"] == 6 and walls["worst_before"] > 1000 and walls["worst_after"] <= 1000
    assert walls["size"] == pytest.approx(0.035)
    assert r["surface"]["triangles"] > 10000
    off = strata.layers(box, layers=2, first_height=5e-5, max_aspect_ratio=0).report["surface"]
    assert off["walls"]["surfaces"] == 0 and off["triangles"] < r["surface"]["triangles"] / 5
    assert strata.surface(box).report["walls"]["worst_before"] == 0
    with pytest.raises(strata.InputError, match=r"max_aspect_ratio = 5"):
        strata.layers(box, layers=2, first_height=5e-5, max_aspect_ratio=5)


def test_loose_cad_faces_are_sewn_and_the_report_says_so():
    # Six faces of a box that miss each other by up to 1e-7 (tests/data/cad_box_loose_faces.py):
    # sewn into one closed solid; by 3e-5, wider than sewing goes unasked: mesh() refuses the open
    # surface naming the sew_tolerance keyword and its value, which then sews it.
    r = strata.surface(os.path.join(TEST_DATA, "cad_box_loose_faces_1e-7.brep")).report
    assert r["sewn"]["faces"] == 6 and r["sewn"]["free_edges_before"] == 24
    assert r["sewn"]["free_edges_after"] == 0 and r["sewn"]["solids"] == 1 and not r["sewn"]["rejected"]
    assert r["closed_components"] == 1
    wide = os.path.join(TEST_DATA, "cad_box_loose_faces_3e-5.brep")
    with pytest.raises(strata.InputError, match=r"sew_tolerance 6.7e-05 sews them") as e:
        strata.mesh(wide, layers=2, first_height=0.01)
    assert "--" not in str(e.value).split("better for this CAD model")[1]
    sewn = strata.surface(wide, sew_tolerance=6.7e-05).report["sewn"]
    assert sewn["free_edges_after"] == 0 and sewn["solids"] == 1
    assert strata.surface(SPHERE_STL).report["sewn"]["faces"] == 0


def test_holes_are_closed_on_request():
    cube = os.path.join(TEST_DATA, "cli_cube_missing_face.stl")
    with pytest.raises(strata.InputError, match=r"fill_holes 3 closes every open loop"):
        strata.mesh(cube, layers=2, first_height=0.01)
    r = strata.surface(cube, fill_holes=3).report
    assert r["holes"]["filled"] == 1 and r["holes"]["triangles"] == 1 and r["holes"]["left"] == 0
    assert r["closed_components"] == 1


def test_a_surface_nothing_repairs_is_wrapped_on_request():
    # examples/data/dirty_body.stl (fins touching the body along a line, a canopy inside it, a
    # hole, a facet twice, a flap): refused, naming the wrap keyword; wrap=None is off, 0 the
    # default size, a number the narrowest gap the wrap follows.
    dirty = os.path.join(EXAMPLES, "dirty_body.stl")
    with pytest.raises(strata.TopologyError, match=r"wrap replaces it"):
        strata.surface(dirty)
    s = strata.surface(dirty, wrap=0)
    w = s.report["wrap"]
    assert s.report["wrapped"] and w["input_faces"] == 3135 and w["faces"] == s.report["triangles"]
    assert w["alpha"] == pytest.approx(0.0113525, rel=1e-5) and w["offset"] == pytest.approx(w["alpha"] / 30)
    assert 0 < w["wrap_to_input"] < w["alpha"] and w["hausdorff"] == max(w["wrap_to_input"], w["input_to_wrap"])
    assert s.report["closed_components"] == 1 and s.report["open_loops"] == 0
    assert sorted(s.patch_names) == ["body", "canopy", "fins"]
    assert strata.surface(dirty, wrap=0.02).report["wrap"]["alpha"] == 0.02
    with pytest.raises(strata.InputError, match=r"wrap=-1"):
        strata.surface(dirty, wrap=-1)


def test_a_vessels_openings_are_capped_each_with_a_patch_of_its_own():
    vessel = os.path.join(TEST_DATA, "vessel_three_cuts.stl")
    s = strata.surface(vessel, fill_holes=1000, caps=True, internal_flow=True, patches={"cap_2": "other:outlet"})
    assert s.patch_names == ["vessel", "cap_1", "outlet", "cap_3"]
    assert s.patch_kinds == ["wall", "other", "other", "other"]
    assert s.report["holes"]["caps"] and s.report["holes"]["filled"] == 3 and s.report["closed_components"] == 1
    with pytest.raises(strata.InputError, match=r"caps closes the loops fill_holes closes"):
        strata.surface(vessel, caps=True)


def test_a_gmsh_abort_is_an_error_and_the_session_goes_on():
    # Gmsh 4.8 throws out of its OpenMP meshing loop on a face it cannot mesh, a std::terminate
    # that ended the whole process (this interpreter, a FreeCAD session) with one line. The
    # package (as the program) has Gmsh mesh the surfaces in a child process: it is an error naming the
    # file and Gmsh's message, and the session goes on. (In a subprocess, so that a regression
    # cannot end pytest.)
    import subprocess
    import sys
    geo = os.path.join(TEST_DATA, "cli_gmsh_aborts.geo")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([BUILD_PYTHON, os.environ.get("PYTHONPATH", "")]))
    script = ("import strata\n"
              "try:\n"
              "    strata.surface(%r)\n"
              "except strata.Error as e:\n"
              "    print('error:', e)\n"
              "print('goes on:', strata.surface(%r).report['triangles'] > 0)\n" % (geo, SPHERE_STL))
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, env=env)
    assert run.returncode == 0, run.stderr
    assert "error: " + geo in run.stdout
    assert "Gmsh aborts (The 1D mesh seems not to be forming a closed loop)" in run.stdout
    assert "a Python or FreeCAD session goes on" in run.stdout
    assert "goes on: True" in run.stdout


def test_errors_carry_strata_messages_in_keyword_names(tmp_path):
    with pytest.raises(strata.InputError, match="missing.stl") as e:
        strata.mesh(str(tmp_path / "missing.stl"), **SMALL)
    assert isinstance(e.value, ValueError) and isinstance(e.value, strata.Error)
    # a library message naming a parameter shows the keyword, not the C++ name or the flag
    with pytest.raises(strata.InputError) as e:
        strata.mesh(SPHERE_STL, layers=0, first_height=1e-3)
    assert "layers" in str(e.value) and "DistributionParams" not in str(e.value) and "--" not in str(e.value)
    with pytest.raises(strata.InputError) as e:
        strata.mesh(SPHERE_STL, size=0.1, **SMALL)  # a surface-meshing option on a surface mesh
    assert "size" in str(e.value) and "--size" not in str(e.value)
    with pytest.raises(strata.InputError, match="distribution"):
        strata.mesh(SPHERE_STL, distribution="cubic", **SMALL)
    # the CLI's range for the fan angle holds for Python too (it is the library's own check)
    for bad in (200, -1, float("nan")):
        with pytest.raises(strata.InputError, match=r"fan_angle_deg = \S+: need an angle in \[0, 180\]"):
            strata.layers(SPHERE_STL, fan_angle_deg=bad, **SMALL)
        with pytest.raises(strata.InputError, match=r"sharp_edge_stop_deg = \S+: need an angle in \[0, 180\]"):
            strata.layers(SPHERE_STL, sharp_edge_stop_deg=bad, **SMALL)
    with pytest.raises(strata.TopologyError):
        strata.surface(os.path.join(TEST_DATA, "cli_nonmanifold_edge.stl"))
    with pytest.raises(strata.InputError):
        strata.mesh(SPHERE_STL, output=str(tmp_path / "x.unknown"), **SMALL)


def test_a_geo_script_that_runs_a_shell_command_needs_trust_geo(tmp_path):
    # a .geo file is a program: Gmsh would run its SystemCall with the user's rights
    geo = tmp_path / "evil.geo"
    pwned = tmp_path / "pwned"
    geo.write_text('SetFactory("OpenCASCADE");\nBox(1) = {0, 0, 0, 1, 1, 1};\n'
                   f"SystemCall \"touch '{pwned}'\";\n")
    with pytest.raises(strata.InputError, match=r"evil.geo, line 3: `SystemCall` runs a shell command.*"
                                                 r"give trust_geo=True to run it") as e:
        strata.surface(str(geo))
    assert "--" not in str(e.value) and "CadParams" not in str(e.value)
    assert not pwned.exists()
    strata.surface(str(geo), trust_geo=True)
    assert pwned.exists()


def test_a_negative_thread_count_is_refused_by_its_keyword():
    with pytest.raises(strata.InputError, match=r"threads is -1: give 0 \(all cores\) or a positive count"):
        strata.layers(SPHERE_STL, threads=-1, **SMALL)


def test_progress_exception_propagates_and_nothing_is_written(tmp_path):
    class Stop(Exception):
        pass

    def progress(stage, fraction):
        if stage == "tetrahedra":
            raise Stop(stage)

    out = tmp_path / "x.msh"
    with pytest.raises(Stop, match="tetrahedra"):
        strata.mesh(SPHERE_STL, output=str(out), progress=progress, **SMALL)
    assert not out.exists()


def test_timeout_raises_timeout_error_and_nothing_is_written(tmp_path):
    stages = []
    out = tmp_path / "x.msh"
    # A limit of 0 s has passed at the first check: the run stops there, after the user's
    # callback saw that stage, and leaves no file.
    with pytest.raises(TimeoutError, match=r"stopped by timeout=0 s in stage \w+; nothing was written"):
        strata.mesh(SPHERE_STL, output=str(out), timeout=0, progress=lambda s, f: stages.append(s), **SMALL)
    assert not out.exists() and len(stages) == 1
    # A generous limit changes nothing; a negative or non-numeric one is refused before running.
    for generous in (600, float("inf")):
        m = strata.mesh(SPHERE_STL, timeout=generous, **SMALL)
        assert len(m.prisms) > 0
    for bad in (-1, "10", True):
        with pytest.raises(ValueError, match="timeout="):
            strata.mesh(SPHERE_STL, timeout=bad, **SMALL)



def test_timeout_stops_tetgen_while_it_runs(tmp_path):
    # tet_growth=0.01 asks TetGen for 16.8 million tetrahedra (144 s on the development
    # machine): the limit must be seen while TetGen runs (the extension polls it, and kills
    # TetGen's child process), so the last report is one of TetGen's phases, short of the 0.9 of
    # the stage its run ends at, and nothing was said past it.
    reports = []
    out = tmp_path / "x.msh"
    with pytest.raises(TimeoutError, match=r"stopped by timeout=2 s in stage tetrahedra; nothing was written"):
        strata.mesh(SPHERE_STL, output=str(out), timeout=2, tet_growth=0.01,
                    progress=lambda s, f: reports.append((s, f)), **SMALL)
    stage, fraction = reports[-1]
    assert stage == "tetrahedra" and 0.0 <= fraction < 0.9, reports[-5:]
    assert not out.exists()

def test_ctrl_c_cancels_as_keyboard_interrupt(tmp_path):
    # No callback: only the progress hook's PyErr_CheckSignals can see the signal while C++
    # runs. The alarm fires 50 ms in (the run takes over a second) and its handler is Python's
    # own Ctrl-C handler, which raises KeyboardInterrupt; the stage then throws
    # strata::Cancelled and Python gets strata.Cancelled. Without the check the run would end
    # normally and a bare KeyboardInterrupt come after it, failing this test.
    out = tmp_path / "x.msh"
    previous = signal.signal(signal.SIGALRM, signal.default_int_handler)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.05)
        with pytest.raises(strata.Cancelled, match="Ctrl-C") as e:
            strata.mesh(SPHERE_STL, output=str(out), layers=10, first_height=1e-3)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert isinstance(e.value, KeyboardInterrupt)
    assert not out.exists()
    # and the next run works
    assert len(strata.mesh(SPHERE_STL, **SMALL).tets) > 0


def test_walls_are_meshed_finer_where_the_layers_step_at_a_gap():
    # Two spheres 0.0118 apart: mesh() meshes their walls again finer where the columns facing
    # the gap step, as the CLI does (step_quality, default 0.1); the report says how much.
    two = os.path.join(EXAMPLES, "two_spheres_narrow_gap.geo")
    args = dict(size=0.1, layers=12, first_height=1e-3, growth=1.2)
    m = strata.mesh(two, **args)
    steps = m.report["surface"]["steps"]
    assert steps["quality"] == 0.1 and steps["points"] > 0 and not steps["over_budget"], steps
    assert steps["faces_after"] > 2 * steps["faces_before"], steps
    assert m.report["quality"]["min_scaled_jacobian"]["pyramid"] > 0.03
    kept = strata.mesh(two, step_quality=0, **args)
    assert kept.report["surface"]["steps"]["points"] == 0
    assert kept.report["quality"]["min_scaled_jacobian"]["pyramid"] < 0.03


def test_quads_where_blossom_would_end_the_python_process():
    # The sweep's sphere with three cones in quads: Gmsh's Blossom recombination throws out of
    # Gmsh's OpenMP loop on a cone, which ended the whole process (this Python session with it).
    # Tried in a child first, the surfaces are recombined with Gmsh's simple algorithm instead,
    # and the report says why.
    spiky = os.path.join(EXAMPLES, "..", "sweep", "spiky.geo")
    s = strata.surface(spiky, fuse=True, quads=True)
    assert "Perfect Match failed" in s.report["blossom_failure"]
    assert s.report["quads"] > s.report["triangles"]
    assert strata.surface(spiky, fuse=True).report["blossom_failure"] == ""



def test_outputs_never_replace_inputs_and_a_full_disk_is_an_output_error(tmp_path):
    src = tmp_path / "in.stl"
    src.write_bytes(open(SPHERE_STL, "rb").read())
    before = src.read_bytes()
    with pytest.raises(strata.InputError, match="is the input"):
        strata.surface(str(src), output=str(src))
    mesh = tmp_path / "in.msh"
    strata.surface(str(src), output=str(mesh))
    with pytest.raises(strata.InputError, match="is the input"):
        strata.mesh(str(mesh), output=str(mesh), **SMALL)
    assert src.read_bytes() == before
    # Strata's writer errors are OSErrors too, so `except OSError` catches a full disk.
    assert issubclass(strata.OutputError, OSError) and issubclass(strata.OutputError, strata.Error)
    with pytest.raises(strata.OutputError, match="too long for the file system"):
        strata.mesh(SPHERE_STL, output=str(tmp_path / ("n" * 250 + ".msh")), **SMALL)


def test_binary_msh_output(tmp_path):
    # binary=True: the CLI's --binary, Gmsh's binary MSH, from the run and from Mesh.write; the same
    # cells read back; asked of another format, an InputError before any work, nothing written
    ascii_path, binary_path, written = tmp_path / "a.msh", tmp_path / "b.msh", tmp_path / "w.msh"
    m = strata.layers(SPHERE_STL, output=str(ascii_path), **SMALL)
    strata.layers(SPHERE_STL, output=str(binary_path), binary=True, **SMALL)
    m.write(str(written), binary=True)
    for path in (binary_path, written):
        assert path.read_bytes().startswith(b"$MeshFormat\n4.1 1 8\n")
    assert ascii_path.read_bytes().startswith(b"$MeshFormat\n4.1 0 8\n")
    import gmsh

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(binary_path))
        types, tags, _ = gmsh.model.mesh.getElements(3)
        assert sum(len(t) for ty, t in zip(types, tags) if ty == 6) == len(m.prisms) > 0
    finally:
        gmsh.finalize()
    with pytest.raises(strata.InputError, match="--binary"):
        strata.mesh(SPHERE_STL, output=str(tmp_path / "x.cgr"), binary=True, **SMALL)
    assert not (tmp_path / "x.cgr").exists()
    with pytest.raises(TypeError, match="binary"):
        strata.layers(SPHERE_STL, binary="yes", **SMALL)


def test_foam_case_is_the_shared_options_keyword(tmp_path):
    # --foam-case through the option table: layers() and mesh() take it, surface() and a Gmsh
    # model (which stays in Gmsh) do not.
    for function in (strata.mesh, strata.layers):
        assert inspect.signature(function).parameters["foam_case"].default is False
    assert "foam_case" not in inspect.signature(strata.surface).parameters
    assert "foam_case" not in [k["name"] for k in strata.keywords("gmsh")]
    assert {k["name"]: k["param"] for k in strata.keywords()}["foam_case"] == "OutputOptions::foam_case"
    case = tmp_path / "case"
    m = strata.mesh(SPHERE_STL, output=str(case), foam_case=True, reynolds=2e5, **SMALL)
    assert len(m.prisms) > 0
    for f in ("constant/polyMesh/boundary", "constant/polyMesh.report.json", "system/controlDict",
              "system/fvSchemes", "system/fvSolution", "constant/transportProperties",
              "constant/turbulenceProperties", "0.orig/U", "0/U", "0/omega"):
        assert (case / f).is_file(), f
    assert "nu              5e-06;" in (case / "constant/transportProperties").read_text()
    assert (case / "0/nut").read_text() == (case / "0.orig/nut").read_text()
    with pytest.raises(strata.InputError, match=r"foam_case=True writes an OpenFOAM case"):
        strata.mesh(SPHERE_STL, foam_case=True, **SMALL)
    # A case directory named without foam_case is refused before any work, saying what to add.
    with pytest.raises(strata.InputError, match=r"it is a directory; for an OpenFOAM case there add foam_case=True"):
        strata.mesh(SPHERE_STL, output=str(case), **SMALL)
