#!/usr/bin/env python3
"""Rows of scripts/speed_table.sh's tables, from `strata mesh` runs of one case.

  speed_row.py NAME RUN2 RUN1
      the first table's row: RUN2 and RUN1 are path prefixes of the runs at 2 threads and at 1:
      PREFIX.log (the summary), PREFIX.time ("SECONDS PEAK_KB" from /usr/bin/time) and
      PREFIX.cgr (the mesh written).
  speed_row.py tets NAME MESHER RUN
      the tetrahedral fill table's row for the run RUN (2 threads) with --tets MESHER.
"""
import os
import re
import sys


def stage_seconds(log):
    """The summary's "time:" line as {stage: seconds}."""
    line = next(l for l in log.splitlines() if l.startswith("time:"))
    return {m.group(1): float(m.group(2)) for m in re.finditer(r"(\w+) ([0-9.]+) s", line)}


def cells(log):
    line = next(l for l in log.splitlines() if l.startswith("cells:"))
    count = {k: 0 for k in ("hexahedra", "prisms", "pyramids", "tetrahedra")}
    for m in re.finditer(r"(\d+) (hexahedra|prisms|pyramids|tetrahedra)", line):
        count[m.group(2)] = int(m.group(1))
    return count


def surface_faces(log):
    m = re.search(r"^surface: \d+ nodes, (\d+) triangles, (\d+) quadrilaterals", log, re.M)
    return int(m.group(1)) + int(m.group(2))


def main(name, run2, run1):
    log2, log1 = open(run2 + ".log").read(), open(run1 + ".log").read()
    t2, t1 = stage_seconds(log2), stage_seconds(log1)
    c = cells(log2)
    layer_cells = c["hexahedra"] + c["prisms"]
    whole, peak_kb = (float(x) for x in open(run2 + ".time").read().split()[:2])
    out_bytes = sum(os.path.getsize(run2 + ext) for ext in (".cgr", ".cgr.bc") if os.path.exists(run2 + ext))
    all_cells = sum(c.values())
    rate = lambda n, s: f"{n / s:,.0f}" if s > 0 else "-"
    print(f"| {name} | {surface_faces(log2):,} | {layer_cells:,} / {c['pyramids']:,} / {c['tetrahedra']:,} "
          f"| {t2['surface']:.1f} | {t2['layers']:.1f} ({rate(layer_cells, t2['layers'])}) "
          f"| {t1['layers']:.1f} ({rate(layer_cells, t1['layers'])}) "
          f"| {t2['tetrahedra']:.1f} ({rate(c['tetrahedra'], t2['tetrahedra'])}) | {t2['validation']:.1f} "
          f"| {t2['write']:.1f} ({out_bytes / 1e6 / t2['write']:.0f}) | {whole:.1f} "
          f"| {peak_kb / 1024:.0f} ({peak_kb * 1024 / all_cells:.0f}) |")


def tets_row(name, mesher, run):
    """Tetrahedra stage, tetrahedra and their rate, the tetrahedra's quality after the
    improvement, checkMesh's figures as Strata computes them, the whole run."""
    log = open(run + ".log").read()
    t, c = stage_seconds(log), cells(log)
    whole = float(open(run + ".time").read().split()[0])
    worst = re.search(r"^  tetrahedron: +min scaled Jacobian ([0-9.e+-]+)", log, re.M)
    improved = re.search(r"below a scaled Jacobian of [0-9.]+: \d+ -> (\d+), the worst [0-9.e+-]+ -> ([0-9.e+-]+)", log)
    foam = re.search(r"non-orthogonality max ([0-9.]+) deg.*skewness max ([0-9.]+)", log)
    rate = c["tetrahedra"] / t["tetrahedra"] if t["tetrahedra"] > 0 else 0
    print(f"| {name} | {mesher} | {t['tetrahedra']:.1f} | {c['tetrahedra']:,} ({rate:,.0f}) "
          f"| {worst.group(1) if worst else '-'} | {improved.group(2) if improved else '-'} "
          f"| {improved.group(1) if improved else '-'} "
          f"| {foam.group(1) if foam else '-'} / {foam.group(2) if foam else '-'} | {whole:.1f} |")


if __name__ == "__main__":
    if len(sys.argv) == 5 and sys.argv[1] == "tets":
        tets_row(*sys.argv[2:])
    elif len(sys.argv) == 4:
        main(*sys.argv[1:])
    else:
        sys.exit(__doc__)
