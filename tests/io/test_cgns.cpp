// write_cgns: a box of every cell type, with patches of triangles, of quadrilaterals and of
// both, written and read back with the CGNS library's own cg_* calls: the zone's sizes, the
// coordinates, one section per cell type with its cells, the patches' sections and element
// ranges, their boundary conditions (type, range, FaceCenter, family) and the base's families.
// Errors: a missing directory and a malformed mesh throw and leave nothing behind.

#include "io/every_type_box.h"
#include "test_support.h"

#include <strata/core/error.h>
#include <strata/core/validate.h>
#include <strata/io/cgns.h>
#include <strata/io/write_volume.h>

#include <cgnslib.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

using namespace strata;
using strata::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

using test::every_type_box;

#define CG(call) ASSERT_EQ((call), CG_OK) << #call << ": " << cg_get_error()

struct Section {
    CGNS_ENUMT(ElementType_t) type;
    cgsize_t start, end;
    std::vector<cgsize_t> conn;
};

const std::vector<std::string> kPatchNames{"inlet_left wall", "xmax", "symmetry", "outflow", "zmin", "farfield"};
const std::vector<CGNS_ENUMT(BCType_t)> kBcTypes{CGNS_ENUMV(BCWall),          CGNS_ENUMV(BCWall),
                                                 CGNS_ENUMV(BCSymmetryPlane), CGNS_ENUMV(BCTypeUserDefined),
                                                 CGNS_ENUMV(BCWall),          CGNS_ENUMV(BCFarfield)};

/// every_type_box written through write_volume and opened with the CGNS library; each step reads
/// one part back (the sections first: the others check against them).
class WriteCgnsReadBack : public testing::Test {
protected:
    ScratchDir dir{"cgns_read_back"};
    const VolumeMesh m = every_type_box();
    int fn = 0;
    bool open = false;
    char name[64] = {};
    std::map<std::string, Section> sections;
    std::vector<std::string> order;                           // the sections' names as read
    std::map<Index, std::pair<cgsize_t, cgsize_t>> faces_of;  // patch -> (triangles, quads)
    std::vector<std::string> bc_names;                        // the boundary conditions' names as read

    void SetUp() override {
        ASSERT_TRUE(validate_mesh(m).ok());
        ASSERT_GT(m.tets.size(), 0u);
        ASSERT_GT(m.pyramids.size(), 0u);
        ASSERT_GT(m.prisms.size(), 0u);
        ASSERT_GT(m.hexes.size(), 0u);
        const std::string path = dir.file("mesh.cgns");
        write_volume(m, path);  // by extension, through write_volume
        EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"mesh.cgns"});
        CG(cg_open(path.c_str(), CG_MODE_READ, &fn));
        open = true;
        for (Index f = 0; f < m.boundary.num_faces(); ++f)
            (m.boundary.face_size(f) == 3 ? faces_of[m.boundary.face_patch[f]].first
                                          : faces_of[m.boundary.face_patch[f]].second) += 1;
    }
    void TearDown() override {
        if (open) {
            EXPECT_EQ(cg_close(fn), CG_OK) << cg_get_error();
        }
    }

    /// One base of dimensions 3, one unstructured zone of the mesh's nodes and cells.
    void check_zone() {
        int nbases = 0, nzones = 0, cell_dim = 0, phys_dim = 0;
        CG(cg_nbases(fn, &nbases));
        ASSERT_EQ(nbases, 1);
        CG(cg_base_read(fn, 1, name, &cell_dim, &phys_dim));
        EXPECT_EQ(cell_dim, 3);
        EXPECT_EQ(phys_dim, 3);
        CG(cg_nzones(fn, 1, &nzones));
        ASSERT_EQ(nzones, 1);
        CGNS_ENUMT(ZoneType_t) zone_type;
        CG(cg_zone_type(fn, 1, 1, &zone_type));
        EXPECT_EQ(zone_type, CGNS_ENUMV(Unstructured));
        cgsize_t size[3] = {};
        CG(cg_zone_read(fn, 1, 1, name, size));
        EXPECT_EQ(size[0], static_cast<cgsize_t>(m.points.size()));
        EXPECT_EQ(size[1], static_cast<cgsize_t>(m.num_cells()));
    }

    /// Coordinates, exactly.
    void check_coordinates() {
        std::vector<double> x(m.points.size());
        cgsize_t lo = 1, hi = static_cast<cgsize_t>(m.points.size());
        for (int d = 0; d < 3; ++d) {
            const char* coord[] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
            CG(cg_coord_read(fn, 1, 1, coord[d], CGNS_ENUMV(RealDouble), &lo, &hi, x.data()));
            for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(x[i], m.points[i][d]) << coord[d] << " " << i;
        }
    }

    /// Every section, by name, and their order.
    void read_sections() {
        int nsections = 0;
        CG(cg_nsections(fn, 1, 1, &nsections));
        for (int s = 1; s <= nsections; ++s) {
            Section sec;
            int nbndry = 0, parent = 0;
            CG(cg_section_read(fn, 1, 1, s, name, &sec.type, &sec.start, &sec.end, &nbndry, &parent));
            cgsize_t data = 0;
            CG(cg_ElementDataSize(fn, 1, 1, s, &data));
            sec.conn.resize(static_cast<std::size_t>(data));
            CG(cg_elements_read(fn, 1, 1, s, sec.conn.data(), nullptr));
            sections[name] = sec;
            order.push_back(name);
        }
    }

    /// Cells per type, numbered from 1; \p next the element number after them.
    void check_cell_sections(cgsize_t& next) {
        next = 1;
        for (CellType t : kCellTypes) {
            const char* names[] = {"Tetrahedra", "Pyramids", "Prisms", "Hexahedra"};
            const CGNS_ENUMT(ElementType_t)
                types[] = {CGNS_ENUMV(TETRA_4), CGNS_ENUMV(PYRA_5), CGNS_ENUMV(PENTA_6), CGNS_ENUMV(HEXA_8)};
            const Section& sec = sections[names[static_cast<int>(t)]];
            EXPECT_EQ(sec.type, types[static_cast<int>(t)]);
            EXPECT_EQ(sec.start, next);
            EXPECT_EQ(sec.end - sec.start + 1, static_cast<cgsize_t>(m.num_cells(t)));
            // The cells, node for node (1-based, Gmsh's order is CGNS's for linear elements).
            const std::size_t k = static_cast<std::size_t>(cell_corners(t));
            for (std::size_t i = 0; i < m.num_cells(t); ++i)
                for (std::size_t j = 0; j < k; ++j) ASSERT_EQ(sec.conn[i * k + j], m.cell(t, i)[j] + 1);
            next = sec.end + 1;
        }
    }

    /// Patch sections: "<name>" (its triangles, or its quadrilaterals if it has no triangles) and
    /// "<name>_quads" when it has both, in patch order, numbered on from \p next after the cells.
    void check_patch_sections(cgsize_t next) {
        EXPECT_GT(faces_of[2].first, 0);
        EXPECT_GT(faces_of[2].second, 0);  // symmetry (y−): both
        std::vector<std::string> expected{"Tetrahedra", "Pyramids", "Prisms", "Hexahedra"};
        for (Index p = 0; p < 6; ++p) {
            const auto [nt, nq] = faces_of[p];
            const std::string& pn = kPatchNames[static_cast<std::size_t>(p)];
            const Section& sec = sections[pn];
            EXPECT_EQ(sec.start, next) << pn;
            EXPECT_EQ(sec.type, nt > 0 ? CGNS_ENUMV(TRI_3) : CGNS_ENUMV(QUAD_4)) << pn;
            EXPECT_EQ(sec.end - sec.start + 1, nt > 0 ? nt : nq) << pn;
            expected.push_back(pn);
            next = sec.end + 1;
            if (nt > 0 && nq > 0) {
                const Section& quads = sections[pn + "_quads"];
                EXPECT_EQ(quads.type, CGNS_ENUMV(QUAD_4)) << pn;
                EXPECT_EQ(quads.start, next) << pn;
                EXPECT_EQ(quads.end - quads.start + 1, nq) << pn;
                expected.push_back(pn + "_quads");
                next = quads.end + 1;
            }
        }
        EXPECT_EQ(order, expected);
        EXPECT_EQ(next, static_cast<cgsize_t>(m.num_cells() + m.boundary.num_faces()) + 1);
    }

    /// The boundary faces, node for node, in boundary order within each patch.
    void check_boundary_faces() {
        std::map<std::string, std::size_t> read_at;
        for (Index f = 0; f < m.boundary.num_faces(); ++f) {
            const Index p = m.boundary.face_patch[f];
            const std::string& pn = kPatchNames[static_cast<std::size_t>(p)];
            const std::string sn = m.boundary.face_size(f) == 4 && faces_of[p].first > 0 ? pn + "_quads" : pn;
            for (const Index* v = m.boundary.face_begin(f); v != m.boundary.face_end(f); ++v)
                ASSERT_EQ(sections[sn].conn[read_at[sn]++], *v + 1) << sn;
        }
    }

    /// Boundary conditions: one per patch, its type, its element range, FaceCenter, its family.
    void check_boundary_conditions() {
        int nbocos = 0;
        CG(cg_nbocos(fn, 1, 1, &nbocos));
        ASSERT_EQ(nbocos, 6);
        for (int bc = 1; bc <= nbocos; ++bc) {
            CGNS_ENUMT(BCType_t) type;
            CGNS_ENUMT(PointSetType_t) ptset;
            cgsize_t npnts = 0, normal_size = 0;
            int normal_index[3], ndataset = 0;
            CGNS_ENUMT(DataType_t) normal_type;
            CG(cg_boco_info(fn, 1, 1, bc, name, &type, &ptset, &npnts, normal_index, &normal_size, &normal_type,
                            &ndataset));
            bc_names.push_back(name);
            const auto p = static_cast<std::size_t>(bc - 1);
            EXPECT_EQ(name, kPatchNames[p]);
            EXPECT_EQ(type, kBcTypes[p]) << name;
            EXPECT_EQ(ptset, CGNS_ENUMV(PointRange)) << name;
            ASSERT_EQ(npnts, 2);
            cgsize_t range[2];
            CG(cg_boco_read(fn, 1, 1, bc, range, nullptr));
            // The patch's sections, both of them for a patch with triangles and quadrilaterals.
            const Section& first = sections[kPatchNames[p]];
            EXPECT_EQ(range[0], first.start) << name;
            EXPECT_EQ(range[1] - range[0] + 1,
                      faces_of[static_cast<Index>(p)].first + faces_of[static_cast<Index>(p)].second)
                << name;
            CGNS_ENUMT(GridLocation_t) location;
            CG(cg_boco_gridlocation_read(fn, 1, 1, bc, &location));
            EXPECT_EQ(location, CGNS_ENUMV(FaceCenter)) << name;
            CG(cg_goto(fn, 1, "Zone_t", 1, "ZoneBC_t", 1, "BC_t", bc, "end"));
            char family[64] = {};
            CG(cg_famname_read(family));
            EXPECT_STREQ(family, name);
        }
    }

    /// Families at the base, one per patch, carrying the patch's BC type.
    void check_families() {
        int nfamilies = 0;
        CG(cg_nfamilies(fn, 1, &nfamilies));
        ASSERT_EQ(nfamilies, 6);
        for (int f = 1; f <= nfamilies; ++f) {
            int nfambc = 0, ngeo = 0;
            CG(cg_family_read(fn, 1, f, name, &nfambc, &ngeo));
            ASSERT_EQ(nfambc, 1) << name;
            char fambc[64] = {};
            CGNS_ENUMT(BCType_t) type;
            CG(cg_fambc_read(fn, 1, f, 1, fambc, &type));
            const auto at = std::find(bc_names.begin(), bc_names.end(), std::string(name));
            ASSERT_NE(at, bc_names.end()) << name;
            EXPECT_EQ(type, kBcTypes[static_cast<std::size_t>(at - bc_names.begin())]) << name;
        }
    }
};

}  // namespace

TEST_F(WriteCgnsReadBack, WithTheCgnsLibrary) {
    ASSERT_NO_FATAL_FAILURE(check_zone());
    ASSERT_NO_FATAL_FAILURE(check_coordinates());
    ASSERT_NO_FATAL_FAILURE(read_sections());
    cgsize_t next = 1;
    ASSERT_NO_FATAL_FAILURE(check_cell_sections(next));
    check_patch_sections(next);
    ASSERT_NO_FATAL_FAILURE(check_boundary_faces());
    ASSERT_NO_FATAL_FAILURE(check_boundary_conditions());
    ASSERT_NO_FATAL_FAILURE(check_families());
}

TEST(WriteCgns, NamesFitCgns) {
    const std::string long_name(40, 'a');
    const std::vector<std::string> names =
        cgns_names({"wall", "a/b", "", long_name, long_name, "Fluid", " "}, {"Fluid", "ZoneBC"});
    EXPECT_EQ(names, (std::vector<std::string>{"wall", "a_b", "patch_3", std::string(32, 'a'),
                                               std::string(30, 'a') + "_2", "Fluid_2", "patch_7"}));
}

TEST(WriteCgns, BadPathAndMalformedMeshLeaveNothing) {
    ScratchDir dir("cgns_bad");
    const VolumeMesh m = every_type_box();
    test::expect_error<InputError>([&] { write_cgns(m, dir.file("missing/mesh.cgns")); },
                                   {"missing", "does not exist"});
    VolumeMesh bad = m;
    bad.hexes[0][3] = 100000;
    test::expect_error<InputError>([&] { write_cgns(bad, dir.file("mesh.cgns")); }, {"mesh.cgns", "100000"});
    EXPECT_TRUE(test::dir_entries(dir.path()).empty());
}
