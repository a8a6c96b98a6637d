"""The Python package's tests run against the build tree's package (BUILD_DIR/python, what
scripts/setup.sh's .pth points at), whichever strata an installed .pth would give."""

import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("BUILD_DIR", "build")
BUILD_PYTHON = os.path.join(BUILD if os.path.isabs(BUILD) else os.path.join(ROOT, BUILD), "python")
sys.path.insert(0, BUILD_PYTHON)

EXAMPLES = os.path.join(ROOT, "examples", "data")
TEST_DATA = os.path.join(ROOT, "tests", "data")
SPHERE_STL = os.path.join(EXAMPLES, "sphere.stl")
