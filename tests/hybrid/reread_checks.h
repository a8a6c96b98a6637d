#pragma once
// Write a hybrid mesh as Cobalt60 and as Gmsh .msh, read both back (the Cobalt60 reader of
// the tests, Gmsh's API) and validate what was read: the round trip every test of a finished
// mesh ends with.

#include <strata/core/validate.h>
#include <strata/io/cobalt.h>
#include <strata/io/write_volume.h>

#include <gtest/gtest.h>

#include "io/cobalt_reader.h"
#include "test_support.h"

#include <algorithm>
#include <string>

namespace strata::test {

/// Write \p m to \p dir as NAME.cgr (+ .bc) and NAME.msh, re-read, validate, compare with \p m.
inline void expect_rereads_valid(const VolumeMesh& m, const ScratchDir& dir, const std::string& name) {
    const ValidationReport orig = validate_mesh(m);
    write_cobalt(m, dir.file(name + ".cgr"));
    const CobaltGrid g = read_cobalt(dir.file(name + ".cgr"));
    EXPECT_EQ(g.ncells, m.num_cells());
    EXPECT_EQ(g.max_nodes_per_face,
              m.num_cells() == static_cast<Index>(m.tets.size()) ? 3 : 4);  // quads unless all tets
    const RebuiltMesh rb = rebuild_mesh(g, read_cobalt_bc(dir.file(name + ".cgr.bc")));
    const ValidationReport rv = validate_mesh(rb.mesh);
    EXPECT_TRUE(rv.ok()) << name << ".cgr: " << (rv.problems.empty() ? "" : rv.problems.front());
    EXPECT_NEAR(rv.cell_volume, orig.cell_volume, 1e-9 * orig.cell_volume);

    write_volume(m, dir.file(name + ".msh"));
    const VolumeMesh back = read_volume_msh(dir.file(name + ".msh"));
    EXPECT_EQ(back.num_cells(), m.num_cells());
    EXPECT_EQ(back.hexes.size(), m.hexes.size());
    EXPECT_EQ(back.prisms.size(), m.prisms.size());
    EXPECT_EQ(back.pyramids.size(), m.pyramids.size());
    EXPECT_EQ(back.tets.size(), m.tets.size());
    EXPECT_EQ(back.boundary.num_faces(), m.boundary.num_faces());
    const ValidationReport bv = validate_mesh(back);
    EXPECT_TRUE(bv.ok()) << name << ".msh: " << (bv.problems.empty() ? "" : bv.problems.front());
    EXPECT_NEAR(bv.cell_volume, orig.cell_volume, 1e-9 * orig.cell_volume);
}

}  // namespace strata::test
