// write_vtu and write_vtm: a box of every cell type with patches of every kind, written through
// write_volume and read back with VTK's own XML readers (tests/io/read_vtk.py, python3-vtk9):
// counts, cell types in VTK's node order (no face of a cell points into it), the cell fields
// equal to what core computes, the blocks named after the patches with their kinds. The same
// bytes on every run and for any thread count; failures leave the previous output as it was.

#include "io/every_type_box.h"
#include "test_support.h"

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/face_match.h>
#include <strata/core/solver_checks.h>
#include <strata/core/validate.h>
#include <strata/io/formats.h>
#include <strata/io/vtk_xml.h>
#include <strata/io/write_volume.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace strata;
using strata::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

/// What read_vtk.py printed: its lines, split at tabs, by their first word.
struct ReadBack {
    int code = -1;
    std::string err;
    std::multimap<std::string, std::vector<std::string>> facts;

    /// The one line of \p key (a test failure and an empty line if there is not exactly one).
    std::vector<std::string> one(const std::string& key) const {
        EXPECT_EQ(facts.count(key), 1u) << key;
        const auto it = facts.find(key);
        return it == facts.end() ? std::vector<std::string>{} : it->second;
    }
    /// The lines of \p key whose second field is \p name.
    std::vector<std::string> named(const std::string& key, const std::string& name) const {
        for (auto [it, end] = facts.equal_range(key); it != end; ++it)
            if (it->second.size() > 1 && it->second[1] == name) return it->second;
        ADD_FAILURE() << "no '" << key << "' line for '" << name << "'";
        return {};
    }
};

ReadBack read_back(const ScratchDir& dir, const std::string& path) {
    const test::CliResult r =
        test::run_program(dir, STRATA_TEST_PYTHON, std::string("'") + STRATA_READ_VTK + "' '" + path + "'");
    ReadBack b{r.code, r.err, {}};
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> fields;
        std::istringstream f(line);
        for (std::string word; std::getline(f, word, '\t');) fields.push_back(word);
        if (!fields.empty()) b.facts.emplace(fields[0], fields);
    }
    return b;
}

/// Fields 2.. of \p line as doubles (read back exactly: %.17g).
std::vector<double> values(const std::vector<std::string>& line, std::size_t first = 2) {
    std::vector<double> v;
    for (std::size_t i = first; i < line.size(); ++i) v.push_back(std::strtod(line[i].c_str(), nullptr));
    return v;
}

/// The volume's block as VTK read it: counts, cell types, node order, and every field exactly.
void expect_volume(const ReadBack& b, const VolumeMesh& m) {
    const std::vector<std::string> d = b.named("dataset", "volume");
    ASSERT_EQ(d.size(), 5u);
    EXPECT_EQ(d[2], "vtkUnstructuredGrid");
    EXPECT_EQ(d[3], std::to_string(m.points.size()));
    EXPECT_EQ(d[4], std::to_string(m.num_cells()));
    std::vector<double> types, jacobian;
    for (const CellType t : kCellTypes)
        for (std::size_t i = 0; i < m.num_cells(t); ++i) {
            types.push_back(t == CellType::Tet ? 10 : t == CellType::Pyramid ? 14 : t == CellType::Prism ? 13 : 12);
            jacobian.push_back(min_scaled_jacobian(m.points, m.cell(t, i), t));
        }
    EXPECT_EQ(values(b.one("types"), 1), types);
    EXPECT_EQ(b.one("inward"), (std::vector<std::string>{"inward", "0"}));  // VTK's node order
    EXPECT_EQ(values(b.named("array", "cell_type")), types);
    EXPECT_EQ(values(b.named("array", "scaled_jacobian")), jacobian);
    const CellSolverFigures foam = cell_solver_figures(m, match_faces(m));
    EXPECT_EQ(values(b.named("array", "non_orthogonality")), foam.non_orthogonality_deg);
    EXPECT_EQ(values(b.named("array", "skewness")), foam.skewness);
    EXPECT_EQ(values(b.named("array", "aspect_ratio")), foam.aspect_ratio);
    if (m.cell_layers.size() == static_cast<std::size_t>(m.num_cells())) {
        EXPECT_EQ(values(b.named("array", "layer")), std::vector<double>(m.cell_layers.begin(), m.cell_layers.end()));
    } else {
        for (auto [it, end] = b.facts.equal_range("array"); it != end; ++it)
            EXPECT_NE(it->second[1], "layer") << "a layer field for a mesh that has none";
    }
}

class VtkXml : public testing::Test {
protected:
    ScratchDir dir{"vtk_xml"};
    const VolumeMesh m = test::every_type_box();
    void SetUp() override {
        ASSERT_TRUE(validate_mesh(m).ok());
        ASSERT_GT(m.tets.size() * m.pyramids.size() * m.prisms.size() * m.hexes.size(), 0u);
    }
};

TEST_F(VtkXml, VtuReadBackWithVtk) {
    write_volume(m, dir.file("mesh.vtu"));
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"mesh.vtu"});
    const ReadBack b = read_back(dir, dir.file("mesh.vtu"));
    ASSERT_EQ(b.code, 0) << "VTK could not read the file (python3-vtk9: scripts/setup.sh installs it)\n" << b.err;
    expect_volume(b, m);
    // Some figures worth seeing: the prisms' and pyramids' faces are not all orthogonal.
    const CellSolverFigures foam = cell_solver_figures(m, match_faces(m));
    double largest = 0.0;
    for (const double a : foam.non_orthogonality_deg) largest = std::max(largest, a);
    EXPECT_GT(largest, 1.0);
    // With each cell's layer, a layer field too.
    VolumeMesh layered = m;
    for (Index c = 0; c < m.num_cells(); ++c) layered.cell_layers.push_back(c % 4);
    write_volume(layered, dir.file("layered.vtu"));
    const ReadBack l = read_back(dir, dir.file("layered.vtu"));
    ASSERT_EQ(l.code, 0) << l.err;
    expect_volume(l, layered);
}

TEST_F(VtkXml, VtmBlocksNamedAfterThePatches) {
    const std::string path = dir.file("mesh.vtm");
    write_volume(m, path);
    EXPECT_EQ(test::dir_entries(dir.path()), (std::vector<std::string>{"mesh.vtm", "mesh_blocks"}));
    EXPECT_EQ(test::dir_entries(dir.file("mesh_blocks")).size(), 1 + m.boundary.patches.size());
    const ReadBack b = read_back(dir, path);
    ASSERT_EQ(b.code, 0) << b.err;
    expect_volume(b, m);
    EXPECT_EQ(b.facts.count("dataset"), 1 + m.boundary.patches.size());
    const SurfaceMesh& s = m.boundary;
    for (std::size_t p = 0; p < s.patches.size(); ++p) {
        const std::string& name = s.patches[p].name;
        std::set<Index> nodes;
        std::size_t faces = 0;
        for (Index f = 0; f < s.num_faces(); ++f)
            if (s.face_patch[static_cast<std::size_t>(f)] == static_cast<Index>(p))
                ++faces, nodes.insert(s.face_begin(f), s.face_end(f));
        EXPECT_EQ(b.named("dataset", name),
                  (std::vector<std::string>{"dataset", name, "vtkPolyData", std::to_string(nodes.size()),
                                            std::to_string(faces)}));
        EXPECT_EQ(b.named("field", name),
                  (std::vector<std::string>{"field", name, "patch_name", name}));  // the first: patch_name
        EXPECT_EQ(values(b.named("patchcells", name)), std::vector<double>(faces, static_cast<double>(p)));
    }
    bool kinds = false;
    for (auto [it, end] = b.facts.equal_range("field"); it != end; ++it)
        if (it->second[1] == "symmetry" && it->second[2] == "patch_kind") kinds = it->second[3] == "symmetry";
    EXPECT_TRUE(kinds);
}

TEST_F(VtkXml, SameBytesEveryRunAndThreadCount) {
    const FaceMatch match = match_faces(m);
    const CellSolverFigures one = cell_solver_figures(m, match, 1), three = cell_solver_figures(m, match, 3);
    EXPECT_EQ(one.non_orthogonality_deg, three.non_orthogonality_deg);
    EXPECT_EQ(one.skewness, three.skewness);
    for (const char* name : {"a.vtm", "b.vtm"}) write_vtm(m, dir.file(name));
    EXPECT_EQ(test::slurp(dir.file("a.vtm")), [&] {
        std::string b = test::slurp(dir.file("b.vtm"));
        for (std::size_t at; (at = b.find("b_blocks")) != std::string::npos;) b.replace(at, 1, "a");
        return b;
    }());
    for (const auto& e : fs::directory_iterator(dir.file("a_blocks")))
        EXPECT_EQ(test::slurp(e.path()), test::slurp(dir.file("b_blocks/" + e.path().filename().string())))
            << e.path();
}

TEST_F(VtkXml, FailuresLeaveThePreviousOutput) {
    const std::string path = dir.file("mesh.vtm");
    test::expect_error<InputError>([&] { write_volume(m, dir.file("missing/mesh.vtu")); }, {"does not exist"});
    write_volume(m, path);
    const std::string before = test::slurp(dir.file("mesh_blocks/volume.vtu"));
    VolumeMesh bad = m;
    bad.tets[0][0] = 100000;
    test::expect_error<InputError>([&] { write_volume(bad, path); }, {"mesh.vtm", "100000"});
    EXPECT_EQ(test::dir_entries(dir.path()), (std::vector<std::string>{"mesh.vtm", "mesh_blocks"}));
    EXPECT_EQ(test::slurp(dir.file("mesh_blocks/volume.vtu")), before);
    // A block left from an earlier mesh goes with the directory it was in.
    { std::ofstream(dir.file("mesh_blocks/9_old.vtp")) << "old"; }
    write_volume(m, path);
    EXPECT_FALSE(fs::exists(dir.file("mesh_blocks/9_old.vtp")));
    // Cancelled half-way: nothing moves.
    test::CancelAt cancel(0.5);
    EXPECT_THROW(write_volume(m, dir.file("other.vtm"), {}, &cancel), Cancelled);
    EXPECT_EQ(test::dir_entries(dir.path()), (std::vector<std::string>{"mesh.vtm", "mesh_blocks"}));
    // A blocks' directory holding anything but blocks is refused, not replaced.
    fs::create_directory(dir.file("data_blocks"));
    { std::ofstream(dir.file("data_blocks/notes.txt")) << "mine"; }
    test::expect_error<InputError>([&] { check_volume_output(dir.file("data.vtm")); },
                                   {"data_blocks", "notes.txt", "another name"});
    test::expect_error<InputError>([&] { write_volume(m, dir.file("data.vtm")); }, {"notes.txt"});
    EXPECT_EQ(test::slurp(dir.file("data_blocks/notes.txt")), "mine");
    EXPECT_EQ(volume_output_files("out/w.vtm"), (std::vector<std::string>{"out/w.vtm", "out/w_blocks"}));
}

}  // namespace
