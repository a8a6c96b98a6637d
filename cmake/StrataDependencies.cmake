# Every third-party dependency, found once, as imported targets. All come from Debian
# packages (scripts/setup.sh installs them).

find_package(Eigen3 3.3 REQUIRED CONFIG)
# Threads for the smoothing, normals and validation (libgomp, part of GCC).
find_package(OpenMP REQUIRED COMPONENTS CXX)
# Exact predicates and box intersection (Debian's libcgal-dev, header-only; GMP, MPFR).
find_package(CGAL REQUIRED CONFIG)
# k-d tree for nearest-point queries (Debian's libnanoflann-dev, header-only).
find_package(nanoflann REQUIRED CONFIG)

# A library Debian ships without a CMake config, as an imported target: its header's folder
# and the library to link.
function(strata_header_and_library target prefix header library)
  if(NOT TARGET ${target})
    find_path(${prefix}_INCLUDE_DIR ${header} REQUIRED)
    find_library(${prefix}_LIBRARY ${library} REQUIRED)
    add_library(${target} INTERFACE IMPORTED)
    set_target_properties(${target} PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${${prefix}_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${${prefix}_LIBRARY}")
  endif()
endfunction()

# Gmsh ships no CMake config (PLATFORM.md): header + library.
strata_header_and_library(strata::libgmsh GMSH gmsh.h gmsh)

# TetGen 1.5 (Debian's libtet1.5-dev): the header, and the library's path for dlopen. It is
# not linked: libgmsh exports its own TetGen under the same symbol names (see hybrid/).
if(NOT TARGET strata::tetgen)
  find_path(TETGEN_INCLUDE_DIR tetgen.h REQUIRED)
  find_library(TETGEN_LIBRARY NAMES libtet.so.1.5 tet REQUIRED)
  add_library(strata::tetgen INTERFACE IMPORTED)
  set_target_properties(strata::tetgen PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${TETGEN_INCLUDE_DIR}"
    INTERFACE_COMPILE_DEFINITIONS "STRATA_LIBTET=\"${TETGEN_LIBRARY}\"")
endif()

# CGNS mid-level library (Debian's libcgns-dev, HDF5 inside): the .cgns writer. No CMake config
# in the Debian package: header + library.
strata_header_and_library(strata::cgns CGNS cgnslib.h cgns)
