#pragma once
// Buffered text output for the hand-written formats (Cobalt60, OpenFOAM polyMesh): numbers
// formatted with std::to_chars into a 1 MB buffer, one fwrite per MB. Doubles use the shortest
// decimal form that reads back to exactly the same value (as %.17g does, but shorter), so the
// files are exact and depend on nothing but the mesh.

#include <strata/core/error.h>
#include <strata/core/types.h>
#include <strata/io/files.h>

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace strata {

/// A file being written at \p temp on behalf of the output \p target (named in errors).

class BufferedFile {
public:
    BufferedFile(const std::string& temp, const std::string& target) : target_(target) {
        file_ = std::fopen(temp.c_str(), "wb");
        if (!file_) throw OutputError(write_failure(target, errno));
        buf_.resize(kCapacity);
    }
    ~BufferedFile() {
        if (file_) std::fclose(file_);
    }
    BufferedFile(const BufferedFile&) = delete;
    BufferedFile& operator=(const BufferedFile&) = delete;

    void put(char c) {
        reserve(1);
        buf_[n_++] = c;
    }
    void put(std::string_view s) {
        if (s.size() > kCapacity / 2) {  // long text: straight through
            flush();
            write(s.data(), s.size());
            return;
        }
        reserve(s.size());
        std::memcpy(buf_.data() + n_, s.data(), s.size());
        n_ += s.size();
    }
    void put(std::int64_t v) {
        reserve(kMaxNumber);
        n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
    }
    /// Shortest decimal form that reads back to exactly \p v.
    void put(double v) {
        reserve(kMaxNumber);
        n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
    }

    /// \p x's three coordinates as put(double) writes them, a space between each.
    void put_point(const Vec3& x) {
        put(x.x());
        put(' ');
        put(x.y());
        put(' ');
        put(x.z());
    }

    /// Flush, fsync and close; throws OutputError if anything could not be written (disk full,
    /// ...) or did not reach the device.
    void close() {
        flush();
        if (std::fflush(file_) != 0) fail();
        if (::fsync(::fileno(file_)) != 0 && errno != EINVAL && errno != EROFS) fail();
        std::FILE* f = file_;
        file_ = nullptr;
        if (std::fclose(f) != 0) fail();
    }

private:
    static constexpr std::size_t kCapacity = std::size_t{1} << 20;
    static constexpr std::size_t kMaxNumber = 32;  // "-2.2250738585072014e-308" is 24

    void reserve(std::size_t k) {
        if (n_ + k > buf_.size()) flush();
    }
    void flush() {
        write(buf_.data(), n_);
        n_ = 0;
    }
    void write(const char* data, std::size_t size) {
        if (size != 0 && std::fwrite(data, 1, size, file_) != size) fail();
    }
    [[noreturn]] void fail() const { throw OutputError(write_failure(target_, errno)); }

    std::FILE* file_ = nullptr;
    std::string target_;
    std::vector<char> buf_;
    std::size_t n_ = 0;
};

}  // namespace strata
