#include "src/case/case_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "src/case/resolved_case.hpp"
#include "src/core/geometry.hpp"

namespace mpsolid {

std::int64_t CaseSpec::step_count() const {
  // Nearest whole step when end is a multiple of dt up to round-off, else the
  // first step at or past end.
  const double ratio = end / dt;
  const double nearest = std::round(ratio);
  if (std::abs(ratio - nearest) <= 1e-9 * std::max(1.0, ratio))
    return static_cast<std::int64_t>(nearest);
  return static_cast<std::int64_t>(std::ceil(ratio));
}

namespace {
// Whole steps in `interval`: the nearest count when it is a multiple of dt up
// to round-off, else rounded down; at least 1.
std::int64_t steps_in(double interval, double dt) {
  const double ratio = interval / dt;
  const double nearest = std::round(ratio);
  if (std::abs(ratio - nearest) <= 1e-9 * std::max(1.0, ratio))
    return std::max<std::int64_t>(1, static_cast<std::int64_t>(nearest));
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(ratio)));
}
}  // namespace

std::int64_t CaseSpec::steps_per_checkpoint() const {
  return checkpoint_interval > 0 ? steps_in(checkpoint_interval, dt) : 0;
}
std::int64_t CaseSpec::steps_per_frame() const {
  return steps_in(frame_interval, dt);
}
std::int64_t CaseSpec::steps_per_history() const {
  return std::min(steps_per_frame(), steps_in(history_interval, dt));
}

std::int64_t CaseSpec::particle_count() const {
  std::int64_t n = 0;
  for (const BodySpec& b : bodies) n += b.site_count(l0, dimension);
  return n;
}

namespace {
bool whole_steps(double ratio) {
  return std::abs(ratio - std::round(ratio)) <= 1e-9 * std::max(1.0, ratio);
}
}  // namespace

void CaseSpec::snap_default_history() {
  if (!history_default) return;
  history_interval = time_at(std::min(steps_per_frame(), steps_in(default_history_interval(), dt)));
}

std::vector<std::string> CaseSpec::check_step_grid() const {
  struct Span {
    const char* key;
    double seconds;
  };
  const Span spans[] = {{"time.end", end},
                        {"output.frame_interval", frame_interval},
                        {"output.history_interval", history_interval},
                        {"output.checkpoint_interval", checkpoint_interval}};
  for (const Span& span : spans)
    if (!(span.seconds / dt <= kMaxSteps))
      throw InputError(fmt::format(
          "{}: {} = {:.6g} s is {:.3g} steps of dt = {:.6g} s, more than a run can count exactly "
          "(at most 2^53 = {:.3g} steps): give {} <= {:.6g} s or a larger dt",
          source, span.key, span.seconds, span.seconds / dt, dt, kMaxSteps, span.key,
          kMaxSteps * dt));
  std::vector<std::string> found;
  if (const double ratio = end / dt; !whole_steps(ratio))
    found.push_back(fmt::format(
        "time.end = {:.9g} s is {:.9g} steps of dt = {:.9g} s: the run ends at the next whole "
        "step, {} (t = {:.9g} s)",
        end, ratio, dt, step_count(), time_at(step_count())));
  const auto interval_note = [&](const char* key, double seconds, std::int64_t steps,
                                 const char* what) {
    if (seconds <= 0 || whole_steps(seconds / dt)) return;
    found.push_back(
        fmt::format("{} = {:.9g} s is {:.9g} steps of dt = {:.9g} s: {} every {} steps ({:.9g} s)",
                    key, seconds, seconds / dt, dt, what, steps, time_at(steps)));
  };
  // history.csv gets a row every steps_per_history() steps and at the end.
  if (const std::int64_t rows = step_count() / steps_per_history() + 1; rows < kFewHistoryRows)
    found.push_back(fmt::format(
        "history.csv gets only {} rows (output.history_interval = {:.6g} s over time.end = "
        "{:.6g} s): set a smaller output.history_interval to resolve the run in time",
        rows, history_interval, end));
  interval_note("output.frame_interval", frame_interval, steps_per_frame(), "frames");
  interval_note("output.history_interval", history_interval, steps_per_history(), "history rows");
  return found;
}

void CaseSpec::set_auto_time_step(double limit, double omega_max) {
  // The finest requested output interval becomes a whole number of steps, so
  // outputs fall on the requested times whatever step is chosen; a defaulted
  // history interval follows the step instead of constraining it.
  const double finest =
      history_default ? frame_interval : std::min(history_interval, frame_interval);
  const double target = dt_safety * limit;
  dt = finest / std::ceil(finest / target * (1.0 - 1e-12));
  // The case was read with dt unknown; a run shorter than the step it chose
  // would not read back (its resolved case, a checkpoint's) any more.
  if (end < dt)
    throw InputError(fmt::format(
        "{}: time.end = {} s is shorter than the step time.dt = \"auto\" chose ({:.6g} s, with "
        "whole steps per output interval); allowed: time.end >= {:.6g} s (or give dt)",
        source, end, dt, dt));
  snap_default_history();
  // The resolved case keeps the chosen step as a number, so a resumed run
  // goes on with it rather than estimating again.
  resolved_toml = fmt::format(
      "# time.dt = \"auto\" chose {:.17g} s: the largest step <= safety {:.17g} x the model's\n"
      "# stability limit 2 / omega_max = {:.17g} s (omega_max = {:.17g} rad/s) with whole steps\n"
      "# per output.\n",
      dt, dt_safety, limit, omega_max);
  resolved_toml += resolved_case_toml(*this);
  if (checkpoint_interval > 0) checkpoint_interval = std::max(checkpoint_interval, dt);
  for (std::string& note : check_step_grid()) notes.push_back(std::move(note));
}

}  // namespace mpsolid
