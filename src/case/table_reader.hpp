#pragma once
// Reading one TOML table of a case: typed values with the file, line, key and
// allowed range in every message, and the keys that were asked for remembered
// so that finish() can refuse any other (a typo is never ignored).
#include <string>
#include <vector>

#include "src/case/case_overrides.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

// Where a value came from: "file:line" or "--set key=value".
std::string origin(const TomlValue& v, const std::string& file);
// The items separated by ", ".
std::string join(const std::vector<std::string>& items);
// A value as TOML text, for messages.
std::string describe(const TomlValue& v);

class TableReader {
 public:
  TableReader(const TomlValue& table, std::string path, const std::string& file)
      : table_(table), path_(std::move(path)), file_(file) {}

  // The dotted key of an entry of this table ("bodies.rod.x").
  std::string key_path(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

  // The entry or nullptr; every key asked for here is allowed in the table.
  const TomlValue* find(const std::string& key);
  bool has(const std::string& key);
  const TomlValue& require(const std::string& key, const std::string& what);

  double number(const TomlValue& v, const std::string& key, const std::string& what = "") const;
  double number(const std::string& key, const std::string& what);
  double number_or(const std::string& key, double fallback);
  std::string string(const TomlValue& v, const std::string& key,
                     const std::string& what = "") const;
  std::string string(const std::string& key, const std::string& what);
  std::string string_or(const std::string& key, const std::string& fallback);
  bool boolean_or(const std::string& key, bool fallback);
  // One of `choices`, or `fallback` when absent.
  std::string choice_or(const std::string& key, const std::vector<std::string>& choices,
                        const std::string& fallback);
  // [a, b] with two numbers; pair_or leaves `out` as it is when absent.
  void pair(const std::string& key, const std::string& what, double out[2]);
  void pair_or(const std::string& key, const std::string& what, double out[2]);
  // [a, b] or [a, b, c]: `count` (2 or 3) numbers, one per axis of the case's
  // dimension; numbers_or leaves `out` as it is when absent.
  void numbers(const std::string& key, const std::string& what, double* out, int count);
  void numbers_or(const std::string& key, const std::string& what, double* out, int count);
  const TomlValue& subtable(const std::string& key, const std::string& what);
  const TomlValue* subtable_or_null(const std::string& key);

  void range_check(const std::string& key, double value, bool ok, const std::string& allowed);
  // Refuses every key that was not asked for, naming those that were.
  void finish() const;

  const std::string& file() const { return file_; }

 private:
  const TomlValue& table_;
  std::string path_;
  const std::string& file_;
  std::vector<std::string> asked_;  // in the order asked
};

}  // namespace mpsolid
