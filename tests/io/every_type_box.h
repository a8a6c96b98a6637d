#pragma once
// A small mesh of every cell type with named patches of every kind, for the writers' tests.

#include "core/box_mesh.h"

#include <strata/core/volume_mesh.h>

namespace strata::test {

/// Every cell type in a box (the arrangement tests/io/test_write_volume.cpp validates): hexahedra,
/// six pyramids, two prisms in a row, six tetrahedra on top of the prisms. The y− and y+ sides
/// hold the prisms' triangular ends and the other cubes' quadrilaterals. Patches named with a
/// character no CGNS name takes ('/') and a space, of every kind.
inline VolumeMesh every_type_box() {
    BoxMesh box(3, 1, 2, 0.5);
    box.set(1, 0, 0, CubeSplit::Pyramids);
    box.set(2, 0, 0, CubeSplit::Prisms);
    box.set(2, 0, 1, CubeSplit::Kuhn);
    for (int i = 0; i < 2; ++i) box.remove(i, 0, 1);
    VolumeMesh m = box.build();
    m.boundary.patches[0] = {"inlet/left wall", PatchKind::Wall};
    m.boundary.patches[2] = {"symmetry", PatchKind::Symmetry};
    m.boundary.patches[5] = {"farfield", PatchKind::Farfield};
    m.boundary.patches[3] = {"outflow", PatchKind::Other};
    return m;
}

}  // namespace strata::test
