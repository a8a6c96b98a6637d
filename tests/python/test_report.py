"""The quality report's plots: `strata mesh --plots`, `strata report` and python3 -m
strata.report on a small sphere mesh. The PNGs are real PNGs of a sensible size with more
than a blank canvas in them, and the report's histograms count every cell."""

import json
import os
import shutil
import struct
import subprocess
import sys
import zlib

import pytest

import strata
import strata.report
from conftest import BUILD, BUILD_PYTHON, ROOT, SPHERE_STL

STRATA = os.path.join(BUILD if os.path.isabs(BUILD) else os.path.join(ROOT, BUILD), "app", "strata")
OPTIONS = ["--layers", "4", "--first-height", "1e-3", "--growth", "1.2"]
PNGS = ["wall_thickness.png", "quality_histograms.png", "layers.png", "wall_layers.png", "cut.png"]

pytest.importorskip("matplotlib")


def read_png(path):
    """Width, height and the number of distinct scanline bytes of an 8-bit RGB(A) PNG, every
    chunk's CRC checked (AssertionError otherwise)."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: no PNG signature"
    pos, idat, chunks = 8, b"", []
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        (crc,) = struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])
        assert zlib.crc32(kind + body) & 0xFFFFFFFF == crc, f"{path}: bad CRC in {kind}"
        chunks.append(kind)
        if kind == b"IDAT":
            idat += body
        pos += 12 + n
    assert chunks[0] == b"IHDR" and chunks[-1] == b"IEND", chunks
    width, height = struct.unpack(">II", data[16:24])
    raw = zlib.decompress(idat)
    return width, height, len(set(raw))


@pytest.fixture(scope="module")
def meshed(tmp_path_factory):
    d = tmp_path_factory.mktemp("report")
    out = str(d / "sphere.cgr")
    plots = str(d / "plots")
    env = dict(os.environ, PYTHONPATH=BUILD_PYTHON)
    run = subprocess.run([STRATA, "mesh", SPHERE_STL, "-o", out, *OPTIONS, "--plots", plots],
                         capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    return d, out, plots, run.stdout


def test_mesh_plots_writes_every_png_and_the_index(meshed):
    d, out, plots, stdout = meshed
    assert sorted(os.listdir(plots)) == sorted(PNGS + ["index.md"])
    for name in PNGS:
        w, h, distinct = read_png(os.path.join(plots, name))
        assert 500 <= w <= 2000 and 300 <= h <= 1500, (name, w, h)
        assert distinct > 10, f"{name}: a blank picture"
    index = open(os.path.join(plots, "index.md")).read()
    for name in PNGS:
        assert f"![{name}]({name})" in index
    assert out + ".plot.json" in stdout and "index.md" in stdout


def test_histograms_count_every_cell_and_match_the_python_report(meshed):
    d, out, plots, _ = meshed
    report = json.load(open(out + ".report.json"))
    q = report["quality"]
    assert len(q["bin_edges"]) == len(next(iter(q["histograms"].values()))) + 1 == 26
    assert q["bin_edges"][0] == 0 and q["bin_edges"][1] == pytest.approx(1e-6) and q["bin_edges"][-1] == 1
    # The same options through Python (the mesh is the same for any front-end): the cell counts
    # from the mesh's own arrays, each type's histogram summing to them.
    m = strata.mesh(SPHERE_STL, layers=4, first_height=1e-3, growth=1.2)
    for name, cells in m.cells.items():
        n = len(cells)
        assert report["cells"][name] == n
        if n:
            assert sum(q["histograms"][name]) == n, name
            mq = m.report["quality"]
            assert mq["histograms"][name] == q["histograms"][name]
            assert q["min_scaled_jacobian"][name] == pytest.approx(mq["min_scaled_jacobian"][name], rel=1e-15)
            # the worst cell lies in the first non-empty bin
            first = next(b for b, c in enumerate(q["histograms"][name]) if c)
            lo, hi = q["bin_edges"][first], q["bin_edges"][first + 1]
            assert lo <= q["min_scaled_jacobian"][name] < hi or (first == 25 - 1 and hi == 1)
    assert report["cells"]["prism"] > 0 and report["cells"]["tetrahedron"] > 0
    assert [s["layer"] for s in report["layer_stats"]] == [1, 2, 3, 4]
    assert report["layer_stats"][1]["height"] == pytest.approx(1.2e-3)


def test_plot_data_has_the_wall_with_layers_and_a_cut(meshed):
    d, out, _, _ = meshed
    data = json.load(open(out + ".plot.json"))
    wall = data["wall"]
    assert len(wall["layers"]) == len(wall["points"]) > 100
    assert len(wall["face_patch"]) == len(wall["faces"])
    assert all(0 <= v < len(wall["points"]) for f in wall["faces"] for v in f)
    assert set(wall["layers"]) <= set(range(5)) and max(wall["layers"]) == 4
    assert len(wall["share"]) == len(wall["points"]) and all(0 <= s <= 1.5 for s in wall["share"])
    cut = data["cut"]
    assert cut["axis"] in "xyz" and len(cut["polygons"]) == len(cut["types"]) > 50
    assert {"prism", "tetrahedron"} <= set(cut["types"])
    u0, u1, v0, v1 = cut["window"]
    for p in cut["polygons"]:
        assert len(p) >= 6 and len(p) % 2 == 0
        assert all(u0 - 1e-9 <= x <= u1 + 1e-9 for x in p[0::2]) and all(v0 - 1e-9 <= y <= v1 + 1e-9 for y in p[1::2])


def test_report_subcommand_and_module_draw_the_same_files(meshed, tmp_path):
    d, out, plots, _ = meshed
    again = str(tmp_path / "again")
    env = dict(os.environ, PYTHONPATH=BUILD_PYTHON)
    run = subprocess.run([STRATA, "report", out + ".report.json", "--plots", again, "-q"],
                         capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    assert run.stdout == ""
    for name in PNGS + ["index.md"]:  # the same report, the same bytes
        assert open(os.path.join(again, name), "rb").read() == open(os.path.join(plots, name), "rb").read(), name


def test_without_plot_data_the_wall_shows_short_nodes_and_no_cut(meshed, tmp_path):
    d, out, _, _ = meshed
    report = str(tmp_path / "alone.cgr.report.json")
    shutil.copy(out + ".report.json", report)
    files = strata.report.write_plots(report, str(tmp_path / "p"), quiet=True)
    assert [os.path.basename(f) for f in files] == ["wall_thickness.png", "quality_histograms.png", "layers.png",
                                                    "wall_layers.png", "index.md"]
    assert "No OUT.plot.json" in open(files[-1]).read()


def test_the_wall_thickness_picture_is_coloured_by_the_share_reached(meshed, tmp_path):
    # The sphere's nodes all reach the thickness asked; told that half of them reached none,
    # the picture changes, and drawn again from the same files it is the same bytes.
    d, out, plots, _ = meshed
    report, data = strata.report.load(out + ".report.json")
    again = str(tmp_path / "again.png")
    strata.report.plot_wall_thickness(report, data, again)
    assert open(again, "rb").read() == open(os.path.join(plots, "wall_thickness.png"), "rb").read()
    share = data["wall"]["share"]
    data["wall"]["share"] = [0.0 if i % 2 else s for i, s in enumerate(share)]
    halved = str(tmp_path / "halved.png")
    strata.report.plot_wall_thickness(report, data, halved)
    assert open(halved, "rb").read() != open(again, "rb").read()
    w, h, distinct = read_png(halved)
    assert 500 <= w <= 2000 and distinct > 10


def test_the_whole_wall_line_is_the_cli_summary_and_the_index(meshed):
    d, out, plots, stdout = meshed
    report = json.load(open(out + ".report.json"))
    summary = strata.report.wall_summary(report)
    assert summary.startswith("every layer on ")
    assert "coverage: " + summary + "\n" in stdout
    assert f"Whole wall: {summary}." in open(os.path.join(plots, "index.md")).read()


def test_a_histogram_that_does_not_count_every_cell_is_refused(meshed, tmp_path):
    d, out, _, _ = meshed
    report = json.load(open(out + ".report.json"))
    report["quality"]["histograms"]["prism"][-1] += 1
    bad = tmp_path / "bad.report.json"
    bad.write_text(json.dumps(report))
    run = subprocess.run([sys.executable, "-m", "strata.report", str(bad), "--plots", str(tmp_path / "p")],
                         capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=BUILD_PYTHON))
    assert run.returncode != 0
    assert "prism: histogram counts sum to" in run.stderr


def test_a_missing_report_is_one_line(tmp_path):
    run = subprocess.run([STRATA, "report", str(tmp_path / "none.report.json"), "--plots", str(tmp_path / "p")],
                         capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=BUILD_PYTHON))
    assert run.returncode != 0
    assert "none.report.json" in run.stderr and len(run.stderr.strip().splitlines()) == 1
