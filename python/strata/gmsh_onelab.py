"""Strata as a solver in stock Gmsh's window (the `gmsh` program), through ONELAB.

    strata-gmsh-onelab --register      list Strata among Gmsh's solvers (in ~/.gmsh-options)
    strata-gmsh-onelab --unregister    take it out again
    gmsh MODEL                         then Modules > Solver > Strata: the panel; Run: the mesh

Gmsh lists the solvers named in its options Solver.Name0..9 under Modules > Solver. Clicking
Strata there runs `strata-gmsh-onelab -onelab Strata ADDRESS` (Solver.Executable), which
connects back to Gmsh (strata.onelab) and puts Strata's parameters into the ONELAB panel, the
same ones as strata-gmsh's (strata.gmsh_gui.PANEL). Gmsh's Run button runs it again with the
action "compute": it opens the model Gmsh has open (the ONELAB parameters "Gmsh/Model name"
and "Gmsh/Model absolute path") in its own Gmsh, with the window's mesh size options, meshes
the surface, builds the hybrid mesh with the panel's values, writes MODEL_strata.msh beside
the model and asks Gmsh to merge it: the window shows it cut at the mid-plane, the report goes
to Gmsh's message console and Strata's errors too, as errors. Gmsh itself never runs Strata's
code, so neither its TetGen nor a crash of Strata can touch the window.
"""

import os
import sys
import time

import gmsh

from . import InputError, gmsh_gui, onelab

NAME = "Strata"
NUM_SOLVERS = 10  # Gmsh 4.8's Solver.Name0..9
BEGIN = "// Strata: begin (written by strata-gmsh-onelab --register; --unregister removes it)"
END = "// Strata: end"

# Gmsh's own Run meshes the model in 3D and saves it before it runs a solver (Solver.AutoMesh);
# Strata meshes it itself, so the client turns that off (a parameter named like an option sets
# the option in Gmsh). strata-gmsh does the same in its window.
AUTOMESH_OFF = {"type": "number", "name": "Solver.AutoMesh", "values": [0]}

# The window's options that shape the surface mesh, copied into the client's Gmsh after the
# model is opened (they hold the model's own settings too: Gmsh parsed the same file).
MESH_OPTIONS = ("Mesh.MeshSizeFactor", "Mesh.MeshSizeMin", "Mesh.MeshSizeMax", "Mesh.MeshSizeFromPoints",
                "Mesh.MeshSizeFromCurvature", "Mesh.MeshSizeExtendFromBoundary", "Mesh.Algorithm",
                "Mesh.RecombineAll", "Mesh.RecombinationAlgorithm")


def model_file(client):
    """The file of the model open in Gmsh, from its ONELAB parameters."""
    name = (client.values("Gmsh/Model name", "string") or [""])[0]
    if not name:
        raise InputError("Gmsh has no model file open (File > Open one, then run Strata)")
    if os.path.isabs(name):
        return name
    directory = (client.values("Gmsh/Model absolute path", "string") or [""])[0]
    return os.path.join(directory, os.path.basename(name))


def result_file(model):
    return os.path.splitext(model)[0] + "_strata.msh"


def _open(model):
    """Open the model in this process's Gmsh unless it is open (a .geo is checked first)."""
    if not gmsh.model.getEntities():
        gmsh_gui.open_model(model)


def _define_missing(client):
    """Define the panel's parameters Gmsh does not have yet (a value the user set stays)."""
    names = [name for name, _ in gmsh_gui.PANEL] + [gmsh_gui.RESULT]
    missing = {name for name in names if not (client.get(name, "number") or client.get(name, "string"))}
    if not missing:
        return
    for p in gmsh_gui.parameter_definitions():
        if p["name"] in missing:
            client.set(p)


def _say(client, line):
    # Gmsh puts the client's name before what it says: "Strata - coverage ..."
    client.info(line.replace(f"{NAME}: ", "", 1))


def _progress_to(client):
    last = {"stage": None, "time": 0.0}

    def progress(stage, fraction):
        now = time.monotonic()
        if stage != last["stage"] or now - last["time"] > 0.25:
            client.progress(f"{stage} {100 * fraction:.0f} %")
            last.update(stage=stage, time=now)

    return progress


def _compute(client, model):
    """Mesh the model with the panel's values and write the result. Returns what Gmsh is to
    parse (the view's options) and merge (the result file)."""
    options = gmsh_gui.options_from_parameters(client.values, lambda name: client.values(name, "string"))
    _open(model)
    for option in MESH_OPTIONS:
        value = client.values(option)
        if value:
            gmsh.option.setNumber(option, value[0])
    report = gmsh_gui.mesh_open_model(options, _progress_to(client), lambda line: _say(client, line))
    out = result_file(model)
    gmsh.write(out)
    lines = gmsh_gui.coverage_lines(report)
    for line in lines + [f"wrote {out}"]:
        _say(client, line)
    client.set(gmsh_gui.result_parameter(gmsh_gui.result_text(lines)))
    return "".join(f"{option} = {value};" for option, value in gmsh_gui.volume_view_options()), out


def _run(client, action):
    """The action in this process's own Gmsh session; for "compute", what to show (_compute)."""
    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        client.set(AUTOMESH_OFF)
        model = model_file(client)
        _define_missing(client)
        return _compute(client, model) if action == "compute" else None
    finally:
        gmsh.finalize()


def serve(name, address):
    """Run as the ONELAB client Gmsh launched: the action Gmsh asks for (initialize, check,
    compute). Errors go to Gmsh's console and the Result parameter; returns the exit status."""
    with onelab.Client(name, address) as client:
        action = (client.values(name + "/Action", "string") or [""])[0]
        if action == "stop":
            return 0
        try:
            shown = _run(client, action)
        except Exception as e:  # Gmsh shows it in its console; the window stays as it was
            client.error(str(e))
            client.set(gmsh_gui.result_parameter(f"failed: {e}"))
            return 1
        if shown:
            # Only once this process's Gmsh is finalized: gmsh.finalize() deletes
            # $HOME/.gmsh-tmp, the file through which Gmsh parses these options when the model
            # is in $HOME (seen: the options lost in 1 run of 4).
            view, out = shown
            client.parse_string(view)
            client.merge_file(out)
        return 0


def _gmsh_home():
    # Gmsh's own rule (Context.cpp): GMSH_HOME, else HOME.
    return os.environ.get("GMSH_HOME") or os.path.expanduser("~")


def _without_block(text):
    lines, keep, inside = text.splitlines(keepends=True), [], False
    for line in lines:
        if line.rstrip("\n") == BEGIN:
            inside = True
        elif inside and line.rstrip("\n") == END:
            inside = False
        elif not inside:
            keep.append(line)
    return "".join(keep)


def registration(executable):
    """The lines register() adds to Gmsh's options file: .geo code run at Gmsh's start-up,
    after the session file (~/.gmshrc, which holds the solvers Gmsh last had). Strata takes the
    slot where the session has it, else the first empty one: no other solver is replaced."""
    if any(c in executable for c in '"\\\n'):
        raise ValueError(f"{executable!r}: a path with a quote, a backslash or a line break cannot go into Gmsh's options")
    out = [BEGIN, "strata_slot_ = -1;"]
    out += [f"If (!StrLen(Solver.Name{i})) strata_slot_ = {i}; EndIf" for i in reversed(range(NUM_SOLVERS))]
    out += [f'If (!StrCmp(Solver.Name{i}, "{NAME}")) strata_slot_ = {i}; EndIf' for i in range(NUM_SOLVERS)]
    out += [f'If (strata_slot_ == {i}) Solver.Name{i} = "{NAME}"; Solver.Executable{i} = "{executable}"; EndIf'
            for i in range(NUM_SOLVERS)]
    return "\n".join(out + [END]) + "\n"


def _rewrite(path, text):
    tmp = path + ".strata-tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def register(executable, home=None):
    """Add Strata to Gmsh's solvers in HOME/.gmsh-options (Gmsh's General.OptionsFileName), or
    replace an earlier registration; the file's other lines stay. Returns the file's path."""
    path = os.path.join(home or _gmsh_home(), ".gmsh-options")
    text = open(path).read() if os.path.exists(path) else ""
    text = _without_block(text)
    if text and not text.endswith("\n"):
        text += "\n"
    _rewrite(path, text + registration(os.path.abspath(executable)))
    return path


def unregister(home=None):
    """Take Strata out of HOME/.gmsh-options and out of the solvers Gmsh's session file
    (HOME/.gmshrc) remembers. Returns the files changed."""
    home = home or _gmsh_home()
    changed = []
    options = os.path.join(home, ".gmsh-options")
    if os.path.exists(options):
        text = open(options).read()
        if _without_block(text) != text:
            _rewrite(options, _without_block(text))
            changed.append(options)
    session = os.path.join(home, ".gmshrc")
    if os.path.exists(session):
        lines = open(session).read().splitlines()
        slots = [i for i in range(NUM_SOLVERS) if f'Solver.Name{i} = "{NAME}";' in lines]
        if slots:
            emptied = tuple(f"Solver.{key}{i} = " for i in slots for key in ("Name", "Executable"))
            _rewrite(session, "\n".join(line.split(" = ")[0] + ' = "";' if line.startswith(emptied) else line
                                         for line in lines) + "\n")
            changed.append(session)
    return changed


USAGE = """usage: strata-gmsh-onelab --register [EXECUTABLE] | --unregister
  --register    list Strata among Gmsh's solvers (Modules > Solver) in ~/.gmsh-options;
                EXECUTABLE: what Gmsh runs (default: this program)
  --unregister  take it out of ~/.gmsh-options and ~/.gmshrc (close Gmsh first: it rewrites
                ~/.gmshrc when its window closes)
Gmsh itself runs it as: strata-gmsh-onelab -onelab NAME ADDRESS"""


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if "-onelab" in argv:
        i = argv.index("-onelab")
        if len(argv) < i + 3:
            print("strata-gmsh-onelab: -onelab needs a client name and the server's address", file=sys.stderr)
            return 2
        return serve(argv[i + 1], argv[i + 2])
    if argv[:1] == ["--register"] and len(argv) <= 2:
        executable = argv[1] if len(argv) == 2 else os.environ.get("STRATA_GMSH_ONELAB")
        if not executable:
            print("strata-gmsh-onelab: --register needs the EXECUTABLE Gmsh is to run", file=sys.stderr)
            return 2
        print(f"strata-gmsh-onelab: Strata is a solver of Gmsh's (Modules > Solver): {register(executable)}")
        return 0
    if argv == ["--unregister"]:
        changed = unregister()
        print("strata-gmsh-onelab: removed from " + (", ".join(changed) if changed else "nothing (not registered)"))
        return 0
    print(USAGE, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
