#include "src/case/case_overrides.hpp"

#include <fmt/format.h>

#include <sstream>

#include "src/core/types.hpp"

namespace mpsolid {

namespace {
bool valid_key_part(const std::string& part) {
  if (part.empty()) return false;
  for (char c : part)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
  return true;
}

TomlValue parse_value(const std::string& text, const std::string& origin) {
  std::istringstream in("value = " + text);
  try {
    auto doc = toml::parse<toml::discard_comments, std::map, std::vector>(in, origin);
    return doc.as_table().at("value");
  } catch (const std::exception&) {
    // A bare word (--set model=paper) is a string.
    std::istringstream quoted("value = " + toml::format(TomlValue(text)));
    auto doc = toml::parse<toml::discard_comments, std::map, std::vector>(quoted, origin);
    return doc.as_table().at("value");
  }
}
}  // namespace

void apply_overrides(TomlValue& root, const std::vector<std::string>& overrides) {
  for (const std::string& item : overrides) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw InputError(
          fmt::format("--set '{}': expected KEY=VALUE with a dotted key, e.g. "
                      "--set time.end=0.002",
                      item));
    const std::string key = item.substr(0, eq);
    std::vector<std::string> parts;
    std::size_t from = 0;
    while (true) {
      const auto dot = key.find('.', from);
      parts.push_back(key.substr(from, dot - from));
      if (dot == std::string::npos) break;
      from = dot + 1;
    }
    for (const auto& part : parts)
      if (!valid_key_part(part))
        throw InputError(fmt::format(
            "--set '{}': key '{}' is not a dotted path of names (letters, digits, _ and -)", item,
            key));
    TomlValue* table = &root;
    for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
      auto& entries = table->as_table();
      auto it = entries.find(parts[k]);
      if (it == entries.end()) it = entries.emplace(parts[k], TomlValue::table_type{}).first;
      if (!it->second.is_table())
        throw InputError(fmt::format("--set '{}': '{}' is a value, not a table", item, parts[k]));
      table = &it->second;
    }
    table->as_table()[parts.back()] = parse_value(item.substr(eq + 1), "--set " + item);
  }
}

}  // namespace mpsolid
