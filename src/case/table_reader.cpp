#include "src/case/table_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mpsolid {

namespace {
bool is_number(const TomlValue& v) {
  return v.is_floating() || v.is_integer();
}
double as_number(const TomlValue& v) {
  return v.is_floating() ? v.as_floating() : static_cast<double>(v.as_integer());
}
std::string detail(const std::string& what) {
  return what.empty() ? "" : " (" + what + ")";
}
// Levenshtein distance: how many single-character edits turn a into b.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string type_name(const TomlValue& v) {
  std::ostringstream s;
  s << v.type();
  return s.str();
}
}  // namespace

std::string origin(const TomlValue& v, const std::string& file) {
  const auto loc = v.location();
  const std::string& name = loc.file_name();
  if (name.rfind("--set", 0) == 0) return name;
  if (name != "unknown file") return fmt::format("{}:{}", name, loc.line());
  // A table made by an override has no location of its own: its entries do.
  if (v.is_table())
    for (const auto& [key, entry] : v.as_table()) {
      const std::string inner = origin(entry, file);
      if (inner != file) return inner;
    }
  return file;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

std::string describe(const TomlValue& v) {
  std::string text = toml::format(v);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

void TableReader::fail(const std::string& key, const std::string& problem) const {
  const auto& entries = table_.as_table();
  const auto it = entries.find(key);
  const std::string where = it != entries.end() ? origin(it->second, file_) : file_;
  throw InputError(fmt::format("{}: {}: {}", where, key_path(key), problem));
}

const TomlValue* TableReader::find(const std::string& key) {
  if (std::find(asked_.begin(), asked_.end(), key) == asked_.end()) asked_.push_back(key);
  const auto& entries = table_.as_table();
  const auto it = entries.find(key);
  return it == entries.end() ? nullptr : &it->second;
}

bool TableReader::has(const std::string& key) {
  return find(key) != nullptr;
}

const TomlValue& TableReader::require(const std::string& key, const std::string& what) {
  const TomlValue* v = find(key);
  if (v) return *v;
  // A key that is here but asked for by no one is likely the missing one, mistyped.
  std::string hint;
  for (const auto& [present, value] : table_.as_table())
    if (std::find(asked_.begin(), asked_.end(), present) == asked_.end() &&
        edit_distance(present, key) <= std::max<std::size_t>(1, key.size() / 3))
      hint += fmt::format("; {} has '{}', which is not a key here: a typo for '{}'?",
                          origin(value, file_), key_path(present), key);
  throw InputError(fmt::format("{}: {} is missing ({}){}", file_, key_path(key), what, hint));
}

double TableReader::number(const TomlValue& v, const std::string& key,
                           const std::string& what) const {
  if (!is_number(v))
    fail(key,
         fmt::format("expected a number{}, got {} ({})", detail(what), describe(v), type_name(v)));
  const double x = as_number(v);
  if (!std::isfinite(x)) fail(key, fmt::format("expected a finite number, got {}", x));
  return x;
}

double TableReader::number(const std::string& key, const std::string& what) {
  return number(require(key, what), key, what);
}

double TableReader::number_or(const std::string& key, double fallback) {
  const TomlValue* v = find(key);
  return v ? number(*v, key) : fallback;
}

std::string TableReader::string(const TomlValue& v, const std::string& key,
                                const std::string& what) const {
  if (!v.is_string())
    fail(key,
         fmt::format("expected a string{}, got {} ({})", detail(what), describe(v), type_name(v)));
  return v.as_string().str;
}

std::string TableReader::string(const std::string& key, const std::string& what) {
  return string(require(key, what), key, what);
}

std::string TableReader::string_or(const std::string& key, const std::string& fallback) {
  const TomlValue* v = find(key);
  return v ? string(*v, key) : fallback;
}

bool TableReader::boolean_or(const std::string& key, bool fallback) {
  const TomlValue* v = find(key);
  if (!v) return fallback;
  if (!v->is_boolean()) fail(key, fmt::format("expected true or false, got {}", describe(*v)));
  return v->as_boolean();
}

std::string TableReader::choice_or(const std::string& key, const std::vector<std::string>& choices,
                                   const std::string& fallback) {
  const std::string value = string_or(key, fallback);
  if (std::find(choices.begin(), choices.end(), value) == choices.end())
    fail(key, fmt::format("unknown value '{}' (allowed: {})", value, join(choices)));
  return value;
}

void TableReader::pair(const std::string& key, const std::string& what, double out[2]) {
  numbers(key, what, out, 2);
}

void TableReader::numbers(const std::string& key, const std::string& what, double* out, int count) {
  const TomlValue& v = require(key, what);
  const auto n = static_cast<std::size_t>(count);
  const bool ok = v.is_array() && v.as_array().size() == n &&
                  std::all_of(v.as_array().begin(), v.as_array().end(),
                              [](const TomlValue& item) { return is_number(item); });
  if (!ok)
    fail(key, fmt::format("expected {} ({}), got {}",
                          count == 2 ? "two numbers [a, b]" : "three numbers [a, b, c]", what,
                          describe(v)));
  for (std::size_t k = 0; k < n; ++k) out[k] = number(v.as_array()[k], key);
}

void TableReader::numbers_or(const std::string& key, const std::string& what, double* out,
                             int count) {
  if (has(key)) numbers(key, what, out, count);
}

void TableReader::pair_or(const std::string& key, const std::string& what, double out[2]) {
  if (has(key)) pair(key, what, out);
}

const TomlValue& TableReader::subtable(const std::string& key, const std::string& what) {
  const TomlValue& v = require(key, what);
  if (!v.is_table()) fail(key, fmt::format("expected a table ({})", what));
  return v;
}

const TomlValue* TableReader::subtable_or_null(const std::string& key) {
  const TomlValue* v = find(key);
  if (v && !v->is_table()) fail(key, "expected a table");
  return v;
}

void TableReader::range_check(const std::string& key, double value, bool ok,
                              const std::string& allowed) {
  if (!ok) fail(key, fmt::format("{} is outside the allowed range {}", value, allowed));
}

void TableReader::finish() const {
  for (const auto& [key, value] : table_.as_table()) {
    if (std::find(asked_.begin(), asked_.end(), key) != asked_.end()) continue;
    throw InputError(fmt::format("{}: {}: unknown key (allowed here: {})", origin(value, file_),
                                 key_path(key), join(asked_)));
  }
}

}  // namespace mpsolid
