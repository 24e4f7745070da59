#pragma once
// A flag that names an enum's value parses straight into the enum through its
// name table (lightcuts/name_table.h): the name becomes the value CLI11 reads
// into the enum, and a wrong name is refused with the list of names.
// (CLI::CheckedTransformer over the same map would print a uint8_t enum's
// values as characters in its message and also accept the bare numbers.)
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <type_traits>

#include "lightcuts/name_table.h"

namespace lc::client {

template <typename Enum, size_t N>
CLI::Validator checked_names(const NameTable<Enum, N>& table) {
    auto to_value = [table](std::string& input) -> std::string {
        const std::optional<Enum> value = value_in(table, input);
        if (!value) return "'" + input + "' is not one of " + names_in(table);
        // CLI11 reads an enum as its underlying number.
        input = std::to_string(static_cast<unsigned>(static_cast<std::underlying_type_t<Enum>>(*value)));
        return std::string();
    };
    return CLI::Validator(to_value, "{" + names_in(table) + "}");
}

}  // namespace lc::client
