#pragma once
/// \file
/// The one index type and sentinel used everywhere in Strata, and the point type.

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products on Vec3
#include <cstdint>
#include <vector>

namespace strata {

#ifdef STRATA_INDEX64
using Index = std::int64_t;
#else
/// Index of a node, face or cell. 32-bit by default (STRATA_INDEX64 switches to 64-bit).
using Index = std::int32_t;
#endif

/// "No such entity" (a missing diagonal, an open side of a ring, ...).
inline constexpr Index kNone = -1;

/// A point or vector in model units.
using Vec3 = Eigen::Vector3d;

/// Compressed sparse rows: row i is values[offsets[i] .. offsets[i+1]).
struct Csr {
    std::vector<Index> offsets{0};  ///< #rows + 1
    std::vector<Index> values;      ///< offsets.back() entries

    Index rows() const { return static_cast<Index>(offsets.size()) - 1; }
    Index row_size(Index i) const { return offsets[i + 1] - offsets[i]; }
    const Index* row_begin(Index i) const { return values.data() + offsets[i]; }
    const Index* row_end(Index i) const { return values.data() + offsets[i + 1]; }
};

/// Row r lists, ascending, the ids i with key[i] == r (a counting sort; keys kNone are left
/// out): faces by patch, nodes by owner, ... \p rows is the number of distinct keys.
inline Csr group_by_key(const std::vector<Index>& key, std::size_t rows) {
    Csr out;
    out.offsets.assign(rows + 1, 0);
    for (Index k : key)
        if (k != kNone) ++out.offsets[static_cast<std::size_t>(k) + 1];
    for (std::size_t r = 0; r < rows; ++r) out.offsets[r + 1] += out.offsets[r];
    out.values.resize(static_cast<std::size_t>(out.offsets.back()));
    std::vector<Index> fill(out.offsets.begin(), out.offsets.end() - 1);
    for (std::size_t i = 0; i < key.size(); ++i)
        if (key[i] != kNone)
            out.values[static_cast<std::size_t>(fill[static_cast<std::size_t>(key[i])]++)] = static_cast<Index>(i);
    return out;
}

}  // namespace strata
