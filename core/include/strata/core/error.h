#pragma once
/// \file
/// Strata's exceptions. Every message names the file, entity, face or node concerned and
/// says what to do; the CLI prints what() on one line and exits non-zero.

#include <strata/core/types.h>

#include <exception>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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

/// A TopologyError at a known place of a surface: the nodes of the faces involved (in the
/// numbering of the surface the throwing stage was given), so that a caller can act there
/// (build_hybrid_mesh lowers the layers at those nodes and tries again).
class LocalTopologyError : public TopologyError {
public:
    LocalTopologyError(const std::string& what, std::vector<Index> nodes, double reached = 0.0)
        : TopologyError(what), nodes_(std::move(nodes)), reached_(reached) {}
    const std::vector<Index>& nodes() const { return nodes_; }
    /// How far the layers got there before it failed (0: not known).
    double reached() const { return reached_; }

private:
    std::vector<Index> nodes_;
    double reached_ = 0.0;
};

/// An output could not be written to the end (disk full, quota, file size limit, I/O error,
/// a directory that is not writable): the message names the file and the cause; the previous
/// output is as it was.
class OutputError : public Error {
public:
    using Error::Error;
};

/// A third-party library (Gmsh, OpenCASCADE, TetGen) failed; the message carries its text.
class BackendError : public Error {
public:
    using Error::Error;
};

/// The text of the exception being handled, whatever it is (a library's std::string or C
/// string too, as Gmsh throws), on one line; "no message" for none or an unknown type. For
/// std::terminate handlers, which are given no exception.
inline std::string current_exception_text() {
    std::string what = "no message";
    if (const std::exception_ptr e = std::current_exception()) {
        try {
            std::rethrow_exception(e);
        } catch (const std::string& text) {
            what = text;
        } catch (const char* text) {
            what = text;
        } catch (const std::exception& x) {
            what = x.what();
        } catch (...) {
        }
    }
    for (char& ch : what)
        if (ch == '\n') ch = ' ';
    return what;
}

}  // namespace strata
