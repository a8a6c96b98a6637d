#pragma once
/// \file
/// What an input path is before a reader opens it (a file, a pipe, a device) and what its bytes
/// look like, so that a wrong input is refused with its name and what to do rather than failing
/// deep inside a reader (/dev/zero named .stl, a pipe given to Gmsh, a PNG named .iges).

#include <strata/core/error.h>

#include <cstddef>
#include <string>
#include <string_view>

namespace strata {

/// How an input can be read.
enum class InputSource {
    File,    ///< a regular file: its size is known, it can be read again
    Stream,  ///< a FIFO or pipe: read once, to its end, in chunks
};

/// Check \p path as an input before any reader opens it. A character or block device or a
/// socket is refused: InputError "'x.stl' is a device, not a file; give the STL file itself"
/// (a device reports a size that means nothing, and /dev/zero never ends). A FIFO or pipe is
/// Stream and is not opened here (opening one waits for its writer, and a second opening loses
/// what the first read). Anything else goes through check_input_file (missing, a directory,
/// unreadable) and is File.
InputSource check_input_source(const std::string& path);

/// check_input_source for a reader that opens the file by name itself, maybe more than once
/// (Gmsh, OpenCASCADE): a FIFO or pipe is refused too, InputError "'x.msh' is a pipe, not a
/// file: <reader> reads it by name; save it to a file and give that".
void require_regular_input(const std::string& path, std::string_view reader);

/// The whole content of \p path after check_input_source: a regular file in one read of its
/// size, a pipe in chunks to its end. InputError naming the file if it cannot be read or does
/// not fit in memory.
std::string read_input(const std::string& path);

/// Up to \p n first bytes of \p path (a regular file), for a reader's check of what it holds.
std::string read_input_head(const std::string& path, std::size_t n);

/// The error for a reader's std::bad_alloc: "not enough memory to read '<path>' (...)".
InputError out_of_memory(const std::string& path);

/// What \p head, a file's first bytes, looks like, as the end of a sentence about the file:
/// "is empty", "looks like a PNG image" (and other common formats by their signatures: ZIP,
/// PDF, gzip, JPEG, HTML, STEP, IGES, BREP, STL, MSH...), "starts with binary data (bytes 00 4f
/// ...)" or "starts with the text 'abc...'".
std::string describe_content(std::string_view head);

}  // namespace strata
