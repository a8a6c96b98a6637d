# The README's FreeCAD picture (docs/images/freecad_strata.png): FreeCAD's GUI under Xvfb, the
# hemisphere-cylinder air domain from examples/data meshed with its own patches (surface_1
# farfield, surface_2 symmetry, surface_3 other, as README's hemisphere-cylinder example), the
# task panel after Mesh, and the 3D view looking (almost) face-on at the symmetry plane y = 0,
# zoomed onto the nose: on the plane, the 8 layers' hexahedra round the body (blue) and the
# tetrahedra beyond; through the body's section, the inside of its wall. From the repository's
# top (with a build in build/):
#   QTWEBENGINE_DISABLE_SANDBOX=1 STRATA_FREECAD_MOD=$PWD/freecad/StrataMesher STRATA_BUILD_PYTHON=$PWD/build/python xvfb-run -a -s "-screen 0 1600x1000x24" freecad docs/freecad_screenshot.py
import os
import sys

if os.environ.get("STRATA_FREECAD_MOD"):
    sys.path.insert(0, os.environ["STRATA_FREECAD_MOD"])
if os.environ.get("STRATA_BUILD_PYTHON"):
    sys.path.insert(0, os.environ["STRATA_BUILD_PYTHON"])
# FreeCAD imported the StrataMesher in its Mod folder at start-up (the workbench imports
# strata_freecad, which imports strata), perhaps another tree's: forget those so the imports
# below take the modules the paths above name.
for _name in list(sys.modules):
    if _name in ("strata", "strata_freecad", "strata_freecad_gui") or _name.startswith("strata."):
        del sys.modules[_name]

import FreeCAD
import FreeCADGui
import Part
from PySide2 import QtCore, QtGui, QtWidgets

import strata
import strata_freecad
import strata_freecad_gui

print("strata_freecad:", strata_freecad.__file__)
print("strata:", strata.__file__)
for _var, _mod in (("STRATA_FREECAD_MOD", strata_freecad), ("STRATA_BUILD_PYTHON", strata)):
    if os.environ.get(_var) and not os.path.realpath(_mod.__file__).startswith(os.path.realpath(os.environ[_var])):
        print(f"{_mod.__name__} is {_mod.__file__}, not from {_var}={os.environ[_var]}")
        os._exit(1)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.environ.get("STRATA_SCREENSHOT", os.path.join(ROOT, "docs", "images", "freecad_strata.png"))
# The 3D view's window on the symmetry plane (x right, z up; the nose is at x = 0, the body's
# radius 0.5): its centre and height; the width follows the view's aspect.
CENTRE = (0.55, 0.0)
HEIGHT = 1.9
TILT = (0.05, 0.05)  # radians about z and x
LAYER_COLOUR = (0.45, 0.65, 0.95)
OTHER_COLOUR = (0.9, 0.9, 0.9)
PANEL_WIDTH = 400  # the Combo View's, so the task panel's fields show whole


def shoot():
    doc = FreeCAD.newDocument("Strata")
    body = doc.addObject("Part::Feature", "HemisphereCylinder")
    body.Shape = Part.read(os.path.join(ROOT, "examples", "data", "hemisphere_cylinder_halfdomain.stp"))
    doc.recompute()
    obj = strata_freecad.make_mesh_object(doc, body)
    strata_freecad._set_options(obj, dict(
        size=10, size_min=0.02, curvature_points=40, quads=True, layers=8, first_height=0.02, growth=1.2,
        patches={"surface_1": "farfield", "surface_2": "symmetry", "surface_3": "other"}))
    FreeCADGui.ActiveDocument.setEdit(obj.Name)
    panel = obj.ViewObject.Proxy.panel
    panel.mesh_button.click()
    panel.patches.setCursorPosition(0)
    body.ViewObject.Visibility = False
    obj.ViewObject.DisplayMode = "Faces & Wireframe"
    # The layers' nodes (those of the hexahedra and prisms) in one colour, the rest in another:
    # the faces take their nodes' colours, so the layers' cells are blue and the first row of
    # cells beyond them (tetrahedra, pyramids) fades from blue to grey. (ElementColor, per
    # element, would be the natural choice, but FreeCAD 0.20 maps the faces of the volumes other
    # than tetrahedra to the wrong elements: everything took the tetrahedra's colour.)
    fm = obj.FemMesh
    layer_nodes = {n for e in fm.Volumes for n in fm.getElementNodes(e) if len(fm.getElementNodes(e)) in (6, 8)}
    obj.ViewObject.NodeColor = {n: LAYER_COLOUR if n in layer_nodes else OTHER_COLOUR for n in fm.Nodes}
    view = FreeCADGui.ActiveDocument.ActiveView
    view.setCameraType("Orthographic")
    # Looking along +y at the symmetry plane y = 0 (the domain is y >= 0), turned a few degrees
    # off face-on: exactly face-on, the plane's edges drew no lines (they lost the depth test to
    # the faces under them).
    from pivy import coin
    view.viewFront()
    cam = view.getCameraNode()
    turn = coin.SbRotation(coin.SbVec3f(0, 0, 1), TILT[0]) * coin.SbRotation(coin.SbVec3f(1, 0, 0), TILT[1])
    cam.orientation.setValue(cam.orientation.getValue() * turn)
    # the camera 50 back from the window's centre, along its own view direction (its -z)
    d = cam.orientation.getValue().multVec(coin.SbVec3f(0, 0, 1))
    cam.position.setValue(CENTRE[0] + 50 * d[0], 50 * d[1], CENTRE[1] + 50 * d[2])
    cam.height.setValue(HEIGHT)
    mw = FreeCADGui.getMainWindow()
    mw.resize(1600, 1000)
    docks = [dock for dock in mw.findChildren(QtWidgets.QDockWidget) if dock.windowTitle() == "Combo View"]
    mw.resizeDocks(docks, [PANEL_WIDTH] * len(docks), QtCore.Qt.Horizontal)

    def grab():
        QtWidgets.QApplication.processEvents()
        shot = mw.grab()
        # The 3D view is OpenGL, which a widget grab leaves blank: render it offscreen (Coin)
        # at the view widget's size and paint it where the widget is.
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
