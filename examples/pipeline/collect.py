"""The workflow's table (examples/pipeline/Snakefile, rule table): one row per case from its
OUT.report.json and Snakemake's benchmark file. Run by Snakemake (the `snakemake` object), or
by hand: python3 collect.py OUT CASE... (reads OUT/CASE/mesh.*.report.json)."""

import csv
import glob
import json
import os
import sys

TYPES = ("tetrahedron", "pyramid", "prism", "hexahedron")
PLURAL = {"tetrahedron": "tetrahedra", "pyramid": "pyramids", "prism": "prisms", "hexahedron": "hexahedra"}
COLUMNS = (["case", "nodes"] + [PLURAL[t] for t in TYPES] + ["cells"]
           + [f"min_sj_{t}" for t in TYPES] + ["min_sj", "full_nodes_pct", "min_layers", "mean_layers",
                                                "short_nodes", "seconds", "options"])


def row(case, report_path, benchmark_path, options):
    with open(report_path) as f:
        r = json.load(f)
    seconds = ""
    if benchmark_path and os.path.exists(benchmark_path):
        with open(benchmark_path) as f:
            head, first = f.read().splitlines()[:2]
        seconds = float(dict(zip(head.split("\t"), first.split("\t")))["s"])
    patches = r["patches"]
    nodes = sum(p["nodes"] for p in patches)
    full = sum(p["full_nodes"] for p in patches)
    out = {"case": case, "nodes": r["nodes"], "cells": sum(r["cells"].values()), "options": options,
           "min_sj": r["quality"]["min_scaled_jacobian"]["all"],
           "full_nodes_pct": round(100.0 * full / nodes, 2) if nodes else 100.0,
           "min_layers": min((p["min_layers"] for p in patches), default=r["layers"]),
           "mean_layers": round(sum(p["mean_layers"] * p["nodes"] for p in patches) / nodes, 3) if nodes else 0,
           "short_nodes": len(r["short_nodes"]), "seconds": round(seconds, 2) if seconds != "" else ""}
    for t in TYPES:
        out[PLURAL[t]] = r["cells"][t]
        out[f"min_sj_{t}"] = r["quality"]["min_scaled_jacobian"].get(t, "")
    return out


def fmt(v):
    return f"{v:.3g}" if isinstance(v, float) else str(v)


def write(rows, csv_path, md_path):
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    shown = [c for c in COLUMNS if c != "options"]
    with open(md_path, "w") as f:
        f.write("| " + " | ".join(shown) + " |\n|" + "---|" * len(shown) + "\n")
        for r in rows:
            f.write("| " + " | ".join(fmt(r[c]) for c in shown) + " |\n")


if "snakemake" in globals():
    sm = globals()["snakemake"]
    rows = [row(c, rp, bp, o) for c, rp, bp, o in
            zip(sm.params.cases, sm.input.reports, sm.input.benchmarks, sm.params.options)]
    write(rows, sm.output.csv, sm.output.md)
elif __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out = sys.argv[1]
    rows = []
    for c in sys.argv[2:]:
        reports = glob.glob(os.path.join(out, c, "mesh.*.report.json"))
        if not reports:
            sys.exit(f"{out}/{c}: no mesh.*.report.json")
        rows.append(row(c, reports[0], os.path.join(out, c, "benchmark.tsv"), ""))
    write(rows, os.path.join(out, "table.csv"), os.path.join(out, "table.md"))
