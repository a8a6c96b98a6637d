# Every third-party dependency, found once, as imported targets. All come from Debian
# packages (scripts/setup.sh installs them).

find_package(Eigen3 3.3 REQUIRED CONFIG)

# Gmsh ships no CMake config (PLATFORM.md): header + library.
if(NOT TARGET strata::gmsh_api)
  find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
  find_library(GMSH_LIBRARY gmsh REQUIRED)
  add_library(strata::gmsh_api INTERFACE IMPORTED)
  set_target_properties(strata::gmsh_api PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${GMSH_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${GMSH_LIBRARY}")
endif()
