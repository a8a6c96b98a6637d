#include <strata/core/cell_quality.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace strata {
namespace {

/// min(j, c), except that a NaN (a corner whose quality cannot be computed, e.g. overflowing
/// coordinates) wins and stays: a cell is never better than its worst corner.
double worse(double j, double c) {
    return std::isnan(j) || (!std::isnan(c) && !(c < j)) ? j : c;
}

}  // namespace

double corner_scaled_jacobian(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 e1 = a - o, e2 = b - o, e3 = c - o;
    const double l = e1.norm() * e2.norm() * e3.norm();
    // NaN or overflowing coordinates: the corner's quality cannot be computed (a finite volume
    // over an infinite l would pass for a flat corner).
    if (!std::isfinite(l)) return std::numeric_limits<double>::quiet_NaN();
    if (!(l > 0.0)) return 0.0;  // a collapsed edge is as bad as an inverted corner
    return e1.cross(e2).dot(e3) / l;
}

namespace {

// The cell measures on any P with p[i] a Vec3 (the mesh's points, or a cell's own corners).

template <class P>
double tet_min(const P& p, const std::array<Index, 4>& v) {
    // Every corner of a tetrahedron sees the same signed volume; only the scaling differs.
    const Vec3 &a = p[v[0]], &b = p[v[1]], &c = p[v[2]], &d = p[v[3]];
    double j = corner_scaled_jacobian(a, b, c, d);
    j = worse(j, corner_scaled_jacobian(b, c, a, d));
    j = worse(j, corner_scaled_jacobian(c, a, b, d));
    return worse(j, corner_scaled_jacobian(d, a, c, b));
}

template <class P>
double pyramid_min(const P& p, const std::array<Index, 5>& v) {
    // Base corners: next base node, previous base node, apex. The apex has four edges; it is
    // measured once per base corner i with its edges to i+1, i and i−1.
    double j = 1.0;
    for (int i = 0; i < 4; ++i)
        j = worse(j, corner_scaled_jacobian(p[v[i]], p[v[(i + 1) % 4]], p[v[(i + 3) % 4]], p[v[4]]));
    for (int i = 0; i < 4; ++i)
        j = worse(j, corner_scaled_jacobian(p[v[4]], p[v[(i + 1) % 4]], p[v[i]], p[v[(i + 3) % 4]]));
    return j;
}

/// Prisms (n = 3) and hexahedra (n = 4): bottom corners 0..n−1 with edges to the next and
/// previous bottom corner and up the column; top corners n..2n−1 the same, seen from above.
template <class P, std::size_t N>
double extruded_min(const P& p, const std::array<Index, N>& v) {
    constexpr int n = static_cast<int>(N) / 2;
    double j = 1.0;
    for (int i = 0; i < n; ++i) {
        const int next = (i + 1) % n, prev = (i + n - 1) % n;
        j = worse(j, corner_scaled_jacobian(p[v[i]], p[v[next]], p[v[prev]], p[v[i + n]]));
        j = worse(j, corner_scaled_jacobian(p[v[i + n]], p[v[prev + n]], p[v[next + n]], p[v[i]]));
    }
    return j;
}

template <std::size_t N>
std::array<Index, N> first(const Index* v) {
    std::array<Index, N> a;
    std::copy(v, v + N, a.begin());
    return a;
}

template <class P>
double cell_min(const P& p, const Index* v, CellType t) {
    switch (t) {
        case CellType::Tet:
            return tet_min(p, first<4>(v));
        case CellType::Pyramid:
            return pyramid_min(p, first<5>(v));
        case CellType::Prism:
            return extruded_min(p, first<6>(v));
        case CellType::Hex:
            return extruded_min(p, first<8>(v));
    }
    return 0.0;
}

}  // namespace

double tet_min_scaled_jacobian(const std::vector<Vec3>& p, const std::array<Index, 4>& v) {
    return tet_min(p, v);
}

double pyramid_min_scaled_jacobian(const std::vector<Vec3>& p, const std::array<Index, 5>& v) {
    return pyramid_min(p, v);
}

double prism_min_scaled_jacobian(const std::vector<Vec3>& p, const std::array<Index, 6>& v) {
    return extruded_min(p, v);
}

double hex_min_scaled_jacobian(const std::vector<Vec3>& p, const std::array<Index, 8>& v) {
    return extruded_min(p, v);
}

double min_scaled_jacobian(const std::vector<Vec3>& p, const Index* v, CellType t) {
    return cell_min(p, v, t);
}

double min_scaled_jacobian(const Vec3* corners, CellType t) {
    static constexpr std::array<Index, 8> kIdentity{0, 1, 2, 3, 4, 5, 6, 7};
    return cell_min(corners, kIdentity.data(), t);
}

double quality_bin_edge(int b) {
    return std::pow(10.0, -kQualityDecades + static_cast<double>(b) / kQualityBinsPerDecade);
}

int quality_bin(double sj) {
    if (!(sj >= quality_bin_edge(0))) return 0;  // NaN too
    // From the log, then corrected against the edges themselves, so a value on an edge lands
    // in the bin above it whatever log10 rounds to.
    int b = 1 + static_cast<int>(std::floor((std::log10(sj) + kQualityDecades) * kQualityBinsPerDecade));
    b = std::clamp(b, 1, kQualityBins - 1);
    while (b > 1 && sj < quality_bin_edge(b - 1)) --b;
    while (b < kQualityBins - 1 && sj >= quality_bin_edge(b)) ++b;
    return b;
}

}  // namespace strata
