#pragma once
/// \file
/// Disjoint sets over 0..n-1 with path halving; a set's representative is its lowest member,
/// so the result does not depend on the order of the unions.

#include <strata/core/types.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace strata {

struct UnionFind {
    std::vector<Index> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), Index{0}); }
    Index find(Index x) {
        while (parent[static_cast<std::size_t>(x)] != x)
            x = parent[static_cast<std::size_t>(x)] =
                parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
        return x;
    }
    void unite(Index a, Index b) {
        a = find(a), b = find(b);
        if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
};

}  // namespace strata
