#pragma once
// Reads and validates a case file (TOML) with command-line overrides. Every
// problem is an InputError naming the file (and line), the key and what is
// allowed; nothing is written before the whole case has been accepted.
#include <string>
#include <vector>

#include "src/case/case_spec.hpp"

namespace mpsolid {

// `overrides` are "dotted.key=VALUE" strings from --set; `models` are the
// models a case may choose, with their options tables (kernels' registry,
// brought in by src/solver/case_loader.hpp).
CaseSpec read_case(const std::string& path, const std::vector<std::string>& overrides,
                   const std::vector<ModelInfo>& models);

// Same, from TOML text; `source_name` stands in for the file name.
CaseSpec parse_case(const std::string& toml_text, const std::string& source_name,
                    const std::vector<std::string>& overrides,
                    const std::vector<ModelInfo>& models);

}  // namespace mpsolid
