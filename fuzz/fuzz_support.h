#pragma once
/// \file
/// What the fuzz targets share: the input read front to back, the node format of the decoded
/// meshes (fuzz_surface.cpp's soup, fuzz_writers.cpp's volume mesh), the oracles' failure and a
/// scratch directory for the targets that go through files.

#include <strata/core/surface_mesh.h>
#include <strata/core/types.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace strata::fuzz {

/// The fuzzer's bytes, read front to back; past the end every read fails.
class Bytes {
public:
    Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    bool byte(std::uint8_t& out) {
        if (pos_ >= size_) return false;
        out = data_[pos_++];
        return true;
    }
    bool raw_double(double& out) {
        if (size_ - pos_ < sizeof out) return false;
        std::memcpy(&out, data_ + pos_, sizeof out);
        pos_ += sizeof out;
        return true;
    }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
};

/// Coordinates a real file may hold or a bug may make: non-finite, extreme, tiny, signed zero.
inline constexpr std::array<double, 16> kSpecial = {std::numeric_limits<double>::quiet_NaN(),
                                                    std::numeric_limits<double>::infinity(),
                                                    -std::numeric_limits<double>::infinity(),
                                                    1e308,
                                                    -1e308,
                                                    std::numeric_limits<double>::max(),
                                                    std::numeric_limits<double>::denorm_min(),
                                                    1e-300,
                                                    1e300,
                                                    1e15,
                                                    -1e15,
                                                    1e-15,
                                                    -0.0,
                                                    0.1,
                                                    3.0000000001,
                                                    9007199254740993.0};

/// Grid point of the 4 × 4 × 4 lattice: bits 0-1 x, 2-3 y, 4-5 z.
inline Vec3 grid(unsigned g) {
    return Vec3(static_cast<double>(g & 3u), static_cast<double>((g >> 2) & 3u), static_cast<double>((g >> 4) & 3u));
}

/// One node of a decoded mesh, from a byte g and what follows it:
///   g < 0xC0          grid point g & 0x3F (x = bits 0-1, y = 2-3, z = 4-5), moved by g >> 6:
///                     0 not, 1 by 1e-10 in x (merges), 2 by 0.5 in z
///   0xC0 <= g < 0xF0  grid point of the next byte & 0x3F with coordinate (g - 0xC0) / 16
///                     replaced by kSpecial[(g - 0xC0) % 16]
///   0xF0 <= g         three raw doubles from the next 24 bytes
/// False if the input ends first.
inline bool decode_point(Bytes& in, Vec3& x) {
    std::uint8_t g = 0, h = 0;
    if (!in.byte(g)) return false;
    if (g < 0xC0) {
        x = grid(g & 0x3Fu);
        if (g >> 6 == 1) x.x() += 1e-10;
        if (g >> 6 == 2) x.z() += 0.5;
        return true;
    }
    if (g < 0xF0) {
        if (!in.byte(h)) return false;
        x = grid(h & 0x3Fu);
        x[(g - 0xC0) / 16] = kSpecial[(g - 0xC0u) % 16];
        return true;
    }
    return in.raw_double(x.x()) && in.raw_double(x.y()) && in.raw_double(x.z());
}

/// A count byte N and N nodes (decode_point) appended to \p points, fewer where the input ends
/// first. False if there is no count byte.
inline bool decode_points(Bytes& in, std::vector<Vec3>& points) {
    std::uint8_t count = 0;
    if (!in.byte(count)) return false;
    for (unsigned i = 0; i < count; ++i) {
        Vec3 x;
        if (!decode_point(in, x)) break;
        points.push_back(x);
    }
    return true;
}

/// \p k node ids into \p v, a byte each: as they are with \p raw (or no nodes, \p n = 0), else
/// modulo \p n. False if the input ends first.
inline bool decode_ids(Bytes& in, int k, bool raw, Index n, Index* v) {
    for (int i = 0; i < k; ++i) {
        std::uint8_t id = 0;
        if (!in.byte(id)) return false;
        v[i] = raw || n == 0 ? Index{id} : Index{id} % n;
    }
    return true;
}

/// Break \p m's face arrays the way a caller's own code might (\p which: 0 the CSR offsets from
/// position \p at on shifted by \p value - 128, all but the last; 1 a patch entry too few or too
/// many; 2 a negative node id at \p at).
inline void corrupt_faces(SurfaceMesh& m, unsigned which, std::size_t at, std::uint8_t value) {
    switch (which) {
        case 0:
            for (std::size_t i = at % m.face_offsets.size(); i + 1 < m.face_offsets.size(); ++i)
                m.face_offsets[i] += Index{value} - 128;
            break;
        case 1:
            m.face_patch.resize(value % (m.face_patch.size() + 2));
            break;
        default:
            if (!m.face_nodes.empty()) m.face_nodes[at % m.face_nodes.size()] = Index{value} - 256;
            break;
    }
}

/// An oracle: a property every result must have. Its failure is a finding, so it is not a
/// strata::Error (those are caught as the expected answer to bad input).
inline void require(bool ok, const std::string& what) {
    if (!ok) throw std::logic_error("fuzz oracle failed: " + what);
}

/// \p name in a directory of this process's own (made on the first call under /dev/shm, or the
/// system's temporary directory without it, and removed at exit): where the targets that go
/// through files write their input or output.
std::string scratch_path(const std::string& name);

}  // namespace strata::fuzz
