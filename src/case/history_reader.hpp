#pragma once
// A load's time history from its [loads.NAME] table (README, "loads"):
//   history = "step" (the default), "ramp" (rise_time), "table" (table =
//   [[t, factor], ...] or table_file, times from the load's start,
//   increasing), or "friedlander" (duration t_d, decay b).
// Every problem is an InputError naming the file (and line), the key and
// what is allowed.
#include <string>

#include "src/case/table_reader.hpp"
#include "src/core/load_history.hpp"

namespace mpsolid {

// `case_file`: the case's path (a table file is found beside it).
LoadHistory read_history(TableReader& r, const std::string& case_file);

}  // namespace mpsolid
