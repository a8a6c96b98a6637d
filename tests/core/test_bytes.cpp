// Bytes out of a child process and back in (bytes.h): values, vectors and strings round trip in
// order, and a short buffer is an error naming its sender, never a read past its end.
#include <strata/core/bytes.h>

#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace strata {
namespace {

TEST(Bytes, ValuesVectorsAndStringsComeBackInOrder) {
    Bytes out;
    out.put<int>(-7);
    out.put_vector(std::vector<double>{1.5, -2.25, 1e300});
    out.put_string("Gmsh's words");
    out.put_vector(std::vector<std::size_t>{});
    out.put<char>('x');
    Bytes in{out.data, 0, "the child"};
    EXPECT_EQ(in.get<int>(), -7);
    EXPECT_EQ(in.get_vector<double>(), (std::vector<double>{1.5, -2.25, 1e300}));
    EXPECT_EQ(in.get_string(), "Gmsh's words");
    EXPECT_TRUE(in.get_vector<std::size_t>().empty());
    EXPECT_EQ(in.get<char>(), 'x');
    EXPECT_EQ(in.at, in.data.size());
}

TEST(Bytes, ATruncatedBufferIsAnErrorNamingItsSender) {
    Bytes out;
    out.put_vector(std::vector<double>{1.0, 2.0, 3.0});
    out.put_string("four");
    for (std::size_t keep : {std::size_t{0}, std::size_t{5}, std::size_t{8 + 16}, out.data.size() - 1}) {
        Bytes in{std::vector<char>(out.data.begin(), out.data.begin() + static_cast<std::ptrdiff_t>(keep)), 0,
                 "Gmsh's child process"};
        test::expect_error<BackendError>(
            [&] {
                in.get_vector<double>();
                in.get_string();
            },
            {"Gmsh's child process sent a truncated result"});
    }
    // A length no buffer could hold is refused before anything is allocated.
    Bytes huge;
    huge.put<std::uint64_t>(~std::uint64_t{0});
    Bytes in{huge.data, 0, "the child"};
    test::expect_error<BackendError>([&] { in.get_vector<double>(); }, {"the child sent a truncated result"});
}

}  // namespace
}  // namespace strata
