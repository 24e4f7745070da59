#pragma once
// One table of {name, value} per enum that a user names (a flag, a script
// command, a stats field): the names are written once, in the table next to
// the enum, and both directions read it. Adding a value adds one entry.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace lc {

template <typename Enum>
struct NamedValue {
    const char* name;  // a literal, so callers may keep the pointer
    Enum value;
};

template <typename Enum, size_t N>
using NameTable = std::array<NamedValue<Enum>, N>;

// Where the value stands in the table (a list's index), or N.
template <typename Enum, size_t N>
constexpr size_t index_in(const NameTable<Enum, N>& table, Enum value) {
    for (size_t i = 0; i < N; ++i) {
        if (table[i].value == value) return i;
    }
    return N;
}

// The names in the table's order, for a list to pick from.
template <typename Enum, size_t N>
constexpr std::array<const char*, N> names_of(const NameTable<Enum, N>& table) {
    std::array<const char*, N> names{};
    for (size_t i = 0; i < N; ++i) names[i] = table[i].name;
    return names;
}

// The value's name, or "unknown" for a value the table lacks.
template <typename Enum, size_t N>
constexpr const char* name_in(const NameTable<Enum, N>& table, Enum value) {
    for (const NamedValue<Enum>& entry : table) {
        if (entry.value == value) return entry.name;
    }
    return "unknown";
}

template <typename Enum, size_t N>
constexpr std::optional<Enum> value_in(const NameTable<Enum, N>& table, std::string_view name) {
    for (const NamedValue<Enum>& entry : table) {
        if (name == entry.name) return entry.value;
    }
    return std::nullopt;
}

// "a, b, c": the names for an error message or a help text.
template <typename Enum, size_t N>
std::string names_in(const NameTable<Enum, N>& table) {
    std::string text;
    for (size_t i = 0; i < N; ++i) {
        if (i > 0) text += ", ";
        text += table[i].name;
    }
    return text;
}

}  // namespace lc
