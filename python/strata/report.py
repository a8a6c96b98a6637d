"""Plots of a mesh's quality report: what `strata report` and `strata mesh --plots` draw.

    python3 -m strata.report OUT.report.json --plots DIR [-q]

Reads OUT.report.json (written next to every mesh) and, if it exists, OUT.plot.json beside it
(the wall surface with the layers and the share of the thickness reached per node and a cut
through the volume mesh, written by `strata mesh --plots`). Writes into DIR, always under the same names:

  quality_histograms.png  cells per scaled-Jacobian bin, one panel per cell type (log bins)
  layers.png              per layer: height, min and mean scaled Jacobian, columns reaching it
  wall_thickness.png      the wall coloured by the share of the thickness asked each node reached,
                          titled with the whole wall's coverage (OUT.plot.json)
  wall_layers.png         the wall coloured by the layers reached per node (OUT.plot.json)
  cut.png                 a section through the mesh near the body, cells by type (OUT.plot.json)
  index.md                the figures as tables and the plots

Everything drawn comes from the files: the C++ side computes the figures (histogram counts in
fixed bins), this only draws them. Matplotlib (Debian's python3-matplotlib), Agg backend.
"""

import argparse
import json
import os
import sys

TYPES = ("tetrahedron", "pyramid", "prism", "hexahedron")
COLOURS = {"tetrahedron": "#4c72b0", "pyramid": "#dd8452", "prism": "#55a868", "hexahedron": "#c44e52"}
PLOTS = ("wall_thickness.png", "quality_histograms.png", "layers.png", "wall_layers.png", "cut.png")


def plot_data_path(report_path):
    """OUT.plot.json beside OUT.report.json."""
    suffix = ".report.json"
    base = report_path[:-len(suffix)] if report_path.endswith(suffix) else os.path.splitext(report_path)[0]
    return base + ".plot.json"


def load(report_path):
    """The report, and the plots' data (None when OUT.plot.json is missing)."""
    try:
        with open(report_path) as f:
            report = json.load(f)
    except OSError as e:
        raise SystemExit(f"strata report: {report_path}: {e.strerror}") from None
    except json.JSONDecodeError as e:
        raise SystemExit(f"strata report: {report_path}: not a Strata report ({e})") from None
    if "quality" not in report:
        raise SystemExit(f"strata report: {report_path}: no \"quality\" section: written by an older strata or by "
                         "`strata layers`/`mesh` before the plots; mesh again")
    data = None
    path = plot_data_path(report_path)
    if os.path.exists(path):
        with open(path) as f:
            data = json.load(f)
    return report, data


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _write_atomically(path, write):
    """write(temporary path), then rename it to path: never a half-written file at path."""
    tmp = f"{path}.tmp{os.getpid()}"
    try:
        write(tmp)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def _save(fig, path):
    # No "Software" metadata (the version): the same report gives the same file.
    _write_atomically(path, lambda tmp: fig.savefig(tmp, format="png", dpi=100, metadata={"Software": None}))


def plot_histograms(report, path):
    plt = _pyplot()
    q = report["quality"]
    edges = q["bin_edges"]
    types = [t for t in TYPES if t in q["histograms"]]
    fig, axes = plt.subplots(len(types), 1, figsize=(8, 1.9 * len(types) + 0.8), sharex=True, squeeze=False)
    # Bin 0 (below 1e-6, from 0) is drawn one bin wide below the first edge, on the log axis.
    lo = edges[1] ** 2 / edges[2]
    lefts = [lo] + edges[1:-1]
    widths = [edges[1] - lo] + [edges[b + 1] - edges[b] for b in range(1, len(edges) - 1)]
    for ax, t in zip(axes[:, 0], types):
        counts = q["histograms"][t]
        ax.bar(lefts, counts, width=widths, align="edge", color=COLOURS[t], edgecolor="black", linewidth=0.4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(0.5, max(counts) * 2)
        ax.set_ylabel("cells")
        ms = q["min_scaled_jacobian"].get(t)
        ax.set_title(f"{t}: {report['cells'][t]} cells, min scaled Jacobian {ms:.3g}", fontsize=10, loc="left")
        ax.grid(True, which="major", axis="x", alpha=0.3)
    axes[-1, 0].set_xlim(lo, 1.0)
    axes[-1, 0].set_xlabel("cell's min scaled Jacobian (leftmost bar: below 1e-6)")
    fig.tight_layout()
    _save(fig, path)
    plt.close(fig)


def plot_layers(report, path):
    plt = _pyplot()
    stats = report.get("layer_stats", [])
    k = [s["layer"] for s in stats]
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(13, 4))
    heights = [s["height"] for s in stats]
    a.semilogy(k, heights, "o-", ms=3)
    a.set_xlabel("layer")
    a.set_ylabel("height asked (model units)")
    a.set_title(f"first height {report['first_height']:.3g}, thickness {report['thickness']:.3g}", fontsize=10)
    b.semilogy(k, [max(s["min_scaled_jacobian"], 1e-7) for s in stats], "v-", ms=3, label="min")
    b.semilogy(k, [max(s["mean_scaled_jacobian"], 1e-7) for s in stats], "o-", ms=3, label="mean")
    b.set_xlabel("layer")
    b.set_ylabel("scaled Jacobian of the layer's cells")
    b.legend()
    b.set_title("quality per layer", fontsize=10)
    walls = max([s["columns"] for s in stats] + [1])
    c.plot(k, [100.0 * s["columns"] / walls for s in stats], "o-", ms=3, label="columns reaching it")
    c.bar(k, [100.0 * s["stopped_nodes"] / walls for s in stats], color="#c44e52", label="stopped below it")
    c.set_ylim(0, 105)
    c.set_xlabel("layer")
    c.set_ylabel(f"% of the {walls} wall columns")
    c.legend(loc="lower left")
    c.set_title("columns per layer", fontsize=10)
    fig.tight_layout()
    _save(fig, path)
    plt.close(fig)


def _layer_colours(plt, asked):
    import matplotlib.colors as mcolors
    cmap = plt.get_cmap("viridis", asked + 1)
    return cmap, mcolors.BoundaryNorm([i - 0.5 for i in range(asked + 2)], asked + 1)


def wall_summary(report):
    """The whole wall's coverage (the report's "coverage") in a line, as the CLI prints it; None
    for a report without it (an older strata's)."""
    w = report.get("coverage")
    if w is None:
        return None
    own = ", ".join(f"{k} {n}" for k, n in w["short"].items() if n and k != "neighbours")
    return (f"every layer on {100 * w['all_layers_share']:.1f} % of {w['nodes']} wall nodes "
            f"({100 * w['unbound_all_layers_share']:.1f} % of the {w['unbound_nodes']} where no proximity limit "
            f"binds), {100 * w['mean_share']:.1f} % of the thickness asked on average "
            f"({100 * w.get('unbound_mean_share', w['mean_share']):.1f} % there); short: "
            f"{w['own_reason_nodes']} for their own reason{f' ({own})' if own else ''}, "
            f"{w['neighbour_nodes']} only because of a neighbour")


def _draw_wall(plt, data, key, short, cmap, norm, path, colourbar, title, nothing):
    """The wall from two sides, each face coloured by the least of its nodes' data["wall"][key]
    (a shortfall is never hidden by its neighbours); with data None, the \\p short nodes (the
    report's) by their key. colourbar: the colour bar's keywords; nothing: the text when there is
    nothing to draw."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    fig = plt.figure(figsize=(12, 5))
    if data is not None:
        pts = data["wall"]["points"]
        values = data["wall"][key]
        faces = data["wall"]["faces"]
        face_values = [min(values[i] for i in f) for f in faces]
        polys = [[pts[i] for i in f] for f in faces]
    else:
        pts = [n["position"] for n in short]
        if not pts:  # nothing to draw in 3D: say so
            ax = fig.add_subplot(1, 1, 1)
            ax.set_axis_off()
            ax.text(0.5, 0.5, nothing, ha="center", va="center", fontsize=14)
            _save(fig, path)
            plt.close(fig)
            return
    xs, ys, zs = zip(*pts) if pts else ((0,), (0,), (0,))
    ranges = [max(v) - min(v) for v in (xs, ys, zs)]
    for j, (az, el) in enumerate(((-60, 25), (120, -25))):
        ax = fig.add_subplot(1, 2, j + 1, projection="3d")
        if data is not None:
            col = Poly3DCollection(polys, facecolors=cmap(norm(face_values)), edgecolors="k", linewidths=0.05)
            ax.add_collection3d(col)
        else:
            ax.scatter(xs, ys, zs, c=[n[key] for n in short], cmap=cmap, norm=norm, s=4)
        ax.set_xlim(min(xs), max(xs))
        ax.set_ylim(min(ys), max(ys))
        ax.set_zlim(min(zs), max(zs))
        ax.set_box_aspect([max(r, 1e-9 * max(ranges)) for r in ranges])
        ax.view_init(elev=el, azim=az)
        ax.set_axis_off()
    import matplotlib.cm as cm
    fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), ax=fig.axes, shrink=0.7, **colourbar)
    fig.suptitle(title)
    _save(fig, path)
    plt.close(fig)


MISSING = "OUT.plot.json missing: no wall drawn; mesh with --plots"


def plot_wall(report, data, path):
    """The wall coloured by the layers reached per node."""
    plt = _pyplot()
    asked = report["layers"]
    cmap, norm = _layer_colours(plt, asked)
    short = report["short_nodes"]
    what = "" if data is not None else " (short nodes only: OUT.plot.json missing; mesh with --plots)"
    _draw_wall(plt, data, "layers", short, cmap, norm, path,
               dict(label=f"layers reached (of {asked})",
                    ticks=sorted(set([0, asked] + list(range(0, asked + 1, max(1, asked // 10)))))),
               f"layers reached over the wall: {len(short)} wall nodes short of {asked} layers{what}",
               f"every wall node reached all {asked} layers\n({MISSING})")


def plot_wall_thickness(report, data, path):
    """The wall coloured by the share of the thickness asked each node reached (0 to 100 %),
    titled with the whole wall's figures."""
    plt = _pyplot()
    import matplotlib.colors as mcolors
    from matplotlib.ticker import PercentFormatter
    shares = data if data is not None and "share" in data["wall"] else None
    what = "" if shares is not None else "\n(short nodes only: OUT.plot.json missing or without shares; mesh again)"
    summary = wall_summary(report)
    title = f"thickness reached over the wall (asked: {report['thickness']:.4g})"
    _draw_wall(plt, shares, "share", report["short_nodes"], plt.get_cmap("viridis"),
               mcolors.Normalize(0.0, 1.0), path,
               dict(label="thickness reached, of the thickness asked", ticks=[k / 10 for k in range(11)],
                    format=PercentFormatter(1.0)),
               title + (":\n" + summary.replace("; ", ";\n") if summary else "") + what,
               f"every wall node reached the thickness asked\n({MISSING})")


def plot_cut(report, data, path):
    plt = _pyplot()
    from matplotlib.collections import PolyCollection
    cut = data["cut"]
    polys = [list(zip(p[0::2], p[1::2])) for p in cut["polygons"]]
    # The layers are thin beside the body: a second panel zooms onto the wall where the cut's
    # layer cells reach highest, 3 thicknesses asked across.
    layer = [p for p, t in zip(polys, cut["types"]) if t in ("prism", "hexahedron")]
    zoom = None
    if layer and report["thickness"] > 0:
        # The body's front in the cut (its lowest u: a leading edge, a nose), where the layers
        # turn round it: the layer cells' polygons there, 3 thicknesses across.
        front = min((pt for p in layer for pt in p), key=lambda pt: pt[0])
        thick = report["thickness"]
        zoom = (front[0] - 0.5 * thick, front[0] + 2.5 * thick, front[1] - 1.5 * thick, front[1] + 1.5 * thick)
    fig, axes = plt.subplots(1, 2 if zoom else 1, figsize=(14 if zoom else 9, 6.5), squeeze=False)
    u0, u1, v0, v1 = cut["window"]
    if layer:
        # The whole panel: the body's section (where its layer cells are) and as much again
        # round it, widened to a square, within the cut's window.
        us = [pt[0] for p in layer for pt in p]
        vs = [pt[1] for p in layer for pt in p]
        cu, cv = (min(us) + max(us)) / 2, (min(vs) + max(vs)) / 2
        half = max(max(us) - min(us), max(vs) - min(vs))
        u0, u1 = max(u0, cu - half), min(u1, cu + half)
        v0, v1 = max(v0, cv - half), min(v1, cv + half)
    for ax, (a0, a1, b0, b1) in zip(axes[0], [(u0, u1, v0, v1)] + ([zoom] if zoom else [])):
        for t in TYPES:
            mine = [p for p, ty in zip(polys, cut["types"]) if ty == t]
            if mine:
                ax.add_collection(PolyCollection(mine, facecolors=COLOURS[t], edgecolors="black",
                                                 linewidths=0.15, alpha=0.85, label=f"{t} ({len(mine)})"))
        ax.set_xlim(a0, a1)
        ax.set_ylim(b0, b1)
        ax.set_aspect("equal")
        ax.set_xlabel(cut["u"])
        ax.set_ylabel(cut["v"])
    axes[0, 0].legend(loc="lower center", bbox_to_anchor=(0.5, 1.01), ncol=4, fontsize=8, frameon=False)
    axes[0, 0].set_title(f"cut {cut['axis']} = {cut['value']:.4g}: cells near the body, by type", fontsize=10,
                         pad=24)
    if zoom:
        axes[0, 1].set_title(f"the layers round the body's front, ({front[0]:.4g}, {front[1]:.4g})", fontsize=10)
    fig.tight_layout()
    _save(fig, path)
    plt.close(fig)


def check(report):
    """The histograms' counts per type are the cells of the type (ValueError otherwise)."""
    for t, counts in report["quality"]["histograms"].items():
        if sum(counts) != report["cells"][t]:
            raise ValueError(f"{t}: histogram counts sum to {sum(counts)}, the mesh has {report['cells'][t]} cells")


def _index(report, data, report_path, written):
    q = report["quality"]
    lines = [f"# Quality report: {os.path.basename(report_path)}", "",
             f"{report['nodes']} nodes; {report['layers']} layers asked, first height {report['first_height']:.4g}, "
             f"thickness {report['thickness']:.4g}.", ""]
    summary = wall_summary(report)
    if summary:
        lines += [f"Whole wall: {summary}.", ""]
    lines += ["| cell type | cells | min scaled Jacobian | cells below 0.01 |", "|---|---:|---:|---:|"]
    edges = q["bin_edges"]
    below = sum(1 for e in edges[1:] if e <= 0.01 * (1 + 1e-12))  # bins wholly below 0.01
    for t in TYPES:
        n = report["cells"][t]
        if n:
            h = q["histograms"][t]
            lines.append(f"| {t} | {n} | {q['min_scaled_jacobian'][t]:.4g} | {sum(h[:below])} |")
    lines += [f"| all | {sum(report['cells'].values())} | {q['min_scaled_jacobian']['all']:.4g} | |", "",
              "| wall patch | nodes | full columns | all layers | mean layers | min layers | mean thickness share |",
              "|---|---:|---:|---:|---:|---:|---:|"]
    for p in report["patches"]:
        full = 100.0 * p["full_nodes"] / p["nodes"] if p["nodes"] else 100.0
        lines.append(f"| {p['name']} | {p['nodes']} | {full:.1f} % | {p['all_layers']} | {p['mean_layers']:.2f} | "
                     f"{p['min_layers']} | {p['mean_share']:.3f} |")
    captions = {
        "quality_histograms.png": "Cells per scaled-Jacobian bin (4 bins a decade), one panel per cell type.",
        "layers.png": "Per layer: height asked, min and mean scaled Jacobian, columns reaching it and stopping.",
        "wall_thickness.png": ("The wall coloured by the share of the thickness asked its nodes reached (a face shows "
                               "its nodes' least; a node nothing limited counts as full)."),
        "wall_layers.png": "The wall coloured by the layers reached (a face shows its nodes' fewest).",
        "cut.png": (f"A cut {data['cut']['axis']} = {data['cut']['value']:.4g} through the mesh near the body."
                    if data else ""),
    }
    lines.append("")
    for name in written:
        lines += [f"## {name}", "", captions[name], "", f"![{name}]({name})", ""]
    if data is None:
        lines += ["No OUT.plot.json beside the report (mesh with `strata mesh --plots DIR`): the wall picture shows "
                  "only the short nodes and there is no cut.", ""]
    return "\n".join(lines)


def write_plots(report_path, plots_dir, quiet=False):
    """Draw the plots of \\p report_path into \\p plots_dir; the files written (index.md last)."""
    report, data = load(report_path)
    check(report)
    os.makedirs(plots_dir, exist_ok=True)
    written = []
    plot_wall_thickness(report, data, os.path.join(plots_dir, "wall_thickness.png"))
    written.append("wall_thickness.png")
    plot_histograms(report, os.path.join(plots_dir, "quality_histograms.png"))
    written.append("quality_histograms.png")
    plot_layers(report, os.path.join(plots_dir, "layers.png"))
    written.append("layers.png")
    plot_wall(report, data, os.path.join(plots_dir, "wall_layers.png"))
    written.append("wall_layers.png")
    if data is not None:
        plot_cut(report, data, os.path.join(plots_dir, "cut.png"))
        written.append("cut.png")
    index = _index(report, data, report_path, written)

    def write_index(tmp):
        with open(tmp, "w") as f:
            f.write(index)

    _write_atomically(os.path.join(plots_dir, "index.md"), write_index)
    files = [os.path.join(plots_dir, n) for n in written + ["index.md"]]
    if not quiet:
        print("wrote " + ", ".join(files))
    return files


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m strata.report", description=__doc__.split("\n")[0])
    parser.add_argument("report", help="OUT.report.json")
    parser.add_argument("--plots", required=True, metavar="DIR", help="directory for the plots (created)")
    parser.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")
    args = parser.parse_args(argv)
    try:
        write_plots(args.report, args.plots, args.quiet)
    except ImportError as e:
        sys.exit(f"strata report: {e}: the plots need matplotlib (Debian: apt install python3-matplotlib)")
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"strata report: {args.report}: {e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
