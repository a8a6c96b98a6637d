#pragma once
/// \file
/// An enum's values and their names in one table, for to_string and for parsing user input
/// (case-insensitive) with one error message, whatever the enum.

#include <strata/core/error.h>

#include <array>
#include <cctype>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

namespace strata {

template <class E, std::size_t N>
struct EnumNames {
    std::array<std::pair<E, std::string_view>, N> names;

    /// The name of \p e ("" for a value not in the table).
    constexpr std::string_view name(E e) const {
        for (const auto& [value, text] : names)
            if (value == e) return text;
        return {};
    }

    /// The value named \p text in any case; InputError "<what> '<text>': use a, b or c" otherwise
    /// (\p what names the parameter, e.g. "FarfieldParams::shape").
    E parse(std::string_view text, std::string_view what) const {
        std::string lower(text);
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        for (const auto& [value, name] : names)
            if (lower == name) return value;
        std::string choices;
        for (std::size_t i = 0; i < N; ++i)
            choices += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(names[i].second);
        throw InputError(std::string(what) + " '" + std::string(text) + "': use " + choices);
    }
};

}  // namespace strata
