"""Source of cad_named_bodies.step (tests/app/test_cli.cpp): two solids a CAD tool names, a box
"Fuselage" (4 x 1 x 1) and a cylinder "Wing" (radius 0.3, height 2, at x = 8), exported by
FreeCAD's STEP writer, which names each solid's product:
    freecadcmd cad_named_bodies.py      (writes cad_named_bodies.step beside this script)
"""
import os

import FreeCAD
import Import

doc = FreeCAD.newDocument("model")
box = doc.addObject("Part::Box", "Fuselage")
box.Length, box.Width, box.Height = 4, 1, 1
wing = doc.addObject("Part::Cylinder", "Wing")
wing.Radius, wing.Height = 0.3, 2
wing.Placement.Base = FreeCAD.Vector(8, 0, 0)
doc.recompute()
Import.export([box, wing], os.path.join(os.path.dirname(os.path.abspath(__file__)), "cad_named_bodies.step"))
