#include "src/case/pairs_file.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "src/core/types.hpp"

namespace mpsolid {

std::vector<std::pair<double, double>> read_pairs_file(const std::string& path,
                                                       const std::string& key_path,
                                                       const std::string& what) {
  std::ifstream in(path);
  if (!in)
    throw InputError(
        fmt::format("{}: {}: cannot read the file (a CSV file of {} lines)", path, key_path, what));
  std::vector<std::pair<double, double>> pairs;
  std::string line;
  bool header_allowed = true;
  for (int number = 1; std::getline(in, line); ++number) {
    std::string text = line;
    for (char& ch : text)
      if (ch == ',' || ch == ';' || ch == '\t' || ch == '\r') ch = ' ';
    const auto first = text.find_first_not_of(' ');
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream fields(text);
    double x = 0, y = 0;
    std::string rest;
    const bool two = static_cast<bool>(fields >> x >> y) && !(fields >> rest);
    if (!two || !std::isfinite(x) || !std::isfinite(y)) {
      // One line of column names may come first.
      if (header_allowed && std::isalpha(static_cast<unsigned char>(text[first]))) {
        header_allowed = false;
        continue;
      }
      throw InputError(fmt::format("{}:{}: {}: expected two finite numbers {}, got '{}'", path,
                                   number, key_path, what, line));
    }
    header_allowed = false;
    pairs.push_back({x, y});
  }
  if (pairs.empty())
    throw InputError(fmt::format("{}: {}: no lines of numbers in the file", path, key_path));
  return pairs;
}

std::vector<std::pair<double, double>> read_pairs(TableReader& r, const std::string& key,
                                                  const std::string& file_key,
                                                  const std::string& what,
                                                  const std::string& case_file) {
  const TomlValue* inline_list = r.find(key);
  const TomlValue* file = r.find(file_key);
  if ((inline_list != nullptr) == (file != nullptr))
    r.fail(inline_list ? key : file_key,
           fmt::format("give either {} = [[{}], ...] or {} = \"FILE.csv\"", key, what, file_key));
  if (file) {
    std::filesystem::path path(r.string(file_key, "a CSV file of " + what + " lines"));
    if (path.is_relative()) path = std::filesystem::path(case_file).parent_path() / path;
    return read_pairs_file(path.string(), r.key_path(file_key), what);
  }
  const auto bad = [&](const std::string& problem) {
    r.fail(key, fmt::format("expected a list of [{}] pairs ({}), got {}", what, problem,
                            describe(*inline_list)));
  };
  if (!inline_list->is_array() || inline_list->as_array().empty()) bad("at least one");
  std::vector<std::pair<double, double>> out;
  for (const TomlValue& item : inline_list->as_array()) {
    if (!item.is_array() || item.as_array().size() != 2) bad("each is two numbers");
    out.push_back(
        {r.number(item.as_array()[0], key, what), r.number(item.as_array()[1], key, what)});
  }
  return out;
}

}  // namespace mpsolid
