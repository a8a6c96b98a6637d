#pragma once
/// \file
/// Strata's exceptions. Every message names the file, entity, face or node concerned and
/// says what to do; the CLI prints what() on one line and exits non-zero.

#include <stdexcept>
#include <string>

namespace strata {

/// Base of every error Strata throws.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The user's input is unusable: missing or unreadable file, bad format, bad option value.
class InputError : public Error {
public:
    using Error::Error;
};

/// The mesh's topology or geometry is invalid: non-manifold edge, degenerate face,
/// non-orientable surface, NaN coordinate, inverted cell.
class TopologyError : public Error {
public:
    using Error::Error;
};

/// A third-party library (Gmsh, OpenCASCADE, TetGen) failed; the message carries its text.
class BackendError : public Error {
public:
    using Error::Error;
};

}  // namespace strata
