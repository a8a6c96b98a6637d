"""What the two FreeCAD test scripts share (they run as freecadcmd scripts, not under pytest).

freecadcmd's exit status does not report a failing script, so run() ends the process itself:
status 0, and the line "<title>: OK" that CTest's PASS_REGULAR_EXPRESSION looks for, only when
every test passed.
"""

import os
import sys
import traceback


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def run(tests, title):
    failed = []
    for t in tests:
        try:
            t()
            print(f"PASS {t.__name__}")
        except Exception:
            traceback.print_exc()
            print(f"FAIL {t.__name__}")
            failed.append(t.__name__)
    print(f"{title}: " + (f"{len(failed)} failed: {', '.join(failed)}" if failed else "OK"))
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(1 if failed else 0)
