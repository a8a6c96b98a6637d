#pragma once
/// \file
/// Local improvement of a tetrahedral fill by its worst cells' scaled Jacobian, after TetGen.
///
/// TetGen's own optimisation (-o/A) works on the largest dihedral angle; the scaled Jacobian,
/// which the validator, the summary and the bounds judge, is lowest on tetrahedra
/// TetGen leaves alone. Each tetrahedron below a bound is offered, best first:
///   - a 2-3 flip across each of its faces shared with another tetrahedron,
///   - the removal of each of its edges whose ring of tetrahedra is closed (3 to 7 of them:
///     the ring polygon re-triangulated, of all its triangulations the one whose worst
///     tetrahedron is best, found by dynamic programming: Shewchuk's edge removal),
///   - moving one of its corners that TetGen added (never a boundary node) to where the worst
///     tetrahedron round it is best (a pattern search);
///   - when the passes of those have done what they can, for a tetrahedron still below whose
///     four corners are all boundary nodes: a new point in a cavity round it (the cavity's
///     tetrahedra replaced by the point joined to the cavity's faces, the point placed where
///     their worst is best, the cavity grown across the face of the worst, up to 12
///     tetrahedra), then up to three more passes.
/// Then each face between two tetrahedra whose OpenFOAM checkMesh skewness is above
/// kTetSkewTarget, worst first, is offered the 2-3 flip across it and the removal of each of
/// its edges; the one whose new faces are least skewed is made if they are less skewed than
/// the face, the fill's boundary faces among them no worse, and the worst tetrahedron made
/// no worse than the worst replaced (up to three passes).
/// A change is made only if the worst of the tetrahedra it creates is better than the worst of
/// those it replaces, so the mesh's worst value never falls and the passes end. The boundary
/// (its nodes and faces) is never changed: the result fills the same region with the same
/// boundary triangles. New tetrahedra are checked by orientation: all positive with the same
/// boundary as the ones they replace means they tile the same region once.
///
/// What it cannot change: a tetrahedron on a boundary face so poor that no apex makes it good
/// (a needle of the layer top); and it sees only the fill, not the layers' own tetrahedra
/// (those closing a layer step). Only a better front lifts those.

#include <strata/core/progress.h>
#include <strata/core/solver_checks.h>
#include <strata/hybrid/tetgen_fill.h>

namespace strata {

/// The skewness pass works on faces between two tetrahedra above this: checkMesh's bound with
/// a margin for the faces on the fill's boundary, whose cell across (a layer cell) it does not see.
inline constexpr double kTetSkewTarget = 0.9 * kFoamSkewness;

struct TetImproveParams {
    /// Work on tetrahedra whose scaled Jacobian is below this (0: off). Tetrahedra above it
    /// change only as neighbours of one below.
    double below = 0.2;
    /// The work allowed, in tetrahedron qualities computed: evaluations_floor plus
    /// evaluations_per_tet per tetrahedron of the fill; the passes stop when it is spent
    /// (TetImproveReport::budget_reached). The README's cases stay within it (the M6 of the main
    /// job needs 57 per tetrahedron, the mixed M6 98, a small fill such as the notched box's
    /// over 200 but a few million in all); the half M6 of hexahedra on 1:60 quads, 68,000 of
    /// its 434,000 tetrahedra below 0.2, took 1,600 per tetrahedron (35 s) and ended with more
    /// below the bound than it started with.
    double evaluations_per_tet = 200.0;
    double evaluations_floor = 5e7;
    int max_passes = 10;  ///< passes over the tetrahedra below the bound; each pass stops early when nothing changed
    /// Threads for the scan of the faces' skewness (0: all; the result is the same for any);
    /// build_hybrid_mesh sets it from HybridParams::threads. The changes are made on one.
    int threads = 0;
};

struct TetImproveReport {
    double below = 0.0;                         ///< the bound worked to (TetImproveParams::below)
    Index flips = 0;                            ///< 2-3 flips made
    Index edge_removals = 0;                    ///< edges removed (a ring of n tetrahedra becomes 2n - 4)
    Index moved_nodes = 0;                      ///< moves of interior nodes (a node may move in several passes)
    Index inserted_nodes = 0;                   ///< points inserted into a cavity round a tetrahedron
    Index skew_changes = 0;                     ///< flips and edge removals made for a face's skewness
    Index skewed_before = 0, skewed_after = 0;  ///< faces between two tetrahedra above checkMesh's skewness bound (4)
    Index below_before = 0, below_after = 0;    ///< tetrahedra below TetImproveParams::below
    double min_before = 1.0, min_after = 1.0;   ///< the smallest scaled Jacobian
    int passes = 0;
    bool budget_reached = false;  ///< stopped at TetImproveParams::evaluations_per_tet
    double seconds = 0.0;         ///< wall-clock time taken
};

/// Throws InputError for a bound outside [0, 1) or fewer than one pass (before any work: the
/// pipeline checks its parameters first).
void check_tet_improve_params(const TetImproveParams& params);

/// Improve \p fill in place: its tetrahedra change, its points from \p num_fixed on (the
/// points TetGen added) may move and points may be added after them; the first \p num_fixed
/// points (the boundary's) never move, nor does any point on a face of only one tetrahedron.
/// Deterministic: the changes are made on one thread in a fixed order, the skewness scan's
/// threads only read. Throws InputError as check_tet_improve_params does, and for \p num_fixed
/// outside the points.
TetImproveReport improve_tets(TetFill& fill, Index num_fixed, const TetImproveParams& params = {},
                              Progress* progress = nullptr);

}  // namespace strata
