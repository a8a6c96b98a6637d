"""Strata's GUI in FreeCAD: the command Strata_HybridMesh (select a Part object or body, click)
and its task panel: the mesh object's options, a Mesh button, progress and Strata's report.
The options' widgets come from strata_freecad.OPTIONS and the object's properties, whose
defaults are the strata package's."""

import os

import FreeCAD
import FreeCADGui
from PySide2 import QtCore, QtWidgets

import strata
import strata_freecad

ICON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "Resources", "strata_mesh.svg")


def _shape_object(obj):
    shape = getattr(obj, "Shape", None)
    return shape is not None and not shape.isNull()


class ViewProviderStrataMesh(strata_freecad.Stateless):
    """FEM's mesh view provider (FreeCAD shows the FemMesh) with a double-click to the task panel."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return ICON

    def setEdit(self, vobj, mode=0):
        self.panel = TaskPanel(vobj.Object)
        FreeCADGui.Control.showDialog(self.panel)
        return True

    def unsetEdit(self, vobj, mode=0):
        FreeCADGui.Control.closeDialog()
        self.panel = None
        return True

    def doubleClicked(self, vobj):
        if FreeCADGui.Control.activeDialog():
            FreeCADGui.Control.closeDialog()
        FreeCADGui.ActiveDocument.setEdit(vobj.Object.Name)
        return True


class TaskPanel:
    """The options of one Strata mesh object, a Mesh button, a progress bar and the report."""

    def __init__(self, obj):
        self.obj = obj
        self.widgets = {}
        self.form = QtWidgets.QWidget()
        self.form.setWindowTitle("Strata hybrid mesh")
        layout = QtWidgets.QVBoxLayout(self.form)
        part = QtWidgets.QLabel(f"Shape: {obj.Part.Label if obj.Part else '(none)'}")
        layout.addWidget(part)
        boxes = {}
        for name, group, kind in strata_freecad.OPTIONS:
            if group not in boxes:
                box = QtWidgets.QGroupBox(group)
                boxes[group] = QtWidgets.QFormLayout(box)
                layout.addWidget(box)
            prop = strata_freecad._property_name(name)
            widget = self._widget(obj, prop, kind)
            widget.setToolTip(obj.getDocumentationOfProperty(prop))
            self.widgets[name] = widget
            boxes[group].addRow(name.replace("_", " "), widget)
        self.patches = QtWidgets.QLineEdit(", ".join(f"{k}={v}" for k, v in obj.PatchKinds.items()))
        self.patches.setPlaceholderText("surface_2=symmetry, surface_1=farfield")
        self.patches.setToolTip(obj.getDocumentationOfProperty("PatchKinds"))
        boxes["Boundary layers"].addRow("patch kinds", self.patches)
        self.mesh_button = QtWidgets.QPushButton("Mesh")
        self.mesh_button.clicked.connect(self.mesh)
        layout.addWidget(self.mesh_button)
        self.progress = QtWidgets.QProgressBar()
        self.progress.setRange(0, 1000)
        self.progress.setFormat("%p%")
        layout.addWidget(self.progress)
        self.report = QtWidgets.QPlainTextEdit(obj.Report)
        self.report.setReadOnly(True)
        self.report.setMinimumHeight(80)
        layout.addWidget(self.report)

    @staticmethod
    def _widget(obj, prop, kind):
        value = getattr(obj, prop)
        if kind == "length":
            w = QtWidgets.QDoubleSpinBox()
            w.setDecimals(6)
            w.setRange(0.0, 1e9)
            w.setSuffix(" mm")
            w.setValue(value.getValueAs("mm"))
        elif isinstance(kind, tuple):
            w = QtWidgets.QComboBox()
            w.addItems(obj.getEnumerationsOfProperty(prop))
            w.setCurrentText(value)
        elif isinstance(value, bool):
            w = QtWidgets.QCheckBox()
            w.setChecked(value)
        elif isinstance(value, int):
            w = QtWidgets.QSpinBox()
            w.setRange(0, 1000000)
            w.setValue(value)
        elif isinstance(value, float):
            w = QtWidgets.QDoubleSpinBox()
            w.setDecimals(6)
            w.setRange(-1e12, 1e12)
            w.setValue(value)
        else:
            w = QtWidgets.QLineEdit(str(value))
        return w

    def apply(self):
        """The widgets' values into the object's properties."""
        options = {}
        for name, widget in self.widgets.items():
            if isinstance(widget, QtWidgets.QComboBox):
                options[name] = widget.currentText()
            elif isinstance(widget, QtWidgets.QCheckBox):
                options[name] = widget.isChecked()
            elif isinstance(widget, QtWidgets.QLineEdit):
                options[name] = widget.text()
            else:
                options[name] = widget.value()
        patches = {}
        for item in self.patches.text().replace(";", ",").split(","):
            if item.strip():
                name, _, kind = item.partition("=")
                patches[name.strip()] = kind.strip()
        options["patches"] = patches
        strata_freecad._set_options(self.obj, options)

    def _on_progress(self, stage, fraction):
        self.progress.setFormat(f"{stage} %p%")
        self.progress.setValue(int(1000 * max(0.0, min(1.0, fraction))))
        QtWidgets.QApplication.processEvents()

    def mesh(self):
        """The Mesh button: apply the options and run Strata; the report or the error below."""
        self.apply()
        self.mesh_button.setEnabled(False)
        QtWidgets.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        try:
            strata_freecad.run(self.obj, progress=self._on_progress)
            self.progress.setFormat("done")
            self.progress.setValue(1000)
            self.report.setPlainText(self.obj.Report)
            self.obj.Document.recompute()
        except (strata.Error, ValueError) as e:
            self.report.setPlainText(f"Strata: {e}")
            FreeCAD.Console.PrintError(f"Strata: {e}\n")
        finally:
            QtWidgets.QApplication.restoreOverrideCursor()
            self.mesh_button.setEnabled(True)

    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Close)

    def reject(self):
        self.apply()
        self._close()
        return True

    def accept(self):
        return self.reject()

    def _close(self):
        if FreeCAD.GuiUp and FreeCADGui.ActiveDocument:
            FreeCADGui.ActiveDocument.resetEdit()
        FreeCADGui.Control.closeDialog()


class CommandHybridMesh:
    """Strata_HybridMesh: a Strata mesh object for the selected shape, and its task panel."""

    def GetResources(self):
        return {
            "Pixmap": ICON,
            "MenuText": "Strata hybrid mesh",
            "ToolTip": "Boundary-layer prisms and hexahedra, pyramids and tetrahedra to a farfield, around the "
                       "selected shape (Strata), as a FEM mesh with a face group per patch",
        }

    def IsActive(self):
        if FreeCAD.ActiveDocument is None:
            return False
        sel = FreeCADGui.Selection.getSelection()
        return len(sel) == 1 and _shape_object(sel[0])

    def Activated(self):
        part = FreeCADGui.Selection.getSelection()[0]
        doc = FreeCAD.ActiveDocument
        doc.openTransaction("Strata hybrid mesh")
        obj = strata_freecad.make_mesh_object(doc, part)
        doc.commitTransaction()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.ActiveDocument.setEdit(obj.Name)


FreeCADGui.addCommand("Strata_HybridMesh", CommandHybridMesh())
