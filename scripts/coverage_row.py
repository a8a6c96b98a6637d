#!/usr/bin/env python3
"""One Markdown table row of a `strata mesh` run's boundary-layer coverage, as issue 54 states it,
from its log and OUT.report.json; coverage_cases.sh prints them.

  coverage_row.py --header [--patches]
  coverage_row.py LOG REPORT NAME SECONDS [--patches]

The whole wall's row: wall nodes; the share with every layer; that share among the nodes whose
column is not short for proximity (a narrow gap, a legitimate limit); the mean thickness reached
(of the asked); the nodes short by reason (the non-zero ones); checkMesh's verdict; the smallest
scaled Jacobian of the prisms, pyramids and tetrahedra; the seconds. The figures are summed over
the report's wall patches (a node on the border of k patches counts k times, as in the summary's
coverage table and case_table.sh). --patches adds a row per wall patch after it."""
import json
import sys

from report_figures import checkmesh_verdict, min_jacobian

REASONS = ["proximity", "front", "held back", "quality", "turning", "twist", "neighbours", "non-finite",
           "sharp edge"]
COLUMNS = ["case", "wall nodes", "every layer", "every layer, proximity aside", "mean thickness reached",
           "short (nodes)", "checkMesh", "min scaled Jacobian: prism / pyramid / tet", "s"]


def coverage(patches):
    """Wall nodes, the share with every layer, that share proximity aside, the node-weighted mean
    thickness reached, and the short nodes by reason, of `patches` summed."""
    nodes = sum(p["nodes"] for p in patches)
    every = sum(p["all_layers"] for p in patches)
    short = {k: sum(p["short"].get(k, 0) for p in patches) for k in REASONS}
    thick = sum(p["nodes"] * p["mean_share"] for p in patches)
    free = nodes - short["proximity"]  # a proximity stop has fewer layers, so is not in `every`
    pct = lambda a, b: f"{100.0 * a / b:.1f} %" if b else "-"
    why = " · ".join(f"{k} {v:,}" for k, v in sorted(short.items(), key=lambda kv: -kv[1]) if v)
    return [f"{nodes:,}", pct(every, nodes), pct(every, free), pct(thick, nodes), why or "none"]


def row(cells):
    return "| " + " | ".join(cells) + " |"


def main(argv):
    patches = "--patches" in argv
    argv = [a for a in argv if a != "--patches"]
    if argv and argv[0] == "--header":
        print(row(COLUMNS))
        print(row(["---"] * len(COLUMNS)))
        return
    log, report, name, seconds = argv
    r = json.load(open(report))
    jac = " / ".join(min_jacobian(r, t) for t in ("prism", "pyramid", "tetrahedron"))
    print(row([name] + coverage(r["patches"]) + [checkmesh_verdict(open(log).read()), jac, f"{float(seconds):.1f}"]))
    if patches:
        for p in r["patches"]:
            print(row([f"{name}: {p['name']}"] + coverage([p]) + ["", "", ""]))


if __name__ == "__main__":
    main(sys.argv[1:])
