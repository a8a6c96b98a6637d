#pragma once
/// \file
/// The names of an enum's values in one table, for to_string and for parsing user input
/// (case-insensitive) with one error message, whatever the enum. The enum's values must be
/// 0, 1, ..., N − 1 (the default for an enum class without initialisers); name i is value i's.

#include <strata/core/error.h>

#include <array>
#include <cctype>
#include <cstddef>
#include <string>
#include <string_view>

namespace strata {

template <class E, std::size_t N>
struct EnumNames {
    std::array<std::string_view, N> names;

    /// The name of \p e.
    constexpr std::string_view name(E e) const { return names[static_cast<std::size_t>(e)]; }

    /// The value named \p text in any case; InputError "<what> '<text>': use a, b or c" otherwise
    /// (\p what names the parameter, e.g. "FarfieldParams::shape").
    E parse(std::string_view text, std::string_view what) const {
        std::string lower(text);
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        std::string choices;
        for (std::size_t i = 0; i < N; ++i) {
            if (lower == names[i]) return static_cast<E>(i);
            choices += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(names[i]);
        }
        throw InputError(std::string(what) + " '" + std::string(text) + "': use " + choices);
    }
};

}  // namespace strata
