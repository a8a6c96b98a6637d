#!/usr/bin/env python3
"""Run the code blocks of README.md and docs/*.md, so that what the documentation shows works.

Each fenced block is one of:
  ```sh, ```bash   run by bash -euo pipefail;
  ```console       its "$ " lines (with their "\\" continuations) run as an sh block, the rest
                   being the output shown;
  ```python        run by /usr/bin/python3 with the build tree's package first on the path;
  ```cpp           a whole program: CMake compiles it (extract-cpp, tests/docs/CMakeLists.txt)
                   against the build's libraries, and the test runs the program;
  ```text, ``` (no language)   a listing, never run.
A line <!-- doc-test: WORDS --> right above a block changes how it runs:
  skip: REASON     not run here; REASON names the test that runs the same thing;
  freecad          a python block run inside FreeCAD (freecadcmd) with Strata's FreeCAD module.
Any other language, or a marker this script does not know, is an error (a block would silently
stop being tested).

Every block runs in a fresh directory holding build/ (the build tree), examples/, scripts/ and
tests/ (links to the repository's), with the build's `strata` on PATH, as a reader who cloned
the repository and ran `bash scripts/setup.sh build` would run it from the repository's root.

  run_doc_blocks.py --source SRC list [--omit KINDS]             the runnable blocks' ids, but
                                                                 KINDS (python, freecad: comma-separated)
  run_doc_blocks.py --source SRC --build BUILD run ID...         run these blocks (exit 1 if one fails)
  run_doc_blocks.py --source SRC --build BUILD all               run every block
  run_doc_blocks.py --source SRC extract-cpp DIR                 write the cpp blocks, print their names
An id is FILE:LINE, the line of the block's opening fence (README.md:120, docs/USAGE.md:40).
"""

import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

RUNNABLE = {"sh", "bash", "console", "python", "cpp"}
LISTINGS = {"", "text"}
MARKER = re.compile(r"^<!--\s*doc-test:\s*(.*?)\s*-->\s*$")
FENCE = re.compile(r"^```(\S*)\s*$")
TIMEOUT = 600


class Block:
    def __init__(self, path, line, lang, text, marker):
        self.path, self.line, self.lang, self.text, self.marker = path, line, lang, text, marker

    @property
    def id(self):
        return f"{self.path}:{self.line}"

    @property
    def cpp_name(self):
        return "doc_" + re.sub(r"[^A-Za-z0-9]", "_", self.path) + f"_{self.line}"


def doc_files(source):
    docs = sorted(os.path.relpath(p, source) for p in glob.glob(os.path.join(source, "docs", "*.md")))
    return ["README.md"] + docs


def parse(source, path):
    """The fenced blocks of one Markdown file; raises ValueError on a block this script cannot judge."""
    blocks, lines = [], open(os.path.join(source, path), encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        start, lang = i, m.group(1)
        j = i + 1
        while j < len(lines) and lines[j].rstrip() != "```":
            j += 1
        if j == len(lines):
            raise ValueError(f"{path}:{start + 1}: the block opened here is never closed")
        k = start - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        mm = MARKER.match(lines[k]) if k >= 0 else None
        marker = mm.group(1) if mm else ""
        if lang not in RUNNABLE | LISTINGS:
            raise ValueError(f"{path}:{start + 1}: block in '{lang}': use sh, bash, console, python, cpp or text")
        if marker and not (marker == "freecad" and lang == "python") and not re.match(r"skip:\s*\S", marker):
            raise ValueError(f"{path}:{start + 1}: unknown marker '{marker}' (skip: REASON, or freecad on python)")
        blocks.append(Block(path, start + 1, lang, "\n".join(lines[start + 1 : j]) + "\n", marker))
        i = j + 1
    return blocks


def all_blocks(source):
    return [b for path in doc_files(source) for b in parse(source, path)]


def console_commands(text):
    """The commands of a console listing: each "$ " line and the lines its trailing "\\" continues."""
    out, continuing = [], False
    for line in text.split("\n"):
        if continuing or line.startswith("$ "):
            out.append(line[2:] if line.startswith("$ ") and not continuing else line)
            continuing = line.rstrip().endswith("\\")
    if not out:
        raise ValueError("a console block with no '$ ' command: make it a text block")
    return "\n".join(out) + "\n"


def workdir(source, build):
    """A fresh directory laid out as the repository's root after a build."""
    work = tempfile.mkdtemp(prefix="strata_doc_")
    for name in ("examples", "scripts", "tests", "docs", "freecad"):
        os.symlink(os.path.join(source, name), os.path.join(work, name))
    os.symlink(build, os.path.join(work, "build"))
    return work


def environment(build):
    env = dict(os.environ)
    env["PATH"] = os.path.join(build, "app") + os.pathsep + env.get("PATH", "")
    python = os.path.join(build, "python")
    env["PYTHONPATH"] = python + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["STRATA_BUILD_PYTHON"] = python
    env["MPLBACKEND"] = "Agg"
    return env


FREECAD_WRAPPER = """\
import os, sys, traceback
sys.path[:0] = [{python!r}, {module!r}]
os.chdir({work!r})
try:
    exec(compile(open({script!r}).read(), {name!r}, "exec"), {{"__name__": "__main__"}})
    print("doc block: OK")
except BaseException:
    traceback.print_exc()
    print("doc block: FAILED")
sys.stdout.flush()
sys.stderr.flush()
os._exit(0)
"""


def command(block, source, build, work):
    """The command line that runs BLOCK in WORK, and the line its output must hold (or None)."""
    script = os.path.join(work, "block")
    if block.lang in ("sh", "bash", "console"):
        text = console_commands(block.text) if block.lang == "console" else block.text
        open(script, "w").write(text)
        return ["bash", "-euo", "pipefail", script], None
    if block.lang == "python" and block.marker == "freecad":
        freecadcmd = shutil.which("freecadcmd")
        if not freecadcmd:
            raise RuntimeError("freecadcmd not found (scripts/setup.sh installs freecad-python3)")
        open(script + ".py", "w").write(block.text)
        wrapper = FREECAD_WRAPPER.format(python=os.path.join(build, "python"),
                                         module=os.path.join(source, "freecad", "StrataMesher"), work=work,
                                         script=script + ".py", name=block.id)
        open(script + "_freecad.py", "w").write(wrapper)
        return [freecadcmd, script + "_freecad.py"], "doc block: OK"
    if block.lang == "python":
        open(script + ".py", "w").write(block.text)
        return ["/usr/bin/python3", script + ".py"], None
    program = os.path.join(build, "tests", "docs", block.cpp_name)
    if not os.path.exists(program):
        raise RuntimeError(f"{program} is not built (cmake --build BUILD --target {block.cpp_name})")
    return [program], None


def run(block, source, build):
    if block.marker.startswith("skip:"):
        print(f"{block.id}: not run here ({block.marker[5:].strip()})")
        return True
    work = workdir(source, build)
    start = time.monotonic()
    try:
        argv, verdict = command(block, source, build, work)
        proc = subprocess.run(argv, cwd=work, env=environment(build), stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, timeout=TIMEOUT, stdin=subprocess.DEVNULL)
        ok = proc.returncode == 0 and (verdict is None or verdict in proc.stdout)
        output = proc.stdout
    except (RuntimeError, ValueError, subprocess.TimeoutExpired) as e:
        ok, output = False, str(e)
    seconds = time.monotonic() - start
    if ok:
        print(f"{block.id}: {block.lang} block ran ({seconds:.1f} s)")
        shutil.rmtree(work, ignore_errors=True)
    else:
        print(f"{block.id}: {block.lang} block FAILED ({seconds:.1f} s; work directory {work})\n"
              f"--- block ---\n{block.text}--- output ---\n{output}")
    return ok


def write_if_changed(path, text):
    if not os.path.exists(path) or open(path).read() != text:
        open(path, "w").write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--source", required=True)
    ap.add_argument("--build")
    ap.add_argument("--omit", default="", help="list: leave out these kinds (python, freecad)")
    ap.add_argument("action", choices=["list", "run", "all", "extract-cpp"])
    ap.add_argument("args", nargs="*")
    a = ap.parse_args()
    source = os.path.abspath(a.source)
    try:
        blocks = all_blocks(source)
    except ValueError as e:
        print(f"run_doc_blocks: {e}", file=sys.stderr)
        return 1
    if a.action == "extract-cpp":
        os.makedirs(a.args[0], exist_ok=True)
        for b in blocks:
            if b.lang == "cpp":
                write_if_changed(os.path.join(a.args[0], b.cpp_name + ".cpp"), f"// {b.id}\n" + b.text)
                print(b.cpp_name)
        return 0
    runnable = [b for b in blocks if b.lang in RUNNABLE]
    if a.action == "list":
        omit = set(filter(None, a.omit.split(",")))
        for b in runnable:
            kind = "freecad" if b.marker == "freecad" else b.lang
            if kind not in omit and not (kind == "freecad" and "python" in omit):
                print(b.id)
        return 0
    build = os.path.abspath(a.build)
    by_id = {b.id: b for b in runnable}
    if a.action == "run":
        missing = [i for i in a.args if i not in by_id]
        if missing or not a.args:
            print(f"run_doc_blocks: no runnable block {missing} (re-run cmake after editing the docs)", file=sys.stderr)
            return 1
        chosen = [by_id[i] for i in a.args]
    else:
        chosen = runnable
    results = [run(b, source, build) for b in chosen]
    print(f"{results.count(True)} passed, {results.count(False)} failed")
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
