// Every kind of bad input is an InputError whose message names the file, the
// key (as a dotted path) and what is allowed; good input (the shipped cases,
// --set overrides, the resolved TOML read back) is accepted as written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <regex>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

#include "src/core/types.hpp"
#include "src/solver/case_loader.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

using Strings = std::vector<std::string>;

std::string shipped(const std::string& name) {
  return std::string(MPSOLID_SOURCE_DIR) + "/cases/" + name;
}

// A small valid case: the shipped rod case, written out so each bad case
// below changes exactly one thing with `edit`. Bodies in name order: plate,
// rod, wall.
std::string base_toml() {
  return R"(name = "base"
model = "paper"
l0 = 0.002
depth = 1.0

[materials.rubber]
E = 2.8e6
nu = 0.495
rho = 1010.0

[bodies.rod]
kind = "elastic"
material = "rubber"
x = [0.0, 0.100]
y = [-0.020, 0.020]

[bodies.plate]
kind = "rigid"
material = "rubber"
x = [-0.006, 0.0]
y = [-0.030, 0.030]

[bodies.wall]
kind = "wall"
material = "rubber"
x = [0.100, 0.104]
y = [-0.020, 0.020]

[loads.shock]
type = "step"
body = "plate"
force = [11200.0, 0.0]
start = 0.0

[time]
dt = 1.0e-8
end = 0.010

[output]
frame_interval = 1.0e-3
)";
}

// `text` with the one occurrence of `from` replaced by `to`. The edit must
// apply, else the test would silently check the valid base case.
std::string edit(const std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos)
    throw std::logic_error("edit: '" + from + "' does not occur exactly once in the base case");
  return text.substr(0, at) + to + text.substr(at + from.size());
}

std::string edit(const std::string& from, const std::string& to) {
  return edit(base_toml(), from, to);
}

// The InputError message of parsing `text` as "bad.toml", or nothing if the
// case was accepted. Any other exception fails the test.
std::optional<std::string> error_of(const std::string& text, const Strings& overrides = {}) {
  try {
    load_case_text(text, "bad.toml", overrides);
  } catch (const InputError& e) {
    return std::string(e.what());
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected mpsolid::InputError, got another exception: " << e.what();
    return std::string();
  }
  return std::nullopt;
}

// Asserts an InputError whose message contains every one of `needles`.
void expect_error(const std::string& text, const Strings& needles, const Strings& overrides = {}) {
  const auto message = error_of(text, overrides);
  ASSERT_TRUE(message.has_value()) << "the case was accepted; expected an InputError";
  for (const auto& needle : needles)
    EXPECT_NE(message->find(needle), std::string::npos)
        << "the message does not contain \"" << needle << "\"; the message is:\n"
        << *message;
}

#define EXPECT_INPUT_ERROR(text, ...) \
  do {                                \
    SCOPED_TRACE(#text);              \
    expect_error(text, __VA_ARGS__);  \
  } while (0)

TEST(CaseErrors, TheBaseCaseIsValid) {
  const CaseSpec spec = load_case_text(base_toml(), "bad.toml");
  EXPECT_EQ(spec.name, "base");
  ASSERT_EQ(spec.bodies.size(), 3u);
  ASSERT_EQ(spec.loads.size(), 1u);
}

// ---- initial motion, holds, probes, automatic step ---------------------------

TEST(CaseErrors, WallsTakeNoMotionOrHold) {
  for (const char* key : {"velocity = [1.0, 0.0]", "spin = 1.0", "hold = \"y\""})
    EXPECT_INPUT_ERROR(edit("x = [0.100, 0.104]", std::string("x = [0.100, 0.104]\n") + key),
                       {"bad.toml", "bodies.wall.", "walls never move"});
}

TEST(CaseErrors, RigidBodiesTakeNoHoldOrBendingMode) {
  EXPECT_INPUT_ERROR(edit("y = [-0.030, 0.030]", "y = [-0.030, 0.030]\nhold = \"x\""),
                     {"bad.toml", "bodies.plate.hold", "rigid body cannot be held"});
  EXPECT_INPUT_ERROR(base_toml(), {"bodies.plate.bending_mode", "only an elastic body"},
                     {"bodies.plate.bending_mode={root_x=0.0, length=0.1, tip_velocity=1.0}"});
}

TEST(CaseErrors, UnknownHold) {
  EXPECT_INPUT_ERROR(edit("y = [-0.020, 0.020]\n\n[bodies.plate]",
                          "y = [-0.020, 0.020]\nhold = \"z\"\n\n[bodies.plate]"),
                     {"bad.toml", "bodies.rod.hold", "'z'", "none, x, y"});
}

TEST(CaseErrors, BendingModeNeedsAPositiveLengthAndItsKeys) {
  EXPECT_INPUT_ERROR(base_toml(), {"bodies.rod.bending_mode.length", "(0, inf) m"},
                     {"bodies.rod.bending_mode={root_x=0.0, length=-0.1, tip_velocity=1.0}"});
  EXPECT_INPUT_ERROR(base_toml(), {"bodies.rod.bending_mode.tip_velocity", "is missing"},
                     {"bodies.rod.bending_mode={root_x=0.0, length=0.1}"});
  EXPECT_INPUT_ERROR(
      base_toml(), {"bodies.rod.bending_mode.kL", "(0, 20)"},
      {"bodies.rod.bending_mode={root_x=0.0, length=0.1, kL=0.0, tip_velocity=1.0}"});
}

TEST(CaseErrors, ProbeOffEveryBody) {
  EXPECT_INPUT_ERROR(base_toml(), {"probes.tip.at", "not within l0", "of any body"},
                     {"probes.tip.at=[0.5, 0.5]"});
  EXPECT_INPUT_ERROR(base_toml(), {"probes.tip.at", "two numbers"}, {"probes.tip.at=0.5"});
}

TEST(CaseErrors, TimeStepMustBeANumberOrAuto) {
  EXPECT_INPUT_ERROR(edit("dt = 1.0e-8", "dt = \"fast\""),
                     {"bad.toml", "time.dt", "\"auto\"", "fast"});
  EXPECT_INPUT_ERROR(edit("dt = 1.0e-8", "dt = \"auto\"\nsafety = 1.5"),
                     {"bad.toml", "time.safety", "(0, 1]"});
  EXPECT_INPUT_ERROR(edit("dt = 1.0e-8", "dt = 1.0e-8\nsafety = 0.5"),
                     {"bad.toml", "time.safety", "only with dt = \"auto\""});
}

// ---- model options: each model's own table ---------------------------------

TEST(CaseErrors, ModelOptionsAreCheckedAgainstTheModelsTable) {
  EXPECT_INPUT_ERROR(base_toml() + "\n[finite_strain]\nhourglass = -1.0\n",
                     {"bad.toml", "finite_strain.hourglass", "-1", "[0, inf)"});
  EXPECT_INPUT_ERROR(base_toml() + "\n[finite_strain]\nhourglass_form = \"loose\"\n",
                     {"bad.toml", "finite_strain.hourglass_form", "'loose'", "consistent, frozen"});
  EXPECT_INPUT_ERROR(base_toml() + "\n[finite_strain]\nhourglas = 1.0\n",
                     {"bad.toml", "finite_strain.hourglas", "unknown key", "hourglass_form"});
  EXPECT_INPUT_ERROR(base_toml(), {"--set", "finite_strain.hourglass", "expected a number"},
                     {"finite_strain.hourglass=\"big\""});
  // linear_elastic reads the same table from its own section.
  EXPECT_INPUT_ERROR(base_toml(), {"--set", "linear_elastic.hourglass", "-1", "[0, inf)"},
                     {"model=linear_elastic", "linear_elastic.hourglass=-1"});
}

TEST(CaseErrors, ModelOptionsTakeDefaultsAndReadBack) {
  const CaseSpec plain = load_case_text(base_toml(), "bad.toml", {"model=finite_strain"});
  EXPECT_EQ(plain.model_section, "finite_strain");
  EXPECT_EQ(plain.model_options.number("hourglass"), 1.0);
  EXPECT_EQ(plain.model_options.choice("hourglass_form"), "consistent");
  const CaseSpec set = load_case_text(base_toml(), "bad.toml",
                                      {"model=finite_strain", "finite_strain.hourglass=0.5",
                                       "finite_strain.hourglass_form=frozen"});
  EXPECT_EQ(set.model_options.number("hourglass"), 0.5);
  EXPECT_EQ(set.model_options.choice("hourglass_form"), "frozen");
  const CaseSpec again = load_case_text(set.resolved_toml, "case.resolved.toml");
  EXPECT_EQ(again.model_options, set.model_options);
  // Another model's section is still checked, but does not apply.
  const CaseSpec paper =
      load_case_text(base_toml() + "\n[finite_strain]\nhourglass = 2.0\n", "bad.toml");
  EXPECT_EQ(paper.model_section, "");
  EXPECT_TRUE(paper.model_options.numbers.empty());
  // ... and a note says so.
  ASSERT_EQ(paper.notes.size(), 1u);
  EXPECT_NE(paper.notes[0].find("[finite_strain] sets options of model finite_strain; this case "
                                "runs model paper"),
            std::string::npos)
      << paper.notes[0];
  EXPECT_TRUE(plain.notes.empty());
}

// ---- step counts ----------------------------------------------------------------

TEST(CaseErrors, StepCountsThatOverflowAreRefusedWithWhatWouldWork) {
  EXPECT_INPUT_ERROR(base_toml(), {"bad.toml", "time.end = 1e+11 s", "2^53", "time.end <="},
                     {"time.end=1e11"});
  EXPECT_INPUT_ERROR(base_toml(), {"output.frame_interval", "2^53"}, {"output.frame_interval=1e9"});
}

TEST(CaseErrors, EndsAndIntervalsOffTheStepGridAreRoundedWithANote) {
  EXPECT_TRUE(load_case_text(base_toml(), "bad.toml").notes.empty());
  const CaseSpec spec =
      load_case_text(base_toml(), "bad.toml", {"time.end=2.5e-7", "output.frame_interval=1.05e-7"});
  EXPECT_EQ(spec.step_count(), 25);
  EXPECT_EQ(spec.steps_per_frame(), 10);
  // Frames off the grid (and, this short, few history rows).
  const auto has_note = [](const CaseSpec& c, const std::string& text) {
    return std::any_of(c.notes.begin(), c.notes.end(),
                       [&](const std::string& n) { return n.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(has_note(spec, "output.frame_interval = 1.05e-07 s is 10.5 steps"));
  EXPECT_TRUE(has_note(spec, "frames every 10 steps"));
  // The history interval was not given: it is put on the grid without a note.
  EXPECT_FALSE(has_note(spec, "output.history_interval = 1.05e-07"));
  EXPECT_DOUBLE_EQ(spec.history_interval, 1e-7);
  const CaseSpec given = load_case_text(
      base_toml(), "bad.toml",
      {"time.end=2.5e-7", "output.frame_interval=1e-7", "output.history_interval=1.5e-8"});
  EXPECT_TRUE(has_note(given, "output.history_interval = 1.5e-08 s is 1.5 steps"));
  const CaseSpec late = load_case_text(base_toml(), "bad.toml", {"time.end=1.005e-6"});
  EXPECT_TRUE(has_note(late, "the next whole step, 101"));
}

TEST(CaseErrors, HistoryDefaultsToAbout200RowsOrEvery10Microseconds) {
  // The rod case sets only the frame interval (1 ms).
  EXPECT_DOUBLE_EQ(testing::rod_case().history_interval, 5e-5);                   // 10 ms / 200
  EXPECT_DOUBLE_EQ(testing::rod_case({"time.end=1e-3"}).history_interval, 1e-5);  // 10 us
  EXPECT_TRUE(testing::rod_case().notes.empty());
  // Fewer than 20 rows get a note.
  const CaseSpec short_run = testing::rod_case({"time.end=2e-5"});
  ASSERT_EQ(short_run.notes.size(), 1u);
  EXPECT_NE(short_run.notes[0].find("history.csv gets only 3 rows"), std::string::npos)
      << short_run.notes[0];
  EXPECT_TRUE(testing::rod_case({"time.end=2e-5", "output.history_interval=1e-6"}).notes.empty());
}

TEST(CaseErrors, AMissingKeyNamesTheLikelyTypo) {
  EXPECT_INPUT_ERROR(edit("l0 = 0.002", "lo = 0.002"),
                     {"bad.toml", "l0 is missing", "bad.toml:", "'lo'", "a typo for 'l0'"});
  // No hint when nothing is close.
  const auto message = error_of(edit("l0 = 0.002", "spacing = 0.002"));
  ASSERT_TRUE(message.has_value());
  EXPECT_EQ(message->find("typo"), std::string::npos) << *message;
}

TEST(CaseErrors, FlushSubnormalsIsABoolean) {
  EXPECT_INPUT_ERROR(base_toml() + "\n[numerics]\nflush_subnormals = 1\n",
                     {"bad.toml", "numerics.flush_subnormals", "true or false"});
  EXPECT_INPUT_ERROR(base_toml() + "\n[numerics]\nflush = true\n",
                     {"bad.toml", "numerics.flush", "flush_subnormals"});
  EXPECT_TRUE(load_case_text(base_toml() + "\n[numerics]\nflush_subnormals = true\n", "bad.toml")
                  .flush_subnormals);
  EXPECT_FALSE(load_case_text(base_toml(), "bad.toml").flush_subnormals);
}

TEST(CaseErrors, HistoryIntervalWithinDtAndFrameInterval) {
  EXPECT_INPUT_ERROR(base_toml(), {"output.history_interval", "[dt, frame_interval]"},
                     {"output.history_interval=0.002"});
  EXPECT_INPUT_ERROR(base_toml(), {"output.history_interval", "[dt, frame_interval]"},
                     {"output.history_interval=1e-9"});
}

TEST(GoodCases, AutoTimeStepFitsWholeStepsInTheFinestOutput) {
  CaseSpec spec =
      load_case_text(base_toml(), "bad.toml", {"time.dt=\"auto\"", "output.history_interval=1e-4"});
  EXPECT_TRUE(spec.dt_auto);
  EXPECT_EQ(spec.dt, 0.0);
  EXPECT_EQ(spec.dt_safety, 0.4);
  spec.set_auto_time_step(1.19e-5, 2.0 / 1.19e-5);
  // 0.4 x 11.9 us = 4.76 us -> 1e-4 / 22 steps = 4.55 us.
  EXPECT_DOUBLE_EQ(spec.dt, 1e-4 / 22);
  EXPECT_EQ(spec.steps_per_history(), 22);
  EXPECT_EQ(spec.steps_per_frame(), 220);
  EXPECT_EQ(spec.step_count(), 2200);
  // The resolved case holds the chosen step as a number and reads back.
  const CaseSpec again = load_case_text(spec.resolved_toml, "case.resolved.toml");
  EXPECT_FALSE(again.dt_auto);
  EXPECT_EQ(again.dt, spec.dt);
  EXPECT_NE(spec.resolved_toml.find("time.dt = \"auto\" chose"), std::string::npos);
}

TEST(CaseErrors, AutoTimeStepLongerThanTheRun) {
  CaseSpec spec =
      load_case_text(base_toml(), "bad.toml",
                     {"time.dt=\"auto\"", "output.history_interval=1e-4", "time.end=2e-6"});
  try {
    spec.set_auto_time_step(1.19e-5, 2.0 / 1.19e-5);  // chooses 4.55 us
    ADD_FAILURE() << "a run shorter than the chosen step was accepted";
  } catch (const InputError& e) {
    for (const char* needle : {"bad.toml", "time.end", "auto", "4.54545e-06"})
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

// ---- unknown keys -----------------------------------------------------------

TEST(CaseErrors, UnknownKeyInATable) {
  EXPECT_INPUT_ERROR(edit("dt = 1.0e-8", "dt = 1.0e-8\ndtt = 1e-8"),
                     {"bad.toml", "time.dtt", "unknown key", "dt, safety, end"});
}

TEST(CaseErrors, UnknownKeyAtTopLevel) {
  EXPECT_INPUT_ERROR(edit("depth = 1.0", "depht = 1.0"),
                     {"bad.toml", "depht", "unknown key", "depth", "model", "l0"});
}

TEST(CaseErrors, UnknownTableAtTopLevel) {
  EXPECT_INPUT_ERROR(edit("[output]", "[outputs]"),
                     {"bad.toml", "outputs", "unknown key", "output"});
}

TEST(CaseErrors, UnknownKeyInAMaterialBodyAndLoad) {
  EXPECT_INPUT_ERROR(edit("rho = 1010.0", "rho = 1010.0\nG = 1.0"),
                     {"bad.toml", "materials.rubber.G", "unknown key", "E, nu, rho"});
  EXPECT_INPUT_ERROR(
      edit("kind = \"elastic\"", "kind = \"elastic\"\nz = [0.0, 1.0]"),
      {"bad.toml", "bodies.rod.z", "unknown key", "kind, material, shape, x, y, angle"});
  EXPECT_INPUT_ERROR(edit("start = 0.0", "start = 0.0\nend = 1.0"),
                     {"bad.toml", "loads.shock.end", "unknown key", "type, body, force, start"});
}

TEST(CaseErrors, UnknownKeyReportsTheLine) {
  // [time] dt is on line 36 of the base case, so the inserted dtt is on line 37.
  EXPECT_INPUT_ERROR(edit("dt = 1.0e-8", "dt = 1.0e-8\ndtt = 1e-8"), {"bad.toml:37"});
}

// ---- wrong types ------------------------------------------------------------

TEST(CaseErrors, StringWhereANumberIsExpected) {
  EXPECT_INPUT_ERROR(edit("E = 2.8e6", "E = \"2.8e6\""),
                     {"bad.toml", "materials.rubber.E", "expected a number"});
  EXPECT_INPUT_ERROR(edit("l0 = 0.002", "l0 = \"2 mm\""), {"bad.toml", "l0", "expected a number"});
  EXPECT_INPUT_ERROR(edit("end = 0.010", "end = true"),
                     {"bad.toml", "time.end", "expected a number"});
}

TEST(CaseErrors, NumberWhereAStringIsExpected) {
  EXPECT_INPUT_ERROR(edit("model = \"paper\"", "model = 1"),
                     {"bad.toml", "model", "expected a string"});
  EXPECT_INPUT_ERROR(edit("body = \"plate\"", "body = 2"),
                     {"bad.toml", "loads.shock.body", "expected a string"});
  EXPECT_INPUT_ERROR(edit("kind = \"elastic\"", "kind = 3"),
                     {"bad.toml", "bodies.rod.kind", "expected a string"});
}

TEST(CaseErrors, NumberWhereABodyKindIsExpectedListsTheKinds) {
  // What is allowed for `kind` is one of three words, not just "a string".
  EXPECT_INPUT_ERROR(edit("kind = \"elastic\"", "kind = 3"),
                     {"bad.toml", "bodies.rod.kind", "elastic", "rigid", "wall"});
}

TEST(CaseErrors, BadRangePairs) {
  EXPECT_INPUT_ERROR(edit("x = [0.0, 0.100]", "x = [0.0, 0.05, 0.100]"),
                     {"bad.toml", "bodies.rod.x", "two numbers"});
  EXPECT_INPUT_ERROR(edit("x = [0.0, 0.100]", "x = 0.1"),
                     {"bad.toml", "bodies.rod.x", "two numbers"});
  EXPECT_INPUT_ERROR(edit("force = [11200.0, 0.0]", "force = [11200.0, \"0\"]"),
                     {"bad.toml", "loads.shock.force", "two numbers"});
}

TEST(CaseErrors, NonFiniteNumbers) {
  EXPECT_INPUT_ERROR(edit("E = 2.8e6", "E = inf"), {"bad.toml", "materials.rubber.E", "finite"});
  EXPECT_INPUT_ERROR(edit("nu = 0.495", "nu = nan"), {"bad.toml", "materials.rubber.nu", "finite"});
}

TEST(CaseErrors, MissingRequiredKeys) {
  EXPECT_INPUT_ERROR(edit("l0 = 0.002\n", ""), {"bad.toml", "l0", "missing"});
  EXPECT_INPUT_ERROR(edit("nu = 0.495\n", ""), {"bad.toml", "materials.rubber.nu", "missing"});
  EXPECT_INPUT_ERROR(edit("[time]\ndt = 1.0e-8\nend = 0.010\n", ""),
                     {"bad.toml", "time", "missing"});
}

// ---- values out of range ----------------------------------------------------

TEST(CaseErrors, YoungsModulusMustBePositive) {
  for (const char* bad : {"E = 0.0", "E = -2.8e6", "E = 0"}) {
    SCOPED_TRACE(bad);
    expect_error(edit("E = 2.8e6", bad), {"bad.toml", "materials.rubber.E", "(0, inf)"});
  }
}

TEST(CaseErrors, PoissonRatioMustBeInsideMinusOneToHalf) {
  for (const char* bad : {"nu = 0.5", "nu = -1.0", "nu = 0.7", "nu = -1.5"}) {
    SCOPED_TRACE(bad);
    expect_error(edit("nu = 0.495", bad), {"bad.toml", "materials.rubber.nu", "(-1, 0.5)"});
  }
  // Just inside is fine.
  EXPECT_FALSE(error_of(edit("nu = 0.495", "nu = 0.4999")).has_value());
  EXPECT_FALSE(error_of(edit("nu = 0.495", "nu = -0.999")).has_value());
}

TEST(CaseErrors, DensityMustBePositive) {
  for (const char* bad : {"rho = 0.0", "rho = -1010.0"}) {
    SCOPED_TRACE(bad);
    expect_error(edit("rho = 1010.0", bad), {"bad.toml", "materials.rubber.rho", "(0, inf)"});
  }
}

TEST(CaseErrors, TimeStepMustBePositive) {
  for (const char* bad : {"dt = 0.0", "dt = -1.0e-8"}) {
    SCOPED_TRACE(bad);
    expect_error(edit("dt = 1.0e-8", bad), {"bad.toml", "time.dt", "(0, inf)"});
  }
}

TEST(CaseErrors, EndMustBeAtLeastOneStep) {
  expect_error(edit("end = 0.010", "end = 5.0e-9"), {"bad.toml", "time.end", "[dt, inf)"});
  expect_error(edit("end = 0.010", "end = -1.0"), {"bad.toml", "time.end", "[dt, inf)"});
  EXPECT_FALSE(error_of(edit("end = 0.010", "end = 1.0e-8")).has_value());
}

TEST(CaseErrors, LatticeSpacingMustBePositive) {
  for (const char* bad : {"l0 = 0.0", "l0 = -0.002"}) {
    SCOPED_TRACE(bad);
    expect_error(edit("l0 = 0.002", bad), {"bad.toml", "l0:", "(0, inf)"});
  }
}

TEST(CaseErrors, TooFineALatticeIsRejected) {
  // Far more particles than the 32-bit bond indices allow, at several scales
  // (from 1e-11 on, nx * ny overflows a 64-bit site count, and from about
  // 1e-20 on, x / l0 overflows the int64 lattice index, if not guarded).
  for (const char* bad : {"l0 = 1e-6", "l0 = 1e-12", "l0 = 1e-13", "l0 = 1e-14", "l0 = 1e-15",
                          "l0 = 1e-18", "l0 = 1e-20", "l0 = 1e-300"}) {
    SCOPED_TRACE(bad);
    expect_error(edit("l0 = 0.002", bad), {"bad.toml", "l0", "particles"});
  }
}

TEST(CaseErrors, DepthMustBePositive) {
  for (const char* bad : {"depth = 0.0", "depth = -1.0"}) {
    SCOPED_TRACE(bad);
    expect_error(edit("depth = 1.0", bad), {"bad.toml", "depth", "(0, inf)"});
  }
}

TEST(CaseErrors, FrameIntervalMustBeAtLeastOneStep) {
  EXPECT_INPUT_ERROR(edit("frame_interval = 1.0e-3", "frame_interval = 5.0e-9"),
                     {"bad.toml", "output.frame_interval", "[dt, inf)"});
  EXPECT_INPUT_ERROR(edit("frame_interval = 1.0e-3", "frame_interval = 0.0"),
                     {"bad.toml", "output.frame_interval", "[dt, inf)"});
}

TEST(CaseErrors, LoadStartMustNotBeNegative) {
  EXPECT_INPUT_ERROR(edit("start = 0.0", "start = -1.0e-3"),
                     {"bad.toml", "loads.shock.start", "[0, inf)"});
}

TEST(CaseErrors, NameMustBeAPlainName) {
  EXPECT_INPUT_ERROR(edit("name = \"base\"", "name = \"a/b\""), {"bad.toml", "name", "'/'"});
  EXPECT_INPUT_ERROR(edit("name = \"base\"", "name = \"\""), {"bad.toml", "name", "non-empty"});
}

// ---- geometry ---------------------------------------------------------------

TEST(CaseErrors, OverlappingBodiesNameBoth) {
  // The plate reaches 1 mm into the rod.
  EXPECT_INPUT_ERROR(edit("x = [-0.006, 0.0]", "x = [-0.006, 0.001]"),
                     {"bad.toml", "bodies.plate", "bodies.rod", "overlap", "touch"});
}

TEST(CaseErrors, TouchingBodiesAreFine) {
  EXPECT_FALSE(error_of(base_toml()).has_value());  // plate|rod|wall share edges
}

TEST(CaseErrors, EmptyBody) {
  // No site centre (k + 1/2) * 2 mm lies in [201.2, 201.8) mm.
  const std::string text = base_toml() +
                           "\n[bodies.speck]\nkind = \"rigid\"\nmaterial = \"rubber\"\n"
                           "x = [0.2012, 0.2018]\ny = [0.2012, 0.2018]\n";
  EXPECT_INPUT_ERROR(text, {"bad.toml", "bodies.speck", "empty", "(k + 1/2) l0"});
}

TEST(CaseErrors, RangeBoundsOutOfOrder) {
  EXPECT_INPUT_ERROR(edit("x = [0.0, 0.100]", "x = [0.100, 0.0]"),
                     {"bad.toml", "bodies.rod.x", "x0 < x1"});
  EXPECT_INPUT_ERROR(edit("x = [0.0, 0.100]", "x = [0.05, 0.05]"),
                     {"bad.toml", "bodies.rod.x", "x0 < x1"});
  EXPECT_INPUT_ERROR(
      edit("y = [-0.020, 0.020]\n\n[bodies.plate]", "y = [0.020, -0.020]\n\n[bodies.plate]"),
      {"bad.toml", "bodies.rod.y", "y0 < y1"});
}

// ---- shapes ----------------------------------------------------------------

// The base case with one more body: `keys` after kind and material.
std::string with_body(const std::string& keys) {
  return base_toml() + "\n[bodies.extra]\nkind = \"elastic\"\nmaterial = \"rubber\"\n" + keys +
         "\n";
}

TEST(CaseErrors, ShapesAreReadAndChecked) {
  EXPECT_FALSE(
      error_of(with_body("shape = \"circle\"\ncenter = [0.3, 0.0]\nradius = 0.01")).has_value());
  EXPECT_FALSE(
      error_of(with_body("shape = \"polygon\"\nvertices = [[0.3, 0], [0.4, 0], [0.35, 0.05]]"))
          .has_value());
  EXPECT_INPUT_ERROR(with_body("shape = \"square\"\nx = [0.3, 0.4]\ny = [0, 0.1]"),
                     {"bad.toml", "bodies.extra.shape",
                      "rectangle, circle, ellipse, annulus, "
                      "polygon"});
  EXPECT_INPUT_ERROR(with_body("shape = \"circle\"\ncenter = [0.3, 0.0]\nradius = -0.01"),
                     {"bad.toml", "bodies.extra.radius", "(0, inf) m"});
  EXPECT_INPUT_ERROR(with_body("shape = \"circle\"\ncenter = [0.3, 0.0]"),
                     {"bad.toml", "bodies.extra.radius"});
  EXPECT_INPUT_ERROR(with_body("shape = \"annulus\"\ncenter = [0.3, 0.0]\nradii = [0.02, 0.01]"),
                     {"bad.toml", "bodies.extra.radii", "0 < inner < outer"});
  EXPECT_INPUT_ERROR(
      with_body("shape = \"ellipse\"\ncenter = [0.3, 0.0]\nsemi_axes = [0.02, 0.01]\nradius = 1"),
      {"bad.toml", "bodies.extra", "radius"});
}

TEST(CaseErrors, SelfIntersectingPolygonNamesTheCrossingEdges) {
  // A bow tie: edge 1 (vertex 1 to 2) crosses edge 3 (vertex 3 to 4).
  EXPECT_INPUT_ERROR(
      with_body("shape = \"polygon\"\nvertices = [[0.3, 0], [0.4, 0.1], [0.4, 0], [0.3, 0.1]]"),
      {"bad.toml", "bodies.extra.vertices", "not a simple polygon",
       "edges 1 (from vertex 1 to 2) and 3 (from vertex 3 to 4) cross at (0.35, 0.05)"});
  EXPECT_INPUT_ERROR(with_body("shape = \"polygon\"\nvertices = [[0.3, 0], [0.4, 0]]"),
                     {"bad.toml", "bodies.extra.vertices", "at least 3 vertices"});
  EXPECT_INPUT_ERROR(with_body("shape = \"polygon\"\nvertices = [[0.3, 0], [0.4, 0], [0.5, 0]]"),
                     {"bad.toml", "bodies.extra.vertices", "no area"});
  EXPECT_INPUT_ERROR(with_body("shape = \"polygon\""),
                     {"bad.toml", "bodies.extra", "vertices_file"});
}

TEST(CaseErrors, HoleOutsideItsBody) {
  EXPECT_FALSE(error_of(with_body("x = [0.3, 0.4]\ny = [0, 0.1]\nholes = [{ shape = \"circle\", "
                                  "center = [0.35, 0.05], radius = 0.02 }]"))
                   .has_value());
  EXPECT_INPUT_ERROR(with_body("x = [0.3, 0.4]\ny = [0, 0.1]\nholes = [{ shape = \"circle\", "
                               "center = [0.39, 0.05], radius = 0.02 }]"),
                     {"bad.toml", "bodies.extra.holes[0]", "not inside the body's rectangle"});
  EXPECT_INPUT_ERROR(with_body("x = [0.3, 0.4]\ny = [0, 0.1]\nholes = [{ shape = \"circle\", "
                               "center = [0.35, 0.05], radius = 0.02, radios = 1 }]"),
                     {"bad.toml", "bodies.extra.holes[0]", "radios"});
}

TEST(CaseErrors, CurvedBodiesThatOverlapNameBoth) {
  // A disk reaching 1 mm into the rod's far end.
  EXPECT_INPUT_ERROR(with_body("shape = \"circle\"\ncenter = [0.05, 0.029]\nradius = 0.01"),
                     {"bad.toml", "bodies.extra (circle)", "bodies.rod (rectangle)", "overlap"});
  // Touching it from above is fine.
  EXPECT_FALSE(
      error_of(with_body("shape = \"circle\"\ncenter = [0.05, 0.03]\nradius = 0.01")).has_value());
}

TEST(CaseErrors, AccelerationLoadsTakeAnAcceleration) {
  EXPECT_FALSE(
      error_of(edit("type = \"step\"\nbody = \"plate\"\nforce = [11200.0, 0.0]",
                    "type = \"acceleration\"\nbody = \"plate\"\nacceleration = [0, -9.81]"))
          .has_value());
  EXPECT_INPUT_ERROR(
      edit("type = \"step\"\nbody = \"plate\"", "type = \"acceleration\"\nbody = \"plate\""),
      {"bad.toml", "loads.shock.acceleration", "m/s^2"});
  EXPECT_INPUT_ERROR(edit("type = \"step\"", "type = \"gravity\""),
                     {"bad.toml", "loads.shock.type", "step, acceleration"});
}

TEST(CaseErrors, PressuresSelectAPartOfTheSurface) {
  const std::string head = "type = \"pressure\"\nbody = \"plate\"\npressure = 1e5\n";
  const auto pressure = [&](const std::string& selection) {
    return edit("type = \"step\"\nbody = \"plate\"\nforce = [11200.0, 0.0]\n", head + selection);
  };
  EXPECT_FALSE(error_of(pressure("face = \"left\"\n")).has_value());
  EXPECT_FALSE(error_of(pressure("")).has_value());
  EXPECT_FALSE(
      error_of(pressure("box = { x = [-0.01, -0.005], y = [-0.04, 0.04] }\n")).has_value());
  EXPECT_FALSE(error_of(pressure("half_plane = { point = [-0.003, 0.0], normal = [-1.0, 0.0] }\n"))
                   .has_value());
  EXPECT_INPUT_ERROR(pressure("face = \"front\"\n"),
                     {"bad.toml", "loads.shock.face", "front", "bottom, right, top, left"});
  EXPECT_INPUT_ERROR(pressure("box = { x = [0.2, 0.3], y = [0.0, 0.1] }\n"),
                     {"bad.toml", "loads.shock.box", "selects no part of bodies.plate's surface",
                      "x = [-0.006, 0]"});
  EXPECT_INPUT_ERROR(
      pressure("face = \"left\"\nhalf_plane = { point = [0.0, 0.0], normal = [1.0, 0.0] }\n"),
      {"bad.toml", "loads.shock.half_plane", "one of face, box and half_plane"});
  EXPECT_INPUT_ERROR(pressure("half_plane = { point = [0.0, 0.0], normal = [0.0, 0.0] }\n"),
                     {"bad.toml", "loads.shock.half_plane.normal", "[0, 0]"});
  EXPECT_INPUT_ERROR(pressure("box = { x = [0.2, 0.1], y = [0.0, 0.1] }\n"),
                     {"bad.toml", "loads.shock.box.x", "x0 <= x1"});
  EXPECT_INPUT_ERROR(edit("type = \"step\"\nbody = \"plate\"\nforce = [11200.0, 0.0]\n",
                          head + "face = \"left\"\nforce = [1.0, 0.0]\n"),
                     {"bad.toml", "force"});
  // A circle has no named faces; a hole that touches the edge leaves no
  // separate loops to put a pressure on.
  const std::string disk =
      "[bodies.disk]\nkind = \"elastic\"\nmaterial = \"rubber\"\nshape = "
      "\"circle\"\ncenter = [0.3, 0.0]\nradius = 0.01\n";
  const std::string on_disk =
      "\n[loads.blast]\ntype = \"pressure\"\nbody = \"disk\"\npressure = 1e5\n";
  EXPECT_INPUT_ERROR(base_toml() + disk + on_disk + "face = \"left\"\n",
                     {"bad.toml", "loads.blast.face", "circle", "box or half_plane"});
  const std::string notched =
      "[bodies.disk]\nkind = \"elastic\"\nmaterial = \"rubber\"\nx = "
      "[0.3, 0.32]\ny = [0.0, 0.01]\nholes = [{ shape = \"circle\", "
      "center = [0.31, 0.008], radius = 0.002 }]\n";
  EXPECT_INPUT_ERROR(base_toml() + notched + on_disk,
                     {"bad.toml", "loads.blast.body", "the body's edge and hole 1 touch"});
  // A polygon's faces are its edges, numbered as written.
  const std::string poly =
      "[bodies.disk]\nkind = \"elastic\"\nmaterial = \"rubber\"\nshape = "
      "\"polygon\"\nvertices = [[0.3, 0.0], [0.32, 0.0], [0.31, 0.02]]\n";
  EXPECT_FALSE(error_of(base_toml() + poly + on_disk + "face = 3\n").has_value());
  EXPECT_INPUT_ERROR(base_toml() + poly + on_disk + "face = 4\n",
                     {"bad.toml", "loads.blast.face", "1 to 3"});
}

TEST(CaseErrors, DampingNeedsACoefficientAndAWindow) {
  EXPECT_FALSE(
      error_of(base_toml() + "\n[damping]\ncoefficient = 100.0\nend = 1e-3\n").has_value());
  EXPECT_INPUT_ERROR(base_toml() + "\n[damping]\ncoefficient = 0.0\nend = 1e-3\n",
                     {"bad.toml", "damping.coefficient", "(0, inf) 1/s"});
  EXPECT_INPUT_ERROR(base_toml() + "\n[damping]\ncoefficient = 100.0\nstart = 2e-3\nend = 1e-3\n",
                     {"bad.toml", "damping.end", "after start"});
  EXPECT_INPUT_ERROR(base_toml() + "\n[damping]\ncoefficient = 100.0\n",
                     {"bad.toml", "damping.end"});
  EXPECT_INPUT_ERROR(base_toml() + "\n[damping]\ncoefficient = 100.0\nend = 1e-3\nalpha = 1\n",
                     {"bad.toml", "damping", "alpha"});
}

TEST(CaseErrors, OnlyWallsAndRigidBodiesAreDriven) {
  EXPECT_FALSE(
      error_of(base_toml() + "\n[bodies.wall.motion]\nvelocity = [-1.0, 0.0]\n").has_value());
  EXPECT_INPUT_ERROR(base_toml() + "\n[bodies.rod.motion]\nvelocity = [1.0, 0.0]\n",
                     {"bad.toml", "bodies.rod.motion", "only a wall or a rigid body"});
  EXPECT_INPUT_ERROR(base_toml() + "\n[bodies.plate.motion]\nspin = 1.0\n",
                     {"bad.toml", "bodies.plate.motion.velocity"});
  EXPECT_INPUT_ERROR(edit("x = [-0.006, 0.0]", "x = [-0.006, 0.0]\nvelocity = [1.0, 0.0]") +
                         "\n[bodies.plate.motion]\nvelocity = [1.0, 0.0]\n",
                     {"bad.toml", "bodies.plate.velocity", "motion.velocity"});
  EXPECT_INPUT_ERROR(base_toml() +
                         "\n[bodies.plate.motion]\nvelocity = [1.0, 0.0]\nhistory = "
                         "\"ramp\"\n",
                     {"bad.toml", "bodies.plate.motion.rise_time"});
}

TEST(CaseErrors, VertexFileProblemsNameTheLine) {
  const std::string good =
      testing::write_temp_file("good.csv", "x,y\n0.3,0\n# a comment\n0.4, 0\n\n0.35 0.05\n");
  EXPECT_FALSE(
      error_of(with_body("shape = \"polygon\"\nvertices_file = \"" + good + "\"")).has_value());
  const std::string bad = testing::write_temp_file("bad.csv", "x,y\n0.3,0\n0.4,zero\n0.35,0.05\n");
  EXPECT_INPUT_ERROR(with_body("shape = \"polygon\"\nvertices_file = \"" + bad + "\""),
                     {bad + ":3:", "bodies.extra.vertices_file", "two finite numbers", "0.4,zero"});
  EXPECT_INPUT_ERROR(with_body("shape = \"polygon\"\nvertices_file = \"" + ::testing::TempDir() +
                               "/missing.csv\""),
                     {"missing.csv", "bodies.extra.vertices_file", "cannot read"});
}

// ---- references between tables ---------------------------------------------

TEST(CaseErrors, LoadOnAMissingBody) {
  EXPECT_INPUT_ERROR(edit("body = \"plate\"", "body = \"plat\""),
                     {"bad.toml", "loads.shock.body", "plat", "plate, rod, wall"});
}

TEST(CaseErrors, LoadOnAWall) {
  EXPECT_INPUT_ERROR(edit("body = \"plate\"", "body = \"wall\""),
                     {"bad.toml", "loads.shock.body", "wall", "walls do not move"});
}

TEST(CaseErrors, ContactKeysOutOfRange) {
  for (const auto& [set, key, allowed] :
       {std::tuple{"contact.distance=0.4", "contact.distance", "[0.5, 1.5] lattice spacings"},
        {"contact.distance=1.6", "contact.distance", "[0.5, 1.5] lattice spacings"},
        {"contact.skin=0", "contact.skin", "(0, 2] lattice spacings"},
        {"contact.stiffness=-1e6", "contact.stiffness", "(0, inf) Pa"},
        {"contact.min_distance=1", "contact.min_distance", "[0.5, 1) contact distances"},
        {"contact.min_distance=0.3", "contact.min_distance", "[0.5, 1) contact distances"}})
    EXPECT_INPUT_ERROR(base_toml(), {"contact.", key, allowed}, {set});
  EXPECT_INPUT_ERROR(base_toml(), {"contact.friction", "unknown key", "distance"},
                     {"contact.friction=0.3"});
}

TEST(CaseErrors, ContactBodiesMustBeKnownDistinctAndNotOnlyWalls) {
  EXPECT_INPUT_ERROR(base_toml(), {"contact.bodies", "unknown body 'rdo'", "plate, rod, wall"},
                     {"contact.bodies=[\"rdo\"]"});
  EXPECT_INPUT_ERROR(base_toml(), {"contact.bodies", "twice"},
                     {"contact.bodies=[\"rod\", \"rod\"]"});
  EXPECT_INPUT_ERROR(base_toml(), {"contact.bodies", "non-empty array"}, {"contact.bodies=[]"});
  EXPECT_INPUT_ERROR(base_toml(), {"contact.bodies", "only walls"}, {"contact.bodies=[\"wall\"]"});
  const CaseSpec two =
      load_case_text(base_toml(), "ok.toml", {"contact.bodies=[\"wall\", \"rod\"]"});
  EXPECT_TRUE(two.contact.enabled);
  EXPECT_EQ(two.contact.bodies, (std::vector<int>{1, 2}));  // rod, wall (name order)
  // The default stiffness: the rubber's lambda + mu.
  const Material& rubber = two.materials.at(0);
  EXPECT_DOUBLE_EQ(two.contact.stiffness, rubber.lambda() + rubber.mu());
  const CaseSpec off = load_case_text(base_toml(), "ok.toml", {"contact.enabled=false"});
  EXPECT_FALSE(off.contact.enabled);
  EXPECT_FALSE(load_case_text(base_toml(), "ok.toml").contact.enabled);
}

TEST(CaseErrors, BodyWithAnUnknownMaterial) {
  EXPECT_INPUT_ERROR(
      edit("kind = \"elastic\"\nmaterial = \"rubber\"", "kind = \"elastic\"\nmaterial = \"steel\""),
      {"bad.toml", "bodies.rod.material", "steel", "defined: rubber"});
}

TEST(CaseErrors, UnknownBodyKind) {
  EXPECT_INPUT_ERROR(edit("kind = \"elastic\"", "kind = \"plastic\""),
                     {"bad.toml", "bodies.rod.kind", "plastic", "elastic, rigid, wall"});
}

TEST(CaseErrors, UnknownModel) {
  EXPECT_INPUT_ERROR(edit("model = \"paper\"", "model = \"papr\""),
                     {"bad.toml", "model", "papr", "allowed: paper"});
}

TEST(CaseErrors, UnknownLoadType) {
  EXPECT_INPUT_ERROR(edit("type = \"step\"", "type = \"ramp\""),
                     {"bad.toml", "loads.shock.type", "ramp", "allowed: step"});
}

// ---- syntax and files -------------------------------------------------------

TEST(CaseErrors, TomlSyntaxErrorHasTheLine) {
  // Line 8 of the base case: "nu = 0.495" becomes "nu = 0.495 0.4".
  const auto message = error_of(edit("nu = 0.495", "nu = 0.495 0.4"));
  ASSERT_TRUE(message.has_value());
  EXPECT_NE(message->find("bad.toml"), std::string::npos) << *message;
  EXPECT_NE(message->find("syntax error"), std::string::npos) << *message;
  // The line number: "bad.toml:8" or toml11's " 8 | nu = ..." excerpt.
  EXPECT_TRUE(std::regex_search(*message, std::regex(R"((bad\.toml:8\b)|(\b8 *\|))")))
      << "no line number 8 in:\n"
      << *message;
}

TEST(CaseErrors, TomlSyntaxErrors) {
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"rho = 1010.0", "rho = "},              // no value
           {"[time]", "[time"},                     // unclosed header
           {"E = 2.8e6", "E = 2.8e6\nE = 2.9e6"},   // duplicate key
           {"x = [0.0, 0.100]", "x = [0.0, 0.100"}  // unclosed array
       }) {
    SCOPED_TRACE(to);
    expect_error(edit(from, to), {"bad.toml", "syntax error"});
  }
}

TEST(CaseErrors, MissingFileNamesThePath) {
  const std::string path = std::string(MPSOLID_SOURCE_DIR) + "/cases/no_such_case.toml";
  try {
    load_case(path);
    FAIL() << "read_case accepted a missing file";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("no such file"), std::string::npos) << message;
  }
}

TEST(CaseErrors, DirectoryInsteadOfAFile) {
  const std::string path = std::string(MPSOLID_SOURCE_DIR) + "/cases";
  try {
    load_case(path);
    FAIL() << "read_case accepted a directory";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is a folder, not a case file"), std::string::npos)
        << e.what();
  }
}

// ---- --set overrides --------------------------------------------------------

TEST(OverrideErrors, MalformedSet) {
  for (const char* bad : {"time.end", "=5", "time.end="}) {
    SCOPED_TRACE(bad);
    expect_error(base_toml(), {"--set", std::string("'") + bad + "'", "KEY=VALUE"}, {bad});
  }
  for (const char* bad : {"time..end=1", ".end=1", "time.=1", "time end=1"}) {
    SCOPED_TRACE(bad);
    expect_error(base_toml(), {"--set", std::string("'") + bad + "'", "dotted path"}, {bad});
  }
}

TEST(OverrideErrors, WrongValueTypeMentionsTheSet) {
  EXPECT_INPUT_ERROR(base_toml(), {"--set", "time.dt=abc", "time.dt", "expected a number"},
                     {"time.dt=abc"});
  EXPECT_INPUT_ERROR(base_toml(), {"--set", "model=3", "model", "expected a string"}, {"model=3"});
}

TEST(OverrideErrors, OutOfRangeValueMentionsTheSet) {
  EXPECT_INPUT_ERROR(base_toml(), {"--set", "materials.rubber.nu", "(-1, 0.5)"},
                     {"materials.rubber.nu=0.7"});
}

TEST(OverrideErrors, UnknownKeyMentionsTheSet) {
  EXPECT_INPUT_ERROR(base_toml(), {"--set", "time.dtt", "unknown key", "dt, safety, end"},
                     {"time.dtt=1e-8"});
  EXPECT_INPUT_ERROR(base_toml(), {"--set", "tmie", "unknown key"}, {"tmie.end=1"});
}

TEST(OverrideErrors, KeyUnderAValue) {
  EXPECT_INPUT_ERROR(base_toml(), {"--set", "l0.x=1", "'l0' is a value"}, {"l0.x=1"});
  EXPECT_INPUT_ERROR(base_toml(), {"--set", "'x' is a value"}, {"bodies.rod.x.0=1"});
}

// ---- good input -------------------------------------------------------------

TEST(GoodCases, ShippedCasesParse) {
  const CaseSpec rod = load_case(shipped("shock_rod.toml"));
  EXPECT_EQ(rod.name, "shock_rod");
  EXPECT_EQ(rod.model, "paper");
  EXPECT_DOUBLE_EQ(rod.l0, 0.002);
  ASSERT_EQ(rod.bodies.size(), 3u);
  ASSERT_EQ(rod.loads.size(), 1u);
  EXPECT_DOUBLE_EQ(rod.loads[0].force[0], 11200.0);
  EXPECT_EQ(rod.step_count(), 1000000);
  EXPECT_EQ(rod.steps_per_frame(), 100000);

  const CaseSpec strong = load_case(shipped("shock_rod_55kN.toml"));
  EXPECT_EQ(strong.name, "shock_rod_55kN");
  EXPECT_EQ(strong.model, "finite_strain");
  ASSERT_EQ(strong.loads.size(), 1u);
  EXPECT_DOUBLE_EQ(strong.loads[0].force[0], 55900.0);
  EXPECT_EQ(strong.step_count(), 1000000);
  EXPECT_EQ(strong.steps_per_frame(), 100000);
  // The experiment's geometry: contact on, a wall three times the rod's height.
  EXPECT_TRUE(strong.contact.enabled);
  EXPECT_EQ(strong.contact.bodies.size(), 3u);
  EXPECT_DOUBLE_EQ(std::get<RectangleRegion>(strong.bodies.at(2).shape.region).y[1], 0.060);

  const CaseSpec paper_geometry = load_case(shipped("shock_rod_55kN_short_wall.toml"));
  EXPECT_FALSE(paper_geometry.contact.enabled);
  EXPECT_DOUBLE_EQ(std::get<RectangleRegion>(paper_geometry.bodies.at(2).shape.region).y[1], 0.020);
  EXPECT_TRUE(load_case(shipped("colliding_blocks.toml")).contact.enabled);
}

TEST(GoodCases, OverridesApply) {
  const CaseSpec fine = load_case(shipped("shock_rod.toml"), {"l0=0.001"});
  EXPECT_DOUBLE_EQ(fine.l0, 0.001);

  const CaseSpec shorter = load_case(shipped("shock_rod.toml"), {"time.end=0.002"});
  EXPECT_DOUBLE_EQ(shorter.end, 0.002);
  EXPECT_EQ(shorter.step_count(), 200000);

  const CaseSpec bare = load_case(shipped("shock_rod.toml"), {"model=paper"});
  EXPECT_EQ(bare.model, "paper");

  const CaseSpec strong =
      load_case(shipped("shock_rod.toml"), {"loads.shock.force=[55900.0, 0.0]"});
  ASSERT_EQ(strong.loads.size(), 1u);
  EXPECT_DOUBLE_EQ(strong.loads[0].force[0], 55900.0);
  EXPECT_DOUBLE_EQ(strong.loads[0].force[1], 0.0);

  // Several at once; the last one of a key wins.
  const CaseSpec several =
      load_case(shipped("shock_rod.toml"),
                {"time.end=0.002", "output.frame_interval=1e-4", "time.end=0.003"});
  EXPECT_DOUBLE_EQ(several.end, 0.003);
  EXPECT_DOUBLE_EQ(several.frame_interval, 1e-4);
}

TEST(GoodCases, OverrideCreatesAMissingTable) {
  const std::string text = edit("[output]\nframe_interval = 1.0e-3\n", "");
  const CaseSpec spec = load_case_text(text, "bad.toml", {"output.frame_interval=2e-3"});
  EXPECT_DOUBLE_EQ(spec.frame_interval, 2e-3);
}

TEST(GoodCases, IntegersAreAcceptedForNumbers) {
  const CaseSpec spec = load_case(shipped("shock_rod.toml"), {"time.end=1"});
  EXPECT_DOUBLE_EQ(spec.end, 1.0);
  const CaseSpec ints = load_case_text(
      edit(edit("E = 2.8e6", "E = 2800000"), "force = [11200.0, 0.0]", "force = [11200, 0]"),
      "bad.toml");
  EXPECT_DOUBLE_EQ(ints.materials.at(0).youngs_modulus, 2.8e6);
  EXPECT_DOUBLE_EQ(ints.loads.at(0).force[0], 11200.0);
}

TEST(GoodCases, DefaultsFillIn) {
  // No depth, no model, no [output], no load start, no load type.
  std::string text = edit("model = \"paper\"\n", "");
  text = edit(text, "depth = 1.0\n", "");
  text = edit(text, "[output]\nframe_interval = 1.0e-3\n", "");
  text = edit(text, "start = 0.0\n", "");
  text = edit(text, "type = \"step\"\n", "");
  const CaseSpec spec = load_case_text(text, "bad.toml");
  EXPECT_EQ(spec.model, "paper");
  EXPECT_DOUBLE_EQ(spec.depth, 1.0);
  EXPECT_DOUBLE_EQ(spec.frame_interval, spec.end / 10);
  EXPECT_DOUBLE_EQ(spec.loads.at(0).start, 0.0);
}

TEST(GoodCases, NameDefaultsToTheFileStem) {
  const CaseSpec spec = load_case_text(edit("name = \"base\"\n", ""), "some/dir/my_case.toml");
  EXPECT_EQ(spec.name, "my_case");
}

void expect_same_case(const CaseSpec& a, const CaseSpec& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.l0, b.l0);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_EQ(a.dt, b.dt);
  EXPECT_EQ(a.end, b.end);
  EXPECT_EQ(a.frame_interval, b.frame_interval);
  EXPECT_EQ(a.step_count(), b.step_count());
  EXPECT_EQ(a.contact.enabled, b.contact.enabled);
  if (a.contact.enabled) {
    EXPECT_EQ(a.contact.distance, b.contact.distance);
    EXPECT_EQ(a.contact.skin, b.contact.skin);
    EXPECT_EQ(a.contact.stiffness, b.contact.stiffness);
    EXPECT_EQ(a.contact.min_distance, b.contact.min_distance);
    EXPECT_EQ(a.contact.bodies, b.contact.bodies);
  }
  EXPECT_EQ(a.steps_per_frame(), b.steps_per_frame());
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t k = 0; k < a.materials.size(); ++k) {
    EXPECT_EQ(a.materials[k].name, b.materials[k].name);
    EXPECT_EQ(a.materials[k].youngs_modulus, b.materials[k].youngs_modulus);
    EXPECT_EQ(a.materials[k].poisson_ratio, b.materials[k].poisson_ratio);
    EXPECT_EQ(a.materials[k].density, b.materials[k].density);
  }
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    SCOPED_TRACE(a.bodies[k].name);
    EXPECT_EQ(a.bodies[k].name, b.bodies[k].name);
    EXPECT_EQ(a.bodies[k].kind, b.bodies[k].kind);
    EXPECT_EQ(a.bodies[k].material, b.bodies[k].material);
    EXPECT_TRUE(a.bodies[k].shape == b.bodies[k].shape);
    for (int e = 0; e < 2; ++e) EXPECT_EQ(a.bodies[k].velocity[e], b.bodies[k].velocity[e]);
    EXPECT_EQ(a.bodies[k].spin[2], b.bodies[k].spin[2]);
    EXPECT_EQ(a.bodies[k].hold, b.bodies[k].hold);
    EXPECT_EQ(a.bodies[k].has_mode, b.bodies[k].has_mode);
    EXPECT_EQ(a.bodies[k].mode.root_x, b.bodies[k].mode.root_x);
    EXPECT_EQ(a.bodies[k].mode.length, b.bodies[k].mode.length);
    EXPECT_EQ(a.bodies[k].mode.kl, b.bodies[k].mode.kl);
    EXPECT_EQ(a.bodies[k].mode.tip_velocity, b.bodies[k].mode.tip_velocity);
  }
  ASSERT_EQ(a.probes.size(), b.probes.size());
  for (std::size_t k = 0; k < a.probes.size(); ++k) {
    EXPECT_EQ(a.probes[k].name, b.probes[k].name);
    EXPECT_EQ(a.probes[k].at[0], b.probes[k].at[0]);
    EXPECT_EQ(a.probes[k].at[1], b.probes[k].at[1]);
  }
  EXPECT_EQ(a.dt_auto, b.dt_auto);
  EXPECT_EQ(a.dt_safety, b.dt_safety);
  EXPECT_EQ(a.history_interval, b.history_interval);
  ASSERT_EQ(a.loads.size(), b.loads.size());
  for (std::size_t k = 0; k < a.loads.size(); ++k) {
    EXPECT_EQ(a.loads[k].name, b.loads[k].name);
    EXPECT_EQ(a.loads[k].body, b.loads[k].body);
    EXPECT_EQ(a.loads[k].force[0], b.loads[k].force[0]);
    EXPECT_EQ(a.loads[k].force[1], b.loads[k].force[1]);
    EXPECT_EQ(a.loads[k].start, b.loads[k].start);
  }
}

TEST(GoodCases, ResolvedTomlReadsBackAsTheSameCase) {
  for (const Strings& overrides :
       {Strings{}, Strings{"l0=0.001", "time.end=0.002", "loads.shock.force=[55900.0, 0.0]"},
        Strings{"time.dt=3e-9", "depth=0.01"},
        Strings{"contact.enabled=true", "contact.bodies=[\"rod\", \"wall\"]", "contact.skin=0.3",
                "contact.stiffness=2.5e7"},
        Strings{"time.dt=\"auto\"", "time.safety=0.3", "output.history_interval=1e-4",
                "probes.tip.at=[0.099, 0.0]", "bodies.rod.velocity=[1.0, -2.0]",
                "bodies.rod.spin=3.0", "bodies.rod.hold=\"y\"",
                "bodies.rod.bending_mode={root_x=0.0, length=0.1, tip_velocity=0.5}"}}) {
    SCOPED_TRACE(overrides.empty() ? std::string("no overrides") : overrides.front());
    const CaseSpec original = load_case(shipped("shock_rod.toml"), overrides);
    const CaseSpec again = load_case_text(original.resolved_toml, "case.resolved.toml");
    expect_same_case(original, again);
    // Resolving is idempotent.
    EXPECT_EQ(load_case_text(again.resolved_toml, "case.resolved.toml").resolved_toml,
              again.resolved_toml);
  }
}

TEST(GoodCases, ResolvedTomlReadsBackWithUnusualNames) {
  // TOML allows any quoted key and any string; the reader must either refuse
  // such names with an InputError or write a resolved TOML that reads back.
  std::string text = edit("name = \"base\"", "name = \"my \\\"quoted\\\" case\"");
  text = edit(text, "[bodies.rod]", "[bodies.\"the rod\"]");
  text = edit(text, "[materials.rubber]", "[materials.\"rubber.soft\"]");
  for (const char* from : {"material = \"rubber\"\nx = [0.0", "material = \"rubber\"\nx = [-0.006",
                           "material = \"rubber\"\nx = [0.100"})
    text = edit(text, from, edit(from, "\"rubber\"", "\"rubber.soft\""));
  text += "\n[contact]\nbodies = [\"the rod\", \"wall\"]\n";
  CaseSpec original;
  try {
    original = load_case_text(text, "odd.toml");
  } catch (const InputError& e) {
    SUCCEED() << "refused: " << e.what();
    return;
  }
  try {
    const CaseSpec again = load_case_text(original.resolved_toml, "case.resolved.toml");
    expect_same_case(original, again);
  } catch (const InputError& e) {
    ADD_FAILURE() << "the case was accepted but its resolved TOML does not read back: " << e.what()
                  << "\nresolved TOML:\n"
                  << original.resolved_toml;
  }
}

// ---- [gas] -------------------------------------------------------------------

// The base case in a shock tube: every body inside the grid.
std::string gas_toml() {
  return base_toml() + R"(
[gas]
cell = 0.002
x = [-0.05, 0.11]
y = [-0.04, 0.04]
left = "inflow"

[gas.initial]
density = 1.2
pressure = 101325.0

[gas.shock]
mach = 1.5
x = -0.03

[gas.probes.front]
at = [-0.01, 0.0]
)";
}

std::string gas_edit(const std::string& from, const std::string& to) {
  return edit(gas_toml(), from, to);
}

TEST(CaseErrors, TheGasCaseIsValidAndReadsBackResolved) {
  const CaseSpec spec = load_case_text(gas_toml(), "gas.toml");
  ASSERT_TRUE(spec.gas.enabled);
  EXPECT_EQ(spec.gas.bodies.size(), 3u);  // every body over the grid
  EXPECT_EQ(spec.gas.reference_pressure, 101325.0);
  EXPECT_EQ(spec.gas.edges[0][0], GasSpec::Edge::inflow);
  const CaseSpec again = load_case_text(spec.resolved_toml, "resolved.toml");
  // The same case but for the first line, which names the file it came from.
  const auto body = [](const std::string& t) { return t.substr(t.find('\n')); };
  EXPECT_EQ(body(again.resolved_toml), body(spec.resolved_toml));
  EXPECT_EQ(again.gas.mach, 1.5);
  ASSERT_EQ(again.gas.probes.size(), 1u);
}

TEST(CaseErrors, GasGridNeedsAWholeNumberOfCellsAndCellsNoCoarserThanTheThinnestBody) {
  EXPECT_INPUT_ERROR(gas_edit("cell = 0.002", "cell = 0.0"), {"bad.toml", "gas.cell", "(0, inf)"});
  EXPECT_INPUT_ERROR(gas_edit("x = [-0.05, 0.11]", "x = [-0.05, 0.1107]"),
                     {"bad.toml", "gas.x", "whole number"});
  EXPECT_INPUT_ERROR(gas_edit("y = [-0.04, 0.04]", "y = [0.04, -0.04]"),
                     {"bad.toml", "gas.y", "y0 < y1"});
  // The wall is 4 mm thin.
  EXPECT_INPUT_ERROR(gas_edit("cell = 0.002", "cell = 0.005"),
                     {"bad.toml", "gas.cell", "'wall'", "0.004"});
  EXPECT_INPUT_ERROR(gas_edit("cell = 0.002", "cell = 0.002\ncfl = 1.5"),
                     {"bad.toml", "gas.cfl", "(0, 1]"});
  EXPECT_INPUT_ERROR(gas_edit("cell = 0.002", "cell = 0.002\ngamma = 1.0"),
                     {"bad.toml", "gas.gamma", "(1, 10)"});
  EXPECT_INPUT_ERROR(gas_edit("left = \"inflow\"", "left = \"open\""),
                     {"bad.toml", "gas.left", "slip_wall, inflow, outflow"});
  EXPECT_INPUT_ERROR(gas_edit("cell = 0.002", "cell = 0.002\ncolour = 1"),
                     {"bad.toml", "gas", "colour"});
}

TEST(CaseErrors, GasStatesNeedPositiveDensityAndPressureAndAShockAMachNumberAboveOne) {
  EXPECT_INPUT_ERROR(gas_edit("density = 1.2", "density = -1.2"),
                     {"bad.toml", "gas.initial.density", "(0, inf)"});
  EXPECT_INPUT_ERROR(gas_edit("pressure = 101325.0", "pressure = 0.0"),
                     {"bad.toml", "gas.initial.pressure", "(0, inf)"});
  EXPECT_INPUT_ERROR(gas_edit("mach = 1.5", "mach = 1.0"),
                     {"bad.toml", "gas.shock.mach", "(1, 50)"});
  EXPECT_INPUT_ERROR(gas_edit("x = -0.03", "x = -0.3"),
                     {"bad.toml", "gas.shock.x", "inside the grid"});
  EXPECT_INPUT_ERROR(gas_edit("pressure = 101325.0", "pressure = 101325.0\nvelocity = [10.0, 0.0]"),
                     {"bad.toml", "gas.shock.mach", "at rest"});
  // An inflow edge with neither a shock nor an inflow state.
  EXPECT_INPUT_ERROR(gas_edit("[gas.shock]\nmach = 1.5\nx = -0.03\n", ""),
                     {"bad.toml", "gas.left", "[gas.inflow]"});
}

TEST(CaseErrors, GasBodiesAndProbesMustBeInsideTheGrid) {
  EXPECT_INPUT_ERROR(gas_edit("left = \"inflow\"", "left = \"inflow\"\nbodies = [\"nobody\"]"),
                     {"bad.toml", "gas.bodies", "unknown body 'nobody'"});
  EXPECT_INPUT_ERROR(gas_edit("x = [-0.05, 0.11]\ny = [-0.04, 0.04]",
                              "x = [-0.05, 0.11]\ny = [-0.04, 0.04]\nbodies = [\"rod\", \"rod\"]"),
                     {"bad.toml", "gas.bodies", "twice"});
  EXPECT_INPUT_ERROR(gas_edit("at = [-0.01, 0.0]", "at = [-0.01, 0.5]"),
                     {"bad.toml", "gas.probes.front.at", "outside the gas grid"});
  // A grid upstream of every body, told to push the rod.
  const std::string upstream =
      edit(gas_edit("x = [-0.05, 0.11]", "x = [-0.05, -0.01]\nbodies = [\"rod\"]"),
           "at = [-0.01, 0.0]", "at = [-0.02, 0.0]");
  EXPECT_INPUT_ERROR(upstream, {"bad.toml", "gas.bodies", "'rod' lies outside the gas grid"});
}

}  // namespace
}  // namespace mpsolid
