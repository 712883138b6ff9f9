#pragma once
// The hourglass penalty's options, shared by the models built on the
// kernel-corrected deformation gradient (MODEL.md section 5).
#include <vector>

#include "src/core/option_table.hpp"

namespace mpsolid {

struct HourglassSettings {
  double alpha = 1.0;      // penalty coefficient (0: off)
  bool consistent = true;  // full gradient (true) or F held fixed ("frozen")
};

inline std::vector<OptionSpec> hourglass_option_table() {
  std::vector<OptionSpec> table(2);
  table[0].key = "hourglass";
  table[0].help = "the hourglass penalty coefficient alpha";
  table[0].default_number = 1.0;
  table[0].valid = [](double v) { return v >= 0; };
  table[0].allowed = "[0, inf) (0 switches the penalty off)";
  table[1].key = "hourglass_form";
  table[1].help = "consistent (the full gradient, conserves energy) or frozen (F held fixed)";
  table[1].choices = {"consistent", "frozen"};
  table[1].default_choice = "consistent";
  return table;
}

inline HourglassSettings hourglass_settings(const OptionValues& options) {
  return {options.number("hourglass"), options.choice("hourglass_form") == "consistent"};
}

}  // namespace mpsolid
