"""Strata's FreeCAD GUI without a display:  QT_QPA_PLATFORM=offscreen freecadcmd tests/freecad/test_freecad_gui.py

FreeCADGui.showMainWindow() starts FreeCAD's whole GUI inside freecadcmd, drawn by Qt's
offscreen platform (no X server). Checked: InitGui.py adds the workbench, activating it
registers the command, the command on a selected shape makes a mesh object and opens its task
panel, the panel's widgets show the object's properties (Strata's defaults) and write back into
them, and its Mesh button fills the FemMesh. Ends the process itself (freecadcmd's status does not report
a failing script): status 0 and "strata_freecad GUI tests: OK" only when every check passed.
"""

import os
import sys

for var in ("STRATA_FREECAD_MOD", "STRATA_BUILD_PYTHON"):
    if os.environ.get(var):
        sys.path.insert(0, os.environ[var])
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # freecad_checks beside this script

import freecad_checks  # noqa: E402
from freecad_checks import check  # noqa: E402

import FreeCAD  # noqa: E402
import FreeCADGui  # noqa: E402

FreeCADGui.showMainWindow()
from PySide2 import QtWidgets  # noqa: E402

import strata  # noqa: E402
import strata_freecad  # noqa: E402


def test_initgui_registers_workbench_and_command():
    here = os.path.dirname(os.path.realpath(strata_freecad.__file__))
    if "StrataWorkbench" not in FreeCADGui.listWorkbenches():
        # Not installed into FreeCAD's Mod folders: run InitGui.py as FreeCAD would at start-up.
        path = os.path.join(here, "InitGui.py")
        with open(path) as f:
            exec(compile(f.read(), path, "exec"), {"Gui": FreeCADGui, "__name__": "InitGui"})
    # Installed by setup (scripts/install_freecad.sh), FreeCAD registered it at start-up: it must
    # be this tree's module.
    check("StrataWorkbench" in FreeCADGui.listWorkbenches(), f"workbenches {sorted(FreeCADGui.listWorkbenches())}")
    wb = FreeCADGui.listWorkbenches()["StrataWorkbench"]
    check(os.path.isfile(wb.Icon), f"icon {wb.Icon}")
    check(os.path.dirname(os.path.dirname(os.path.realpath(wb.Icon))) == here, f"icon {wb.Icon} not from {here}")
    FreeCADGui.activateWorkbench("StrataWorkbench")  # runs Initialize: the command and toolbar
    check("Strata_HybridMesh" in FreeCADGui.listCommands(), "Strata_HybridMesh not registered")
    import strata_freecad_gui

    res = strata_freecad_gui.CommandHybridMesh().GetResources()
    check(os.path.isfile(res["Pixmap"]) and res["MenuText"], res)


def test_task_panel():
    import strata_freecad_gui

    doc = FreeCAD.newDocument("StrataGui")
    sphere = doc.addObject("Part::Sphere", "Sphere")
    sphere.Radius = 10
    doc.recompute()
    # The command, as a user runs it: select the sphere, Strata_HybridMesh.
    FreeCADGui.Selection.clearSelection()
    check(not strata_freecad_gui.CommandHybridMesh().IsActive(), "command active with nothing selected")
    FreeCADGui.Selection.addSelection(sphere)
    check(strata_freecad_gui.CommandHybridMesh().IsActive(), "command inactive on a selected sphere")
    FreeCADGui.runCommand("Strata_HybridMesh")
    meshes = [o for o in doc.Objects if o.TypeId == "Fem::FemMeshObjectPython"]
    check(len(meshes) == 1 and meshes[0].Part == sphere, f"mesh objects {meshes}")
    obj = meshes[0]
    check(FreeCADGui.Control.activeDialog(), "no task panel open")
    check(isinstance(obj.ViewObject.Proxy, strata_freecad_gui.ViewProviderStrataMesh), "view provider")
    panel = obj.ViewObject.Proxy.panel
    check(isinstance(panel.form, QtWidgets.QWidget), "no form")
    defaults = {k["name"]: k["default"] for k in strata.keywords("mesh")}
    w = panel.widgets
    check(set(w) == {name for name, _, _ in strata_freecad.OPTIONS}, f"widgets {sorted(w)}")
    check(w["layers"].value() == defaults["layers"], f"layers widget {w['layers'].value()}")
    check(w["farfield"].currentText() == defaults["farfield"], w["farfield"].currentText())
    check(abs(w["farfield_size"].value() - defaults["farfield_size"]) < 1e-9, "farfield_size widget")
    check(w["quads"].isChecked() == defaults["quads"], "quads widget")
    # The user's values go into the properties, then the Mesh button meshes.
    w["layers"].setValue(2)
    w["first_height"].setValue(0.1)
    w["size"].setValue(4.0)
    w["farfield_size"].setValue(3.0)
    w["farfield_divisions"].setValue(4)
    w["farfield"].setCurrentText("box")
    panel.mesh_button.click()
    check(obj.Layers == 2 and abs(obj.FirstHeight.Value - 0.1) < 1e-12 and obj.Farfield == "box", "not applied")
    fm = obj.FemMesh
    check(fm.PrismCount > 0 and fm.TetraCount > 0, f"FemMesh {fm.PrismCount} prisms, {fm.TetraCount} tetrahedra")
    check(panel.progress.value() == 1000 and "prism" in panel.report.toPlainText(), panel.report.toPlainText())
    volumes = fm.VolumeCount
    # An error is shown in the panel, not raised into Qt's event loop.
    w["growth"].setValue(0.5)
    panel.mesh_button.click()
    check("growth" in panel.report.toPlainText(), panel.report.toPlainText())
    check(obj.FemMesh.VolumeCount == volumes, "a failed run changed the mesh")
    panel.reject()  # Close: the panel goes, the option stays as typed
    check(not FreeCADGui.Control.activeDialog(), "task panel still open")
    check(obj.Growth == 0.5, "Close did not apply the options")
    FreeCAD.closeDocument(doc.Name)


def main():
    freecad_checks.run([test_initgui_registers_workbench_and_command, test_task_panel], "strata_freecad GUI tests")


main()
