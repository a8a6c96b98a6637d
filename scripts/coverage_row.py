#!/usr/bin/env python3
"""One Markdown table row of a `strata mesh` run's boundary-layer coverage, as issue 54 states it,
from its log and OUT.report.json; coverage_cases.sh prints them.

  coverage_row.py --header [--patches]
  coverage_row.py LOG REPORT NAME SECONDS [--patches]

The whole wall's row, each wall node once (the report's "coverage", as the summary's coverage
line): wall nodes; the share with every layer; that share among the nodes no proximity limit
binds (a narrow gap, a legitimate limit); the mean thickness reached (of the asked) and the same
where no proximity limit binds; the nodes short by reason (the non-zero ones); checkMesh's
verdict; the smallest scaled Jacobian of the prisms, pyramids and tetrahedra; the seconds.
--patches adds a row per wall patch after it (a node on the border of k patches counts in each)."""
import json
import sys

from report_figures import checkmesh_verdict, min_jacobian

REASONS = ["proximity", "front", "held back", "quality", "turning", "twist", "neighbours", "non-finite",
           "sharp edge"]
COLUMNS = ["case", "wall nodes", "every layer", "every layer, proximity aside", "mean thickness reached",
           "mean thickness, proximity aside", "short (nodes)", "checkMesh", "min scaled Jacobian: prism / pyramid / tet",
           "s"]


def pct(a, b):
    return f"{100.0 * a / b:.1f} %" if b else "-"


def reasons(short):
    """The non-zero reasons of `short`, most nodes first."""
    return " · ".join(f"{k} {v:,}" for k, v in sorted(short.items(), key=lambda kv: -kv[1]) if v) or "none"


def wall_coverage(w):
    """The whole wall's figures from the report's "coverage" (each wall node once): wall nodes,
    the share with every layer, that share where no proximity limit binds, the mean thickness
    reached and the same where no proximity limit binds, and the short nodes by reason."""
    short = {k: w["short"].get(k, 0) for k in REASONS}
    return [f"{w['nodes']:,}", pct(w["all_layers"], w["nodes"]), pct(w["unbound_all_layers"], w["unbound_nodes"]),
            f"{100.0 * w['mean_share']:.1f} %",
            f"{100.0 * w['unbound_mean_share']:.1f} %" if "unbound_mean_share" in w else "-", reasons(short)]


def coverage(patches):
    """The same figures summed over `patches` (a node on the border of k patches counts k
    times, as in the summary's coverage table): for a report without the whole wall's, and
    for --patches."""
    nodes = sum(p["nodes"] for p in patches)
    every = sum(p["all_layers"] for p in patches)
    short = {k: sum(p["short"].get(k, 0) for p in patches) for k in REASONS}
    thick = sum(p["nodes"] * p["mean_share"] for p in patches)
    unbound = sum(p["unbound_nodes"] for p in patches)
    unbound_every = sum(p["unbound_all_layers"] for p in patches)
    unbound_thick = sum(p["unbound_nodes"] * p.get("unbound_mean_share", 0.0) for p in patches)
    has_unbound = all("unbound_mean_share" in p for p in patches)
    return [f"{nodes:,}", pct(every, nodes), pct(unbound_every, unbound), pct(thick, nodes),
            pct(unbound_thick, unbound) if has_unbound else "-", reasons(short)]


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
    figures = wall_coverage(r["coverage"]) if "coverage" in r else coverage(r["patches"])
    print(row([name] + figures + [checkmesh_verdict(open(log).read()), jac, f"{float(seconds):.1f}"]))
    if patches:
        for p in r["patches"]:
            print(row([f"{name}: {p['name']}"] + coverage([p]) + ["", "", ""]))


if __name__ == "__main__":
    main(sys.argv[1:])
