#pragma once
// Command-line overrides of case keys: --set dotted.key=VALUE. The value is
// read as a TOML value; a bare word that is not TOML becomes a string.
#include <map>
#include <string>
#include <vector>

#include <toml.hpp>

namespace mpsolid {

// Tables keep keys sorted (std::map): deterministic order for ids and output.
using TomlValue = toml::basic_value<toml::discard_comments, std::map, std::vector>;

// Applies each override to `root` (a table), creating tables on the way.
// Throws InputError for a malformed override.
void apply_overrides(TomlValue& root, const std::vector<std::string>& overrides);

}  // namespace mpsolid
