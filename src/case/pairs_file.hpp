#pragma once
// A CSV file of number pairs (a polygon's vertices, a load's time table):
// one pair per line, commas, semicolons or blanks between; blank lines,
// lines starting with '#' and one header line of column names skipped.
#include <string>
#include <utility>
#include <vector>

#include "src/case/table_reader.hpp"

namespace mpsolid {

// The pairs of the file at `path`, for the case key `key_path`; `what`
// names the two numbers ("x, y (m)"). Throws InputError naming the file
// (and the line) when it cannot be read, a line is not two finite numbers,
// or it holds none.
std::vector<std::pair<double, double>> read_pairs_file(const std::string& path,
                                                       const std::string& key_path,
                                                       const std::string& what);

// The pairs a case table gives either inline, `key = [[a, b], ...]`, or as
// `file_key = "FILE.csv"` (relative to the case file `case_file`), one of
// the two and at least one pair; `what` names the two numbers ("t,
// factor"). Refusals name the file, the key and what is allowed.
std::vector<std::pair<double, double>> read_pairs(TableReader& r, const std::string& key,
                                                  const std::string& file_key,
                                                  const std::string& what,
                                                  const std::string& case_file);

}  // namespace mpsolid
