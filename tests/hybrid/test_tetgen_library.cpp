// The private TetGen loader (hybrid/src/tetgen_library.h): it loads libtet, redirects its
// crashing error exit, and refuses, with BackendError saying why, whatever it cannot load or
// patch, instead of handing out a TetGen whose failure would crash the process.

#include "tetgen_library.h"

#include <strata/core/error.h>
#include <strata/core/progress.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace strata {
namespace {

using test::expect_error;

TEST(TetgenLibrary, LoadsAndRedirectsTheErrorExit) {
    const tetgen::Library lib = tetgen::load();
    EXPECT_NE(lib.tetrahedralize, nullptr);
    EXPECT_GE(lib.replaced_slots, 1);
    EXPECT_GE(lib.assert_slots, 1);  // Debian's libtet keeps its assert()s: each throws instead of aborting
    // Loading again (the library is already in the process, its slot already patched) works.
    EXPECT_GE(tetgen::load().replaced_slots, 1);
}

TEST(TetgenLibrary, MissingTetrahedralizeIsBackendError) {
    tetgen::Symbols s;
    s.tetrahedralize = "_Z20no_such_tetrahedralizev";
    expect_error<BackendError>([&] { tetgen::load(s); }, {"_Z20no_such_tetrahedralizev"});
}

TEST(TetgenLibrary, UnpatchableErrorExitIsBackendError) {
    // Without the redirect a TetGen failure would free its mesh twice and crash: refused.
    tetgen::Symbols s;
    s.terminate = "_Z21no_such_terminatetetgenv";
    expect_error<BackendError>([&] { tetgen::load(s); }, {"would crash"});
}

TEST(TetgenLibrary, FailureMessagesSayWhatToDo) {
    for (int code : {1, 2, 3, 4, 5, 10}) {
        const std::string m = tetgen::failure_message(code);
        EXPECT_NE(m.find("code " + std::to_string(code)), std::string::npos) << m;
        EXPECT_NE(m.find(": "), std::string::npos) << m;
        EXPECT_EQ(m.find("strata check"), std::string::npos) << m;  // no such command
    }
    EXPECT_NE(tetgen::failure_message(3).find("intersects itself"), std::string::npos);
}

/// \p triangles as \p io's facets, one polygon each (new[]ed: tetgenio delete[]s them).
void set_triangles(tetgenio& io, const std::vector<std::array<int, 3>>& triangles) {
    io.numberoffacets = static_cast<int>(triangles.size());
    io.facetlist = new tetgenio::facet[triangles.size()];
    for (std::size_t f = 0; f < triangles.size(); ++f) {
        tetgenio::facet& fa = io.facetlist[f];
        tetgenio::init(&fa);
        fa.polygonlist = new tetgenio::polygon[1];
        tetgenio::init(&fa.polygonlist[0]);
        fa.numberofpolygons = 1;
        fa.polygonlist[0].vertexlist = new int[3];
        fa.polygonlist[0].numberofvertices = 3;
        for (int k = 0; k < 3; ++k) fa.polygonlist[0].vertexlist[k] = triangles[f][static_cast<std::size_t>(k)];
    }
}

/// tests/data/tetgen_internal_check.txt as TetGen's input (points, one triangle per facet).
void read_plc(const std::string& path, tetgenio& io) {
    std::ifstream in(path);
    ASSERT_TRUE(in) << path;
    std::string line, word;
    while (std::getline(in, line) && (line.empty() || line[0] == '#')) {
    }
    std::istringstream head(line);
    int n = 0;
    head >> word >> n;
    ASSERT_EQ(word, "points");
    io.firstnumber = 0;
    io.numberofpoints = n;
    io.pointlist = new REAL[3 * static_cast<std::size_t>(n)];
    for (int i = 0; i < 3 * n; ++i) in >> io.pointlist[i];
    int m = 0;
    in >> word >> m;
    ASSERT_EQ(word, "faces");
    std::vector<std::array<int, 3>> triangles(static_cast<std::size_t>(m));
    for (std::array<int, 3>& t : triangles) in >> t[0] >> t[1] >> t[2];
    ASSERT_TRUE(in) << path;
    set_triangles(io, triangles);
}

TEST(TetgenLibrary, InternalCheckIsLocatedAtTheFaceBeingRecovered) {
    // TetGen stops on an assert() while recovering a boundary face: run() says so as
    // LocalFailure, and its run repeated with its trace names that face.
    tetgenio in;
    read_plc(test::test_data("tetgen_internal_check.txt"), in);
    ASSERT_EQ(in.numberofpoints, 919);
    const std::string switches = "pYzQc";
    {
        tetgenio out;
        expect_error<tetgen::LocalFailure>([&] { tetgen::run(switches, in, out, nullptr); },
                                           {"internal checks", "scount == 1"});
    }
    testing::internal::CaptureStdout();
    std::vector<int> ids = tetgen::locate_failure(switches, in, nullptr);
    const std::string printed = testing::internal::GetCapturedStdout();
    EXPECT_EQ(printed, "");  // its trace is read, not printed
    // The face (786, 785, x) it was recovering when it gave up and added Steiner points.
    ASSERT_EQ(ids.size(), 3u);
    EXPECT_NE(std::find(ids.begin(), ids.end(), 785), ids.end());
    EXPECT_NE(std::find(ids.begin(), ids.end(), 786), ids.end());
    for (const int id : ids) EXPECT_LT(id, in.numberofpoints);
    // The library still works afterwards, and prints nothing with Q.
    tetgenio box, out;
    box.firstnumber = 0;
    box.numberofpoints = 8;
    box.pointlist = new REAL[24];
    for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 3; ++k) box.pointlist[3 * i + k] = (i >> k) & 1;
    testing::internal::CaptureStdout();
    tetgen::run("zQ", box, out, nullptr);
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
    EXPECT_GE(out.numberoftetrahedra, 5);
    // A run that does not fail locates nothing.
    EXPECT_TRUE(tetgen::locate_failure("zQ", box, nullptr).empty());
}

TEST(TetgenLibrary, CrashIsAnErrorAndLocated) {
    // TetGen dies of a SIGSEGV on this front (removing a Steiner point from a face it could not
    // recover): run in a child process, that is an error here, the process goes on, and the
    // traced run (which crashes too) still says where it was.
    tetgenio in;
    read_plc(test::test_data("tetgen_crash.txt"), in);
    ASSERT_EQ(in.numberofpoints, 667);
    {
        tetgenio out;
        expect_error<tetgen::LocalFailure>([&] { tetgen::run("pYzQc", in, out, nullptr); },
                                           {"TetGen crashed (signal 11", "remesh"});
    }
    const std::vector<int> ids = tetgen::locate_failure("pYzQc", in, nullptr);
    ASSERT_GE(ids.size(), 2u);
    for (const int id : ids) EXPECT_TRUE(id >= 0 && id < in.numberofpoints) << id;
}

/// A unit cube's boundary as 12 triangles (points 0-7), and if \p inner a triangle lying in its
/// top face (points 8-10).
void cube_plc(tetgenio& in, bool inner) {
    const double p[11][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},     {0, 1, 0},     {0, 0, 1},    {1, 0, 1},
                             {1, 1, 1}, {0, 1, 1}, {0.2, 0.2, 1}, {0.8, 0.2, 1}, {0.2, 0.8, 1}};
    const int t[13][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4}, {1, 2, 6},
                          {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}, {8, 9, 10}};
    in.firstnumber = 0;
    in.numberofpoints = inner ? 11 : 8;
    in.pointlist = new REAL[3 * in.numberofpoints];
    for (int i = 0; i < in.numberofpoints; ++i)
        for (int k = 0; k < 3; ++k) in.pointlist[3 * i + k] = p[i][k];
    std::vector<std::array<int, 3>> triangles;
    for (int f = 0; f < (inner ? 13 : 12); ++f) triangles.push_back({t[f][0], t[f][1], t[f][2]});
    set_triangles(in, triangles);
}

/// Asks to stop once polled \p after times.
class StopAfter : public Progress {
public:
    explicit StopAfter(int after) : left_(after) {}
    void report(std::string_view, double) override {}
    bool cancelled() const override { return --left_ < 0; }

private:
    mutable int left_;
};

TEST(TetgenLibrary, CancelStopsTetGen) {
    // A unit cube filled with tetrahedra of volume at most 1e-7 (millions: many seconds): asked
    // to stop at its third poll (0.2-0.3 s in), TetGen's child is killed and run() throws
    // Cancelled instead of finishing.
    tetgenio in;
    cube_plc(in, false);
    tetgenio out;
    StopAfter stop(2);
    EXPECT_THROW(tetgen::run("pzQqa1e-7", in, out, nullptr, &stop), Cancelled);
    EXPECT_EQ(out.numberoftetrahedra, 0);
    // Afterwards TetGen runs as before.
    tetgenio again;
    tetgen::run("pzQ", in, again, nullptr);
    EXPECT_GE(again.numberoftetrahedra, 5);
}

TEST(TetgenLibrary, SelfIntersectionIsLocated) {
    // A unit cube's boundary and a triangle lying in its top face: TetGen finds them crossing
    // (code 3) while recovering the top face's diagonal, and its trace names that edge.
    tetgenio in;
    cube_plc(in, true);
    {
        tetgenio out;
        expect_error<tetgen::LocalFailure>([&] { tetgen::run("pYzQ", in, out, nullptr); },
                                           {"intersects itself", "code 3"});
    }
    testing::internal::CaptureStdout();
    const std::vector<int> ids = tetgen::locate_failure("pYzQ", in, nullptr);
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
    ASSERT_GE(ids.size(), 2u);
    for (const int id : ids) EXPECT_TRUE(id >= 4 && id <= 10) << id;  // the top face's or the triangle's
}

}  // namespace
}  // namespace strata
