// The private TetGen loader (hybrid/src/tetgen_library.h): it loads libtet, redirects its
// crashing error exit, and refuses, with BackendError saying why, whatever it cannot load or
// patch, instead of handing out a TetGen whose failure would crash the process.

#include "tetgen_library.h"

#include <strata/core/error.h>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace strata
