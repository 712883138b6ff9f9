#include "src/run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "src/atomic_file.hpp"
#include "src/hdf5_writer.hpp"
#include "src/history_writer.hpp"
#include "src/parallel.hpp"
#include "src/progress.hpp"
#include "src/run_report.hpp"
#include "src/simulation.hpp"
#include "src/state_snapshot.hpp"

namespace mpsolid {

namespace {
std::string body_of(const Simulation& sim, std::size_t i) {
  return sim.spec().bodies[static_cast<std::size_t>(sim.particles().body[i])].name;
}

std::string describe_particle(const Simulation& sim, std::size_t i) {
  const ParticleStore& p = sim.particles();
  return fmt::format(
      "particle {} (body {}, initial position ({:.4g}, {:.4g}) mm, now ({:.4g}, "
      "{:.4g}) mm)",
      p.id[i], body_of(sim, i), 1e3 * p.x0[i], 1e3 * p.y0[i], 1e3 * p.x[i], 1e3 * p.y[i]);
}

// Where, when and which criterion, in words (the state is the failing one).
std::string describe_failure(const Simulation& sim, const StabilityVerdict& v,
                             std::int64_t last_good_step) {
  std::string text = fmt::format(
      "{} at t = {:.6g} s (step {}, checked every {} steps; last good "
      "check at step {}): {}",
      v.criterion, sim.time(), sim.step(), sim.spec().stability.check_interval, last_good_step,
      describe_particle(sim, v.particle));
  if (v.has_neighbor) text += ", bonded to " + describe_particle(sim, v.neighbor);
  return text;
}

std::string failure_json(const Simulation& sim, const StabilityVerdict& v,
                         std::int64_t last_good_step) {
  const ParticleStore& p = sim.particles();
  const std::size_t i = v.particle;
  return fmt::format(
      "{{\"criterion\": \"{}\", \"time\": {:.17g}, \"step\": {}, \"particle_id\": {}, "
      "\"body\": \"{}\", \"initial_position\": [{:.17g}, {:.17g}], \"position\": [{:.17g}, "
      "{:.17g}], \"neighbor_id\": {}, \"value\": {:.17g}, \"last_good_step\": {}, "
      "\"last_good_time\": {:.17g}}}",
      v.criterion, sim.time(), sim.step(), p.id[i], body_of(sim, i), p.x0[i], p.y0[i], p.x[i],
      p.y[i], v.has_neighbor ? std::to_string(p.id[v.neighbor]) : "null", v.value, last_good_step,
      static_cast<double>(last_good_step) * sim.spec().dt);
}

void print_summary(const Simulation& sim, const RunFacts& facts, const RunOptions& options) {
  const double rate =
      facts.wall_seconds > 0 ? static_cast<double>(facts.steps) / facts.wall_seconds : 0;
  fmt::print("mpsolid: {} ({} model) {}: {} steps to t = {:.6g} s in {:.3g} s wall, {} threads\n",
             sim.spec().name, sim.spec().model, facts.outcome, facts.steps, sim.time(),
             facts.wall_seconds, facts.threads);
  fmt::print("  {} particles, {} bonds; {:.4g} steps/s, {:.4g} particle-steps/s\n",
             sim.particles().size(), sim.state().bonds.entry_count() / 2, rate,
             rate * static_cast<double>(sim.particles().size()));
  fmt::print("  {} frames, {:.3g} MB written ({:.3g} kB per frame) to {}\n", facts.frames,
             static_cast<double>(facts.bytes_written) / 1e6,
             facts.frames ? static_cast<double>(facts.bytes_written) / 1e3 / facts.frames : 0.0,
             options.out_dir.string());
  std::string table = "  phase seconds:";
  for (std::size_t k = 0; k < kPhaseNames.size(); ++k)
    table += fmt::format(" {} {:.3g}", kPhaseNames[k], sim.timers().seconds(static_cast<Phase>(k)));
  fmt::print("{}\n", table);
}
}  // namespace

int run_case(const CaseSpec& spec, const RunOptions& options) {
  set_thread_count(options.threads);
  const auto wall_start = std::chrono::steady_clock::now();
  std::filesystem::create_directories(options.out_dir);

  Simulation sim(spec);
  HistoryWriter history(options.out_dir / "history.csv", sim);
  FrameWriter frames(options.out_dir / "frames.h5", sim);

  RunFacts facts;
  facts.command_line = options.command_line;
  facts.threads = thread_count();

  // Writes the current state as a frame (its fields must be fresh).
  std::int64_t last_frame_step = -1;
  auto write_frame = [&](const Diagnostics& d) {
    auto t = sim.timers().time(Phase::output);
    history.write(sim, d);
    frames.write(sim);
    last_frame_step = sim.step();
  };

  const std::int64_t total = spec.step_count();
  const std::int64_t cadence = spec.steps_per_frame();
  const std::int64_t check_every = spec.stability.check_interval;
  Progress progress(total, spec.dt, options.progress);
  write_frame(sim.diagnostics());
  StateSnapshot last_good = StateSnapshot::capture(sim.state());
  constexpr std::int64_t kProgressChunk = 2000;
  while (sim.step() < total) {
    const std::int64_t next_frame = std::min(total, (sim.step() / cadence + 1) * cadence);
    const std::int64_t next_check =
        std::min(next_frame, (sim.step() / check_every + 1) * check_every);
    while (sim.step() < next_check) {
      sim.advance(std::min(kProgressChunk, next_check - sim.step()));
      progress.update(sim.step());
    }
    Diagnostics d;
    const StabilityVerdict verdict = sim.check_stability(&d);
    if (!verdict.ok) {
      progress.finish();
      facts.outcome = "unstable";
      facts.diagnosis = describe_failure(sim, verdict, last_good.step);
      facts.diagnosis_json = failure_json(sim, verdict, last_good.step);
      // Keep the last good state as the final frame of the outputs.
      last_good.restore(sim.state());
      if (sim.step() != last_frame_step) write_frame(sim.diagnostics());
      break;
    }
    last_good = StateSnapshot::capture(sim.state());
    if (sim.step() == next_frame) write_frame(d);
  }
  progress.finish();

  facts.steps = sim.step();
  facts.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  {
    auto t = sim.timers().time(Phase::output);
    history.publish();
    frames.publish();
    write_file_atomically(options.out_dir / "case.resolved.toml", spec.resolved_toml);
    facts.frames = frames.frames_written();
    facts.bytes_written = history.bytes_written() + frames.bytes_written();
  }
  write_file_atomically(options.out_dir / "run.json", run_report_json(sim, facts));
  print_summary(sim, facts, options);
  if (facts.outcome == "unstable") {
    fmt::print(stderr,
               "mpsolid: unstable: {}\n  The last good state (t = {:.6g} s) is the last "
               "frame of {} and {}.\n",
               facts.diagnosis, sim.time(), (options.out_dir / "history.csv").string(),
               (options.out_dir / "frames.h5").string());
    return kExitUnstable;
  }
  return kExitOk;
}

}  // namespace mpsolid
