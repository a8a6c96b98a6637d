#!/usr/bin/env python3
"""One row of scripts/speed_table.sh's first table, from two `strata mesh` runs of one case.

  speed_row.py NAME RUN2 RUN1

RUN2 and RUN1 are path prefixes of the runs at 2 threads and at 1: PREFIX.log (the summary),
PREFIX.time ("SECONDS PEAK_KB" from /usr/bin/time) and PREFIX.cgr (the mesh written).
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


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
