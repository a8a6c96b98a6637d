# Strata's GUI in FreeCAD: a workbench "Strata" with the command Strata_HybridMesh (select a
# Part object or body, then the command: a mesh object and its task panel). The command is
# registered when the workbench is first activated, and can then be added to any toolbar
# (Tools > Customize), e.g. FEM's. FreeCAD execs this file with FreeCADGui as Gui in scope.
import os


class StrataWorkbench(Gui.Workbench):  # noqa: F821  (FreeCAD provides Gui)
    MenuText = "Strata"
    ToolTip = "Near-body hybrid meshes for viscous CFD (boundary layers, pyramids, tetrahedra) as FEM meshes"

    def __init__(self):
        import strata_freecad  # noqa: F401  (this folder is on sys.path)

        self.__class__.Icon = os.path.join(
            os.path.dirname(strata_freecad.__file__), "Resources", "strata_mesh.svg")

    def Initialize(self):
        import strata_freecad_gui  # noqa: F401  (registers Strata_HybridMesh)

        self.appendToolbar("Strata", ["Strata_HybridMesh"])
        self.appendMenu("Strata", ["Strata_HybridMesh"])

    def GetClassName(self):
        return "Gui::PythonWorkbench"


Gui.addWorkbench(StrataWorkbench())  # noqa: F821
