#pragma once
/// \file
/// The check of a .msh file's header before Gmsh parses it: Gmsh sizes its arrays from the
/// counts a file claims, so a damaged file claiming billions of nodes ends in std::bad_alloc
/// (or in the machine's swap) instead of an error about the file.

#include <string>

namespace strata {

/// InputError unless \p path (a regular file) starts as a Gmsh MSH file does (its first
/// non-blank byte is `$`: "'x.msh' is not an MSH file: it looks like a PNG image; ..."), and,
/// for MSH 4.1 and 2.x, ASCII or binary, unless the node and element counts of its `$Nodes`
/// and `$Elements` headers fit in its size at the fewest bytes one takes in that encoding
/// (ASCII 4.1: 8 per node, 4 per element; binary 4.1: 24 + the data size per node, twice the
/// data size per element; ASCII 2.x: 8 and 8; binary 2.x: 28 and 8): "'x.msh' claims
/// 3000000000 nodes but the file has only 1234 bytes: it is truncated or damaged; write it
/// again". MSH 4.1 node tags beyond INT_MAX (its $Nodes header's maxNodeTag) are refused too:
/// Gmsh 4.8 crashes reading elements on them. Other versions are left to Gmsh.
void check_msh_counts(const std::string& path);

}  // namespace strata
