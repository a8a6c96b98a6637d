# Strata's FreeCAD module (freecad/StrataMesher in Strata's repository). FreeCAD runs this file
# at start-up, in freecadcmd too, after putting this folder on sys.path: that is all it takes
# for scripts and the Python console to `import strata_freecad` (strata_freecad.mesh_shape).
# The strata package itself comes from Strata's build tree through the .pth file
# scripts/install_python.sh writes (FreeCAD runs Debian's Python 3.11, which reads it).
# Installed by scripts/install_freecad.sh (a symlink into FreeCAD's Mod folder).
