#pragma once
/// \file
/// Bytes out of a child process and back in (run_in_child, child_process.h): trivially
/// copyable values, vectors of them and strings, appended in order and read back in the same
/// order. A read past the end is a BackendError naming \p what sent it.

#include <strata/core/error.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace strata {

struct Bytes {
    std::vector<char> data;
    std::size_t at = 0;  ///< the next byte to read
    std::string what;    ///< who sent them, for the error: "TetGen's child process"

    template <class T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        append(&v, sizeof(T));
    }
    template <class T>
    void put_vector(const std::vector<T>& v) {  // its length, then its items
        static_assert(std::is_trivially_copyable_v<T>);
        put<std::uint64_t>(v.size());
        append(v.data(), v.size() * sizeof(T));
    }
    void put_string(const std::string& text) {
        put<std::uint64_t>(text.size());
        append(text.data(), text.size());
    }
    /// \p n bytes from \p in.
    void append(const void* in, std::size_t n) {
        if (n == 0) return;
        const std::size_t end = data.size();
        data.resize(end + n);
        std::memcpy(data.data() + end, in, n);
    }

    template <class T>
    T get() {
        T v{};
        take(&v, sizeof(T));
        return v;
    }
    template <class T>
    std::vector<T> get_vector() {
        const auto n = static_cast<std::size_t>(get<std::uint64_t>());
        if (n > (data.size() - at) / sizeof(T)) truncated();
        std::vector<T> v(n);
        take(v.data(), n * sizeof(T));
        return v;
    }
    std::string get_string() {
        const auto n = static_cast<std::size_t>(get<std::uint64_t>());
        if (n > data.size() - at) truncated();
        std::string text(data.data() + at, n);
        at += n;
        return text;
    }
    /// \p n bytes into \p out.
    void take(void* out, std::size_t n) {
        if (n > data.size() - at) truncated();
        if (n > 0) std::memcpy(out, data.data() + at, n);
        at += n;
    }
    [[noreturn]] void truncated() const { throw BackendError(what + " sent a truncated result"); }
};

}  // namespace strata
