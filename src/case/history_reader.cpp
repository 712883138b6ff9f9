#include "src/case/history_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>
#include <vector>

#include "src/case/pairs_file.hpp"

namespace mpsolid {

namespace {
LoadHistory read_table(TableReader& r, const std::string& case_file) {
  const std::vector<std::pair<double, double>> points =
      read_pairs(r, "table", "table_file", "t (s from the load's start), factor", case_file);
  const char* key = r.has("table") ? "table" : "table_file";
  LoadHistory h;
  h.kind = LoadHistory::Kind::table;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto [t, f] = points[k];
    if (t < 0)
      r.fail(key, fmt::format("point {} has time {} s: times run from the load's start, >= 0",
                              k + 1, t));
    if (k > 0 && !(t > h.times.back()))
      r.fail(key, fmt::format("point {} has time {} s, not after point {}'s {} s: times must "
                              "increase",
                              k + 1, t, k, h.times.back()));
    h.times.push_back(t);
    h.factors.push_back(f);
  }
  return h;
}
}  // namespace

LoadHistory read_history(TableReader& r, const std::string& case_file) {
  const std::string kind = r.choice_or("history", {"step", "ramp", "table", "friedlander"}, "step");
  LoadHistory h;
  if (kind == "ramp") {
    h.kind = LoadHistory::Kind::ramp;
    h.rise_time = r.number("rise_time", "the time in s from 0 to the full value");
    r.range_check("rise_time", h.rise_time, h.rise_time > 0, "(0, inf) s");
  } else if (kind == "table") {
    h = read_table(r, case_file);
  } else if (kind == "friedlander") {
    h.kind = LoadHistory::Kind::friedlander;
    h.duration = r.number("duration", "the positive phase's duration t_d in s");
    r.range_check("duration", h.duration, h.duration > 0, "(0, inf) s");
    h.decay = r.number("decay", "the decay coefficient b");
    r.range_check("decay", h.decay, h.decay >= 0, "[0, inf)");
  }
  return h;
}

}  // namespace mpsolid
