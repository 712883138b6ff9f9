#include "src/app/run.hpp"
#include "src/distributed/communicator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <limits>
#include <new>
#include <optional>
#include <utility>

#include "src/app/memory_check.hpp"
#include "src/app/progress.hpp"
#include "src/app/signals.hpp"
#include "src/app/thread_governor.hpp"
#include "src/core/hash.hpp"
#include "src/core/parallel.hpp"
#include "src/io/atomic_file.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/folder_lock.hpp"
#include "src/io/run_folder.hpp"
#include "src/io/run_report.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"
#include "src/solver/time_step_choice.hpp"

namespace mpsolid {

namespace {
std::string body_name(Simulation& sim, const ParticleFacts& f) {
  return sim.spec().bodies[static_cast<std::size_t>(f.body)].name;
}

std::string in_mm(const std::vector<double>& position) {
  std::vector<std::string> parts;
  for (const double v : position) parts.push_back(fmt::format("{:.4g}", 1e3 * v));
  return fmt::format("({}) mm", fmt::join(parts, ", "));
}

std::string describe_particle(Simulation& sim, std::size_t i) {
  const ParticleFacts f = sim.particle_facts(i);
  return fmt::format("particle {} (body {}, initial position {}, now {})", f.id, body_name(sim, f),
                     in_mm(f.initial), in_mm(f.now));
}

// Where, when and which criterion, in words (the state is the failing one).
std::string describe_failure(Simulation& sim, const StabilityVerdict& v,
                             std::int64_t last_good_step) {
  if (!v.where.empty())
    return fmt::format("{} at t = {:.6g} s (step {}; last good check at step {}): {}", v.criterion,
                       sim.time(), sim.step(), last_good_step, v.where);
  std::string text = fmt::format(
      "{} at t = {:.6g} s (step {}, checked every {} steps; last good "
      "check at step {}): {}",
      v.criterion, sim.time(), sim.step(), sim.spec().stability.check_interval, last_good_step,
      describe_particle(sim, v.particle));
  if (v.has_neighbor)
    text += fmt::format(", {} {}", v.neighbor_role, describe_particle(sim, v.neighbor));
  return text;
}

Json failure_json(Simulation& sim, const StabilityVerdict& v, std::int64_t last_good_step) {
  if (!v.where.empty())
    return {{"criterion", v.criterion},
            {"time", sim.time()},
            {"step", sim.step()},
            {"where", v.where},
            {"last_good_step", last_good_step},
            {"last_good_time", sim.spec().time_at(last_good_step)}};
  const ParticleFacts f = sim.particle_facts(v.particle);
  return {{"criterion", v.criterion},
          {"time", sim.time()},
          {"step", sim.step()},
          {"particle_id", f.id},
          {"body", body_name(sim, f)},
          {"initial_position", f.initial},
          {"position", f.now},
          {"neighbor_id", v.has_neighbor ? Json(sim.particle_facts(v.neighbor).id) : Json(nullptr)},
          {"value", v.value},
          {"last_good_step", last_good_step},
          {"last_good_time", sim.spec().time_at(last_good_step)}};
}

// What run.json and a checkpoint read (over MPI ranks, rank 0's copy with
// its bodies, loads and step current: Simulation::checkpoint_source).
RunReportInputs report_inputs(Simulation& sim, const SolverState& state) {
  return {sim.spec(),        state,          sim.particle_count(), sim.bond_count(), sim.timers(),
          sim.stable_step(), sim.gas_saved()};
}

// A checkpoint of the current state, over MPI ranks each rank writing its
// own particles.
void write_checkpoint(Simulation& sim, RunFolder& outputs, const RunFacts& facts) {
  const Simulation::CheckpointSource source = sim.checkpoint_source();
  outputs.checkpoint(report_inputs(sim, source.state), facts, source.placer);
}

void print_summary(Simulation& sim, const RunFacts& facts, const RunOptions& options) {
  const double rate =
      facts.wall_seconds > 0 ? static_cast<double>(facts.steps) / facts.wall_seconds : 0;
  fmt::print("mpsolid: {} ({} model) {}: {} steps to t = {:.6g} s in {:.3g} s wall, {} threads\n",
             sim.spec().name, sim.spec().model, outcome_name(facts.outcome), facts.steps,
             sim.time(), facts.wall_seconds, facts.threads);
  fmt::print("  {} particles, {} bonds; {:.4g} steps/s, {:.4g} particle-steps/s\n",
             sim.particle_count(), sim.bond_count(), rate,
             rate * static_cast<double>(sim.particle_count()));
  if (const StableStepEstimate& e = sim.stable_step(); e.iterations > 0)
    fmt::print(
        "  dt = {:.6g} s (auto: safety {} x limit {:.6g} s, omega_max {:.6g} rad/s, {} power "
        "iterations{})\n",
        sim.spec().dt, sim.spec().dt_safety, e.dt_limit, e.omega_max, e.iterations,
        e.converged ? "" : ", not converged");
  fmt::print("  {} frames, {:.3g} MB written ({:.3g} kB per frame) to {}\n", facts.frames,
             static_cast<double>(facts.bytes_written) / 1e6,
             facts.frames ? static_cast<double>(facts.bytes_written) / 1e3 / facts.frames : 0.0,
             options.out_dir.string());
  fmt::print("  {} checkpoints, {:.3g} MB, {:.3g} s ({:.2g} % of the wall time)\n",
             facts.checkpoints, static_cast<double>(facts.checkpoint_bytes) / 1e6,
             facts.checkpoint_seconds,
             facts.wall_seconds > 0 ? 100 * facts.checkpoint_seconds / facts.wall_seconds : 0.0);
  std::string table = "  phase seconds:";
  for (std::size_t k = 0; k < kPhaseNames.size(); ++k)
    table += fmt::format(" {} {:.3g}", kPhaseNames[k], sim.timers().seconds(static_cast<Phase>(k)));
  fmt::print("{} checkpoint {:.3g}\n", table, facts.checkpoint_seconds);
}

// The step after `step` on a cadence of `every` steps (none when every is 0).
std::int64_t next_on_cadence(std::int64_t step, std::int64_t every) {
  return every > 0 ? (step / every + 1) * every : std::numeric_limits<std::int64_t>::max();
}

// A case's output and check cadences, in steps.
struct Cadences {
  std::int64_t total, frame, history, check, checkpoint;
  // Steps between looks at the stop flag: about 2e7 particle-steps (well
  // under a second), at most 2000.
  std::int64_t chunk;

  Cadences(const CaseSpec& spec, std::size_t particles)
      : total(spec.step_count()),
        frame(spec.steps_per_frame()),
        history(spec.steps_per_history()),
        check(spec.stability.check_interval),
        checkpoint(spec.steps_per_checkpoint()),
        chunk(std::clamp<std::int64_t>(
            20'000'000 / static_cast<std::int64_t>(std::max<std::size_t>(1, particles)), 1, 2000)) {
  }

  // The next step at which something must be looked at or written.
  std::int64_t next_stop(std::int64_t step) const {
    return std::min({std::min(total, (step / frame + 1) * frame), next_on_cadence(step, history),
                     next_on_cadence(step, check), next_on_cadence(step, checkpoint)});
  }
};

// Steps the state in `sim` (set up, or restored from a checkpoint) to the end
// of the case, a stop signal or a blow-up, writing frames, history rows and
// checkpoints on their cadences. `fresh`: the run starts at step 0 and writes
// its first frame and checkpoint. Fills the outcome (and diagnosis) in `facts`.
void step_to_end(Simulation& sim, RunFolder& outputs, RunFacts& facts, const RunOptions& options,
                 bool fresh) {
  const Cadences every(sim.spec(), sim.particle_count());
  // The current state as a frame (its fields must be fresh); over MPI ranks
  // each rank writes its own particles' rows (compressed: sends them to rank
  // 0 chunk by chunk).
  auto write_frame = [&](const Diagnostics& d) {
    auto t = sim.timers().time(Phase::output);
    if (const RowPlacer placer = sim.row_placer()) {
      const Simulation::HistorySource h = sim.history_source();
      outputs.write_placed_frame(h.state, sim.spec(), d, h.readings, sim.gas_frame(), placer);
    } else {
      outputs.write_frame(sim.state_with_fields(), sim.spec(), d, sim.gas_frame());
    }
  };
  // A checkpoint mid-run records the segment as "interrupted".
  auto checkpoint = [&] {
    RunFacts now = facts;
    now.outcome = Outcome::interrupted;
    write_checkpoint(sim, outputs, now);
  };

  Progress progress(every.total, sim.spec().dt, options.progress, facts.threads);
  if (fresh) {
    write_frame(sim.diagnostics());
    checkpoint();
  }
  sim.keep_good();
  facts.outcome = Outcome::completed;
  ThreadGovernor governor(facts.threads, options.adaptive_threads);
  while (sim.step() < every.total) {
    const std::int64_t next = every.next_stop(sim.step());
    while (sim.step() < next && !stop_requested() && !sim.gas_failed()) {
      set_thread_count(governor.threads());
      const auto started = std::chrono::steady_clock::now();
      const double waited = team_wait_seconds();
      const std::int64_t steps =
          std::min({every.chunk, next - sim.step(), governor.max_batch_steps()});
      sim.advance(steps);
      governor.record(
          steps, std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
          team_wait_seconds() - waited);
      progress.update(sim.step(), governor.threads(), sim.gas_steps());
    }
    Diagnostics d;
    const StabilityVerdict verdict = sim.check_stability(&d);
    if (!verdict.ok) {
      facts.outcome = Outcome::unstable;
      facts.diagnosis = describe_failure(sim, verdict, sim.good_step());
      facts.diagnosis_json = failure_json(sim, verdict, sim.good_step());
      // Keep the last good state as the final frame of the outputs.
      sim.restore_good();
      if (sim.step() != outputs.last_frame_step()) write_frame(sim.diagnostics());
      break;
    }
    sim.keep_good();
    const std::int64_t step = sim.step();
    if (step == every.total || step % every.frame == 0) write_frame(d);
    if (step % every.history == 0) {
      auto t = sim.timers().time(Phase::output);
      const Simulation::HistorySource h = sim.history_source();
      outputs.write_history(h.state, sim.spec(), d, h.readings);
    }
    if (step == every.total) break;
    if (every.checkpoint > 0 && step % every.checkpoint == 0 &&
        step > outputs.last_checkpoint_step())
      checkpoint();
    if (stop_requested()) {
      facts.outcome =
          stop_signal() == SIGTERM ? Outcome::stopped_by_sigterm : Outcome::stopped_by_sigint;
      break;
    }
  }
  progress.finish();
  set_thread_count(facts.threads);
  facts.team_size_changes = governor.changes();
  facts.team_size_seconds.assign(governor.seconds_at().begin(), governor.seconds_at().end());
}

// Publishes the outputs, writes the run's last checkpoint (an unstable state
// is not one to go on from) and run.json, prints the summary.
void finish_run(Simulation& sim, RunFolder& outputs, RunFacts& facts, const RunOptions& options) {
  const auto seconds_since_start = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - facts.started).count();
  };
  facts.steps = sim.step() - facts.start_step;
  facts.wall_seconds = seconds_since_start();
  facts.thread_wait_seconds = team_wait_seconds() - facts.wait_at_start;
  facts.rank_times = sim.rank_times();
  facts.rank_zero_copy = sim.holds_particles();
  facts.cut = sim.rank_cut();
  facts.thread_crossing = sim.thread_crossing();
  {
    auto t = sim.timers().time(Phase::output);
    outputs.publish();
  }
  if (facts.outcome != Outcome::unstable) write_checkpoint(sim, outputs, facts);
  outputs.fill(facts);
  facts.wall_seconds = seconds_since_start();
  write_file_atomically(options.out_dir / "run.json",
                        run_report_json(report_inputs(sim, sim.checkpoint_source().state), facts,
                                        outputs.previous_segments()));
  print_summary(sim, facts, options);
}

// The process exit code of an outcome, with what the user must know on stderr.
int exit_code(const Simulation& sim, const RunFacts& facts, const RunOptions& options) {
  switch (facts.outcome) {
    case Outcome::completed:
      return kExitOk;
    case Outcome::stopped_by_sigint:
    case Outcome::stopped_by_sigterm:
      fmt::print(stderr,
                 "mpsolid: {} at t = {:.6g} s (step {}); checkpoint and outputs are in {}. "
                 "Continue with: mpsolid resume {}\n",
                 outcome_name(facts.outcome), sim.time(), sim.step(), options.out_dir.string(),
                 options.out_dir.string());
      return kExitStopped;
    case Outcome::unstable:
      fmt::print(stderr,
                 "mpsolid: unstable: {}\n  The last good state (t = {:.6g} s) is the last "
                 "frame of {} and {}.\n",
                 facts.diagnosis, sim.time(), (options.out_dir / "history.csv").string(),
                 (options.out_dir / "frames.h5").string());
      return kExitUnstable;
    case Outcome::interrupted:
      break;  // only ever recorded in a checkpoint mid-run
  }
  return kExitError;
}

// The run with outputs: steps to the end, then the closing files and summary.
int run_loop(Simulation& sim, RunFolder& outputs, RunFacts& facts, const RunOptions& options,
             bool fresh) {
  for (const std::string& note : sim.spec().notes) fmt::print(stderr, "mpsolid: note: {}\n", note);
  step_to_end(sim, outputs, facts, options, fresh);
  finish_run(sim, outputs, facts, options);
  return exit_code(sim, facts, options);
}

// `--set` keys a resumed run may change: the rest would make it another case.
const std::vector<std::string> kResumeKeys = {"time.end", "output.checkpoint_interval",
                                              "output.compression"};
}  // namespace

namespace {
// A new segment's facts, with the run's thread count applied.
RunFacts begin_segment(const RunOptions& options, std::int64_t start_step) {
  set_thread_count(options.threads);
  RunFacts facts;
  facts.command_line = options.command_line;
  facts.overrides = options.overrides;
  facts.threads = thread_count();
  facts.ranks = Communicator::world().size();
  facts.start_step = start_step;
  facts.wait_at_start = team_wait_seconds();
  return facts;
}

// Runs `body` (which owns the run's outputs, closed when it returns or
// throws); a failure while writing becomes abandon_failed_run's account of
// what is intact. Bad input passes through as it is.
// The outputs of `dir` continued from `from`; a refused resume leaves the
// folder as it was (the staging copies it made are removed).
RunFolder resumed_outputs(const std::filesystem::path& dir, Simulation& sim,
                          const Checkpoint& from) {
  try {
    return RunFolder(dir, sim.state(), sim.spec(), from);
  } catch (const InputError&) {
    for (const char* name : {"history.csv", "frames.h5"})
      std::filesystem::remove(staging_path(dir / name));
    throw;
  }
}

template <class Body>
int with_failed_writes_explained(const std::filesystem::path& dir, Body&& body) {
  try {
    return body();
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // main says "out of memory"; reading the checkpoint now would need more
  } catch (const std::exception& e) {
    throw std::runtime_error(abandon_failed_run(dir, e.what()));
  }
}
}  // namespace

std::filesystem::path default_out_dir(const std::string& case_name,
                                      const std::vector<std::string>& overrides) {
  if (overrides.empty()) return std::filesystem::path("out") / case_name;
  Fnv1a h;
  for (const std::string& o : overrides) h.text(o);
  return std::filesystem::path("out") /
         fmt::format("{}-{:08x}", case_name,
                     static_cast<std::uint32_t>(h.value() ^ (h.value() >> 32)));
}

// The share of the case this machine holds: over ranks where rank 0 keeps
// no copy (`spread`), its ranks' share; otherwise all of it (rank 0's copy).
double machine_share(bool spread) {
  const Communicator& world = Communicator::world();
  return spread ? static_cast<double>(world.node_size()) / world.size() : 1.0;
}

// Refuses a folder that holds an earlier run's results, unless --force.
void refuse_earlier_results(const RunOptions& options) {
  if (options.force) return;
  if (const std::string earlier = earlier_results(options.out_dir); !earlier.empty())
    throw InputError(fmt::format(
        "{} holds the results of an earlier run ({}); give --force to replace them, --out for "
        "another folder, or continue a stopped run with: mpsolid resume {}",
        options.out_dir.string(), earlier, options.out_dir.string()));
}

int run_case(const CaseSpec& spec, const RunOptions& options) {
  RunFacts facts = begin_segment(options, 0);
  check_memory(spec, facts.threads, available_memory_bytes(),
               machine_share(options.followers != nullptr));
  // An existing folder is locked and checked before the set-up (seconds to
  // minutes on a large case); a new one once it is made.
  std::optional<FolderLock> lock;
  const auto lock_and_check = [&] {
    lock.emplace(options.out_dir);
    refuse_earlier_results(options);
  };
  if (std::filesystem::is_directory(options.out_dir)) lock_and_check();
  Simulation sim(spec, options.followers);
  // Before the first step, so a dt that cannot run is named with its fix
  // (its estimate is set-up work).
  std::string warning;
  if (!sim.spec().dt_auto)
    warning = fixed_time_step_warning(sim.spec(), sim.estimate_stable_step());
  if (!warning.empty()) fmt::print(stderr, "mpsolid: warning: {}\n", warning);
  prepare_output_folder(options.out_dir);
  if (!lock) lock_and_check();
  return with_failed_writes_explained(options.out_dir, [&] {
    RunFolder outputs(options.out_dir, sim.state(), sim.spec(), sim.particle_count(),
                      sim.bond_hash());
    lock->record_owner();
    return run_loop(sim, outputs, facts, options, true);
  });
}

int resume_run(const std::vector<std::string>& overrides, const RunOptions& options) {
  const std::filesystem::path path = RunFolder::checkpoint_path(options.out_dir);
  // Another process's run is not to be read while it writes (a missing folder
  // is read_checkpoint's to report).
  std::optional<FolderLock> lock;
  if (std::filesystem::is_directory(options.out_dir)) lock.emplace(options.out_dir);
  for (const std::string& o : overrides) {
    const std::string key = o.substr(0, o.find('='));
    if (std::find(kResumeKeys.begin(), kResumeKeys.end(), key) == kResumeKeys.end())
      throw InputError(fmt::format(
          "--set {}: a resumed run keeps its case; it may change only {} (run the case afresh "
          "to change anything else)",
          o, fmt::join(kResumeKeys, ", ")));
  }
  // Its particle rows first only located: over ranks where rank 0 needs no
  // copy, each rank reads its own.
  Checkpoint checkpoint = read_checkpoint(path, ParticleRows::placed);
  const CaseSpec spec = load_case_text(checkpoint.case_toml, path.string(), overrides);
  const double at = spec.time_at(checkpoint.step);
  if (spec.step_count() < checkpoint.step)
    throw InputError(fmt::format("time.end = {} s is before the checkpoint (t = {} s, step {})",
                                 spec.end, at, checkpoint.step));
  // A run killed after its last checkpoint but before run.json is finished
  // by a resume of no steps.
  if (spec.step_count() == checkpoint.step) {
    if (run_report_completes(options.out_dir, checkpoint))
      throw InputError(fmt::format(
          "{}: the run already reached its end (t = {} s, step {}); continue it with --set "
          "time.end=LATER",
          path.string(), at, checkpoint.step));
    fmt::print(stderr,
               "mpsolid: note: the run reached its end (step {}) but stopped before writing "
               "run.json; finishing it\n",
               checkpoint.step);
  }

  RunFacts facts = begin_segment(options, checkpoint.step);
  const bool by_rows = options.followers && !checkpoint.particle_offsets.empty();
  check_memory(spec, facts.threads, available_memory_bytes(), machine_share(by_rows));
  if (!by_rows) checkpoint = read_checkpoint(path);  // restored whole on rank 0
  Simulation sim(spec, options.followers, by_rows ? RankZeroCopy::as_needed : RankZeroCopy::whole);
  if (by_rows)
    check_placed_content(checkpoint,
                         sim.restore_without_copy(
                                [&](SolverState& head) {
                                  restore_state_without_particles(head, sim.particle_count(),
                                                                  sim.bond_hash(), checkpoint,
                                                                  path.string());
                                },
                                {RowPlacement::Content::restore,
                                 std::filesystem::absolute(path).string(),
                                 checkpoint.particle_offsets,
                                 {}})
                             .array_hashes,
                         path.string());
  else
    restore_state(sim.state_to_change(), checkpoint, path.string());
  try {
    sim.restore_gas_saved(checkpoint.gas);
  } catch (const InputError& e) {
    throw InputError(
        fmt::format("{}: the checkpoint does not fit this case: {}", path.string(), e.what()));
  }
  return with_failed_writes_explained(options.out_dir, [&] {
    RunFolder outputs = resumed_outputs(options.out_dir, sim, checkpoint);
    if (lock) lock->record_owner();
    return run_loop(sim, outputs, facts, options, false);
  });
}

}  // namespace mpsolid
