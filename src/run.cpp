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

namespace mpsolid {

namespace {
bool finite(const Diagnostics& d) {
  return std::isfinite(d.kinetic_energy) && std::isfinite(d.strain_energy) &&
         std::isfinite(d.max_speed) && std::isfinite(d.angular_momentum);
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

  // Writes the current state as a frame; false if it is not finite.
  auto write_frame = [&]() {
    const Diagnostics d = sim.diagnostics();  // refreshes strain and pressure
    if (!finite(d)) return false;
    auto t = sim.timers().time(Phase::output);
    history.write(sim, d);
    frames.write(sim);
    return true;
  };

  const std::int64_t total = spec.step_count();
  const std::int64_t cadence = spec.steps_per_frame();
  Progress progress(total, spec.dt, options.progress);
  write_frame();
  constexpr std::int64_t kProgressChunk = 2000;
  while (sim.step() < total) {
    const std::int64_t next_frame = std::min(total, (sim.step() / cadence + 1) * cadence);
    while (sim.step() < next_frame) {
      sim.advance(std::min(kProgressChunk, next_frame - sim.step()));
      progress.update(sim.step());
    }
    if (!write_frame()) {
      facts.outcome = "unstable";
      break;
    }
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
               "mpsolid: the state became non-finite between t = {:.6g} s and t = {:.6g} s; the "
               "last good frame is in {}\n",
               sim.time() - static_cast<double>(cadence) * spec.dt, sim.time(),
               (options.out_dir / "frames.h5").string());
    return kExitUnstable;
  }
  return kExitOk;
}

}  // namespace mpsolid
