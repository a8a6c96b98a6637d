"""Figures of one `strata mesh` run that the case tables print (case_table.sh, coverage_row.py):
the smallest scaled Jacobian of a cell type from OUT.report.json, and what OpenFOAM's checkMesh
will say from the run's log (its `openfoam:` line and the warnings naming what would fail)."""
import re


def min_jacobian(report, kind):
    """The smallest scaled Jacobian of cells of `kind` (e.g. 'prism'), or '-' if there are none."""
    if report["cells"].get(kind, 0) == 0:
        return "-"
    v = report["quality"]["min_scaled_jacobian"][kind]
    return f"{v:.2g}" if v < 0.01 else f"{v:.3f}"


def checkmesh_verdict(log_text):
    """'Mesh OK' or 'fails', then what would fail: kind, the worst value and (how many)."""
    m = re.search(r"^openfoam: .*?: checkMesh would (say \"Mesh OK\"|fail it)", log_text, re.M)
    verdict = "Mesh OK" if m and "OK" in m.group(1) else "fails"
    why = []
    for w in re.finditer(r"^warning: checkMesh would fail: (\d+) (faces with a skewness|cells with an aspect ratio|"
                         r"[a-z ]+?)[ ,].*?the worst ([0-9.e+-]+)", log_text, re.M):
        kind = "skewness" if "skew" in w.group(2) else "aspect ratio" if "aspect" in w.group(2) else w.group(2)
        why.append(f"{kind} {w.group(3)} ({w.group(1)})")
    return verdict + (": " + ", ".join(why) if why else "")
