# The README's FreeCAD picture (docs/images/freecad_strata.png): FreeCAD's GUI under Xvfb, the
# hemisphere-cylinder from examples/data, a Strata mesh object, its task panel after Mesh.
#   QTWEBENGINE_DISABLE_SANDBOX=1 STRATA_FREECAD_MOD=$PWD/freecad/StrataMesher xvfb-run -a -s "-screen 0 1600x1000x24" freecad docs/freecad_screenshot.py
import os
import sys

if os.environ.get("STRATA_FREECAD_MOD"):
    sys.path.insert(0, os.environ["STRATA_FREECAD_MOD"])
if os.environ.get("STRATA_BUILD_PYTHON"):
    sys.path.insert(0, os.environ["STRATA_BUILD_PYTHON"])

import FreeCAD
import FreeCADGui
import Part
from PySide2 import QtCore, QtWidgets

import strata_freecad
import strata_freecad_gui

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.environ.get("STRATA_SCREENSHOT", os.path.join(ROOT, "docs", "images", "freecad_strata.png"))


def shoot():
    doc = FreeCAD.newDocument("Strata")
    body = doc.addObject("Part::Feature", "HemisphereCylinder")
    body.Shape = Part.read(os.path.join(ROOT, "examples", "data", "hemisphere_cylinder_halfdomain.stp"))
    doc.recompute()
    obj = strata_freecad.make_mesh_object(doc, body)
    strata_freecad._set_options(obj, dict(layers=5, first_height=0.01, growth=1.3, quads=True,
                                          farfield="box", farfield_size=1.5, farfield_divisions=4))
    FreeCADGui.ActiveDocument.setEdit(obj.Name)
    panel = obj.ViewObject.Proxy.panel
    panel.mesh_button.click()
    body.ViewObject.Visibility = False
    obj.ViewObject.DisplayMode = "Faces & Wireframe"
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    mw = FreeCADGui.getMainWindow()
    mw.resize(1600, 1000)

    def grab():
        QtWidgets.QApplication.processEvents()
        shot = mw.grab()
        # The 3D view is OpenGL, which a widget grab leaves blank: render it offscreen (Coin)
        # at the view widget's size and paint it where the widget is.
        from PySide2 import QtGui
        gl = [w for w in mw.findChildren(QtWidgets.QWidget) if w.metaObject().className() == "SIM::Coin3D::Quarter::QuarterWidget"]
        if gl:
            w = max(gl, key=lambda g: g.width() * g.height() if g.isVisible() else 0)
            tmp = OUT + ".view.png"
            view.saveImage(tmp, w.width(), w.height(), "White")
            painter = QtGui.QPainter(shot)
            painter.drawImage(w.mapTo(mw, QtCore.QPoint(0, 0)), QtGui.QImage(tmp))
            painter.end()
            os.remove(tmp)
        shot.save(OUT)
        print("wrote", OUT)
        os._exit(0)

    QtCore.QTimer.singleShot(3000, grab)


QtCore.QTimer.singleShot(2000, shoot)
