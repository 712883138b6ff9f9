#pragma once
// A case as Python holds it: where it came from (a file, or TOML text), the
// overrides given so far, and the CaseSpec they make. Every override re-reads
// the source with all of them, as `mpsolid run CASE --set ...` does, so
// Python sees the command line's validation and messages.
#include <optional>
#include <string>
#include <vector>

#include "src/case/case_spec.hpp"

namespace mpsolid::python {

class CaseHandle {
 public:
  static CaseHandle from_file(const std::string& path);
  static CaseHandle from_text(const std::string& toml_text, const std::string& source_name);

  // Adds "key=value" (value in TOML); throws InputError and changes nothing
  // when the case with it is not valid.
  void set(const std::string& key, const std::string& toml_value);

  const CaseSpec& spec() const { return spec_; }
  const std::vector<std::string>& overrides() const { return overrides_; }
  const std::optional<std::string>& path() const { return path_; }
  const std::string& source_name() const { return source_name_; }

 private:
  CaseSpec read(const std::vector<std::string>& overrides) const;

  std::optional<std::string> path_;  // empty: the case came as text
  std::string text_;
  std::string source_name_;
  std::vector<std::string> overrides_;
  CaseSpec spec_;
};

}  // namespace mpsolid::python
