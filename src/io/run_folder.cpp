#include "src/io/run_folder.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <random>

#include "build_info.hpp"
#include "src/io/atomic_file.hpp"

namespace mpsolid {

namespace {
std::uint64_t new_run_id() {
  std::random_device device;
  const auto now =
      static_cast<std::uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());
  std::uint64_t id = (static_cast<std::uint64_t>(device()) << 32) ^ device() ^ now ^
                     (static_cast<std::uint64_t>(::getpid()) << 17);
  return id == 0 ? 1 : id;
}

// Temporary files a killed process may have left behind.
void remove_leftovers(const std::filesystem::path& dir) {
  for (const char* name : {"checkpoint.h5", "frames.xdmf", "run.json"})
    std::filesystem::remove(staging_path(dir / name));
  for (const char* name : {"history.csv", "frames.h5"})
    std::filesystem::remove(dir / (std::string(name) + copy_path_suffix()));
}

// Removes an old checkpoint before anything else of a fresh run is written.
const std::filesystem::path& prepare_fresh(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::filesystem::remove(RunFolder::checkpoint_path(dir));
  remove_leftovers(dir);
  return dir;
}

// A resumed run's folder must hold the checkpoint's own outputs.
const std::filesystem::path& check_same_run(const std::filesystem::path& dir,
                                            const Checkpoint& from) {
  const std::uint64_t outputs_run = frames_run_id(dir / "frames.h5");
  if (outputs_run != from.run_id)
    throw InputError(
        fmt::format("{} belongs to another run than {} (run id {:016x}, the frames' is {:016x}): a "
                    "checkpoint from a different run or case",
                    RunFolder::checkpoint_path(dir).string(), (dir / "frames.h5").string(),
                    from.run_id, outputs_run));
  return dir;
}
}  // namespace

std::string abandon_failed_run(const std::filesystem::path& dir, const std::string& failure) {
  // Disk-full errors arrive as EIO from a copy or as an HDF5 message: the
  // file system's free space, before the temporary files go, tells.
  constexpr long long kNearlyFull = 1 << 20;
  const long long free = free_bytes(dir);
  std::error_code ignored;
  for (const char* name : {"history.csv", "frames.h5"}) {
    std::filesystem::remove(staging_path(dir / name), ignored);
    std::filesystem::remove(dir / (std::string(name) + copy_path_suffix()), ignored);
  }
  remove_leftovers(dir);
  std::string text = failure;
  if (free >= 0 && free < kNearlyFull)
    text += fmt::format("; no space left on the device holding {} ({} bytes free when it failed)",
                        dir.string(), free);
  try {
    const Checkpoint last = read_checkpoint(RunFolder::checkpoint_path(dir));
    text += fmt::format(
        ". The last checkpoint (step {}) and the history.csv and frames.h5 it records are "
        "intact; the temporary files are removed. Free some space, then continue with: mpsolid "
        "resume {}",
        last.step, dir.string());
  } catch (const std::exception&) {
    text += ". No checkpoint was completed; the temporary files are removed";
  }
  return text;
}

std::string earlier_results(const std::filesystem::path& dir) {
  std::vector<std::string> present;
  for (const char* name : {"history.csv", "frames.h5", "checkpoint.h5", "run.json"})
    if (std::filesystem::exists(dir / name)) present.push_back(name);
  if (present.empty()) return "";
  std::string text = fmt::format("{}", fmt::join(present, ", "));
  try {
    std::ifstream in(dir / "run.json");
    const Json report = Json::parse(in);
    text += fmt::format("; run.json: case {}, model {}, {} at step {}",
                        report.at("case").get<std::string>(), report.at("model").get<std::string>(),
                        report.at("outcome").get<std::string>(),
                        report.at("final_step").get<std::int64_t>());
  } catch (const std::exception&) {
    // No readable run.json: the file names say enough.
  }
  return text;
}

bool run_report_completes(const std::filesystem::path& dir, const Checkpoint& last) {
  try {
    std::ifstream in(dir / "run.json");
    const Json report = Json::parse(in);
    return report.at("outcome").get<std::string>() == outcome_name(Outcome::completed) &&
           report.at("final_step").get<std::int64_t>() == last.step &&
           report.at("segments").size() >= last.segments.size();
  } catch (const std::exception&) {
    return false;  // missing or unreadable: not written after `last`
  }
}

RunFolder::RunFolder(const std::filesystem::path& dir, const SolverState& state,
                     const CaseSpec& spec, std::size_t particles, std::uint64_t bond_hash)
    : dir_(prepare_fresh(dir)),
      run_id_(new_run_id()),
      bond_hash_(bond_hash),
      history_(dir / "history.csv", state, spec),
      frames_(dir / "frames.h5", state, spec, run_id_, particles) {
  write_file_atomically(dir / "case.resolved.toml", spec.resolved_toml);
}

RunFolder::RunFolder(const std::filesystem::path& dir, const SolverState& state,
                     const CaseSpec& spec, const Checkpoint& from)
    : dir_(check_same_run(dir, from)),
      run_id_(from.run_id),
      bond_hash_(from.bond_hash),
      history_(dir / "history.csv", state, spec, from.history_bytes),
      frames_(dir / "frames.h5", state, spec, run_id_,
              static_cast<std::size_t>(from.particle_count), static_cast<int>(from.frames)),
      previous_segments_(from.segments),
      last_checkpoint_step_(from.step),
      last_frame_step_(-1) {
  remove_leftovers(dir);
  write_file_atomically(dir / "case.resolved.toml", spec.resolved_toml);
}

void RunFolder::write_history(const SolverState& state, const CaseSpec& spec, const Diagnostics& d,
                              const HistoryReadings* readings) {
  if (state.step == last_history_step_) return;
  history_.write(state, spec, d, readings ? *readings : history_readings(state, spec));
  last_history_step_ = state.step;
}

void RunFolder::write_frame(const SolverState& state, const CaseSpec& spec, const Diagnostics& d,
                            const GasFrame& gas) {
  write_history(state, spec, d);
  frames_.write(state, spec, gas);
  last_frame_step_ = state.step;
}

void RunFolder::write_placed_frame(const SolverState& state, const CaseSpec& spec,
                                   const Diagnostics& d, const HistoryReadings* readings,
                                   const GasFrame& gas, const RowPlacer& placer) {
  write_history(state, spec, d, readings);
  frames_.write_placed(state.step, spec, gas, placer);
  last_frame_step_ = state.step;
}

void RunFolder::fill(RunFacts& facts) const {
  facts.frames = frames_.frames_written();
  facts.bytes_written = history_.bytes_written() + frames_.bytes_written();
  facts.checkpoints = checkpoints_;
  facts.checkpoint_bytes = checkpoint_bytes_;
  facts.checkpoint_seconds = checkpoint_seconds_;
}

void RunFolder::checkpoint(const RunReportInputs& in, RunFacts facts, const RowPlacer& placer) {
  const SolverState& state = in.state;
  const CaseSpec& spec = in.spec;
  const auto start = std::chrono::steady_clock::now();
  if (!published_) {
    history_.publish_copy();
    frames_.publish_copy();
  }
  Checkpoint c = capture_state(state, !placer);
  c.particle_count = static_cast<std::int64_t>(in.particles);
  c.gas = in.gas;
  c.case_toml = spec.resolved_toml;
  c.bond_hash = bond_hash_;
  c.run_id = run_id_;
  c.frames = frames_.frames_total();
  c.history_bytes = history_.file_bytes();
  c.written_by = fmt::format("mpsolid {} ({})", build_info::version, build_info::git_commit);
  fill(facts);
  facts.checkpoints += 1;
  facts.steps = state.step - facts.start_step;
  facts.wall_seconds = std::chrono::duration<double>(start - facts.started).count();
  c.segments = previous_segments_;
  c.segments.push_back(segment_json(in, facts).dump());
  checkpoint_bytes_ += write_checkpoint(checkpoint_path(dir_), c, placer);
  ++checkpoints_;
  last_checkpoint_step_ = state.step;
  checkpoint_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void RunFolder::publish() {
  history_.publish();
  frames_.publish();
  published_ = true;
}

}  // namespace mpsolid
