#pragma once
// A model's options table as plain data: the keys of its case section, their
// defaults and allowed values. Models declare one (kernels/), the case reader
// validates a section against it (src/case/), and neither includes the other.
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace mpsolid {

struct OptionSpec {
  std::string key;
  std::string help;  // what the value means, for messages
  // A number in the range `allowed` describes, checked by `valid`; or, when
  // `choices` is not empty, one of those words.
  double default_number = 0;
  std::function<bool(double)> valid;
  std::string allowed;
  std::vector<std::string> choices;
  std::string default_choice;

  bool is_choice() const { return !choices.empty(); }
};

// One model as the case reader (and a test) sees it: its name (`model =
// ...`), the case section its options live in (empty: none), that section's
// table, and the traits that decide which checks apply to it.
struct ModelInfo {
  std::string name;
  std::string section;
  std::vector<OptionSpec> options;
  bool uses_rotation = false;       // particles carry a rotation (spins, torques)
  bool rotation_invariant = false;  // a rigid rotation is stress-free (objective)
};

// Validated option values of one model, every key present (defaults filled).
struct OptionValues {
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> choices;

  double number(const std::string& key) const { return numbers.at(key); }
  const std::string& choice(const std::string& key) const { return choices.at(key); }
  bool operator==(const OptionValues&) const = default;
};

// The defaults of a table.
inline OptionValues default_options(const std::vector<OptionSpec>& table) {
  OptionValues v;
  for (const OptionSpec& o : table) {
    if (o.is_choice())
      v.choices[o.key] = o.default_choice;
    else
      v.numbers[o.key] = o.default_number;
  }
  return v;
}

}  // namespace mpsolid
