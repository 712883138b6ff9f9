#pragma once
// case.resolved.toml: the case as TOML with every default and override filled
// in, derived figures as comments; it reads back as the same case.
#include <string>

#include "src/case/case_spec.hpp"

namespace mpsolid {

std::string resolved_case_toml(const CaseSpec& c);

}  // namespace mpsolid
