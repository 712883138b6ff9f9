#pragma once
// A case file read against the models this build has: the case reader
// (src/case/) with the kernels' registry, which the case layer may not include.
#include <string>
#include <vector>

#include "kernels/model_registry.hpp"
#include "src/case/case_reader.hpp"

namespace mpsolid {

inline CaseSpec load_case(const std::string& path, const std::vector<std::string>& overrides = {}) {
  return read_case(path, overrides, model_catalog());
}

// From TOML text; `source_name` stands in for the file name.
inline CaseSpec load_case_text(const std::string& toml_text, const std::string& source_name,
                               const std::vector<std::string>& overrides = {}) {
  return parse_case(toml_text, source_name, overrides, model_catalog());
}

}  // namespace mpsolid
