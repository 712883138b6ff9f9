#include "src/app/launch.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <exception>
#include <new>
#include <optional>

#include "src/app/progress.hpp"
#include "src/app/run.hpp"
#include "src/app/signals.hpp"
#include "src/app/study_launcher.hpp"
#include "src/app/thread_choice.hpp"
#include "src/core/parallel.hpp"
#include "src/distributed/communicator.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/ranked_stepper.hpp"

namespace mpsolid {

namespace {
// The thread count, with a warning on stderr when it exceeds the cores.
int chosen_threads(int requested) {
  const ThreadChoice choice = choose_threads(requested, available_cores());
  if (!choice.warning.empty()) fmt::print(stderr, "mpsolid: warning: {}\n", choice.warning);
  return choice.threads;
}

// The stepping options of `run` and `resume` (none for `study`).
const SteppingOptions* stepping_of(const CommandLine& c) {
  if (const auto* run = std::get_if<RunCommand>(&c.command)) return &run->stepping;
  if (const auto* resume = std::get_if<ResumeCommand>(&c.command)) return &resume->stepping;
  return nullptr;
}

// The exit code of a launch this process refuses (the message printed once),
// with a note on stderr for one that is only suspicious.
std::optional<int> refused_launch(const Communicator& world, bool study) {
  if (world.size() == 1 && launcher_job_size() > 1) {
    // A build without MPI, started as one of several ranks: each would run
    // the whole case alone, into the same folder.
    if (launcher_rank() == 0)
      fmt::print(stderr,
                 "mpsolid: error: started as one of {} ranks, but this mpsolid was built without "
                 "MPI (mpsolid --version), so every rank would run the whole case alone; install "
                 "MPI and build again (scripts/install_deps.sh, docs/mpi.md), or run it without "
                 "mpirun and use --threads\n",
                 launcher_job_size());
    return kExitBadInput;
  }
  if (world.size() == 1 && launcher_job_size() == 1 && slurm_step_tasks() > 1 && slurm_task() == 0)
    // Not refused: an interactive `srun -n N --pty bash` shell looks the same.
    fmt::print(stderr,
               "mpsolid: note: srun started {} tasks, but not as one MPI job (no MPI plugin: "
               "Open MPI needs srun --mpi=pmix), so each runs the case alone (docs/mpi.md)\n",
               slurm_step_tasks());
  if (world.size() > 1 && study) {
    if (world.rank() == 0)
      fmt::print(stderr,
                 "mpsolid: error: mpsolid study runs on one rank (its runs use the "
                 "cores); start it without mpirun\n");
    return kExitBadInput;
  }
  return std::nullopt;
}

// `run` or `resume` on rank 0 (or alone), every error as its exit code.
int run_or_resume(const CommandLine& c, int threads, Followers* followers) {
  try {
    install_stop_handlers();
    const SteppingOptions& stepping = *stepping_of(c);
    RunOptions options;
    options.threads = chosen_threads(threads);
    options.adaptive_threads = !stepping.fixed_threads;
    options.progress = stderr_is_terminal();
    options.command_line = c.text;
    options.overrides = stepping.overrides;
    options.followers = followers;
    if (const auto* resume = std::get_if<ResumeCommand>(&c.command)) {
      options.out_dir = resume->dir;
      return resume_run(stepping.overrides, options);
    }
    const auto& run = std::get<RunCommand>(c.command);
    const CaseSpec spec = load_case(run.case_path, stepping.overrides);
    options.out_dir = run.out_dir.empty() ? default_out_dir(spec.name, stepping.overrides)
                                          : std::filesystem::path(run.out_dir);
    options.force = run.force;
    return run_case(spec, options);
  } catch (const InputError& e) {
    fmt::print(stderr, "mpsolid: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr,
               "mpsolid: failed: out of memory (the estimate before set-up passed, so another "
               "process took memory, or the case's outputs need more than it allows)\n");
    return kExitError;
  } catch (const std::exception& e) {
    fmt::print(stderr, "mpsolid: failed: {}\n", e.what());
    return kExitError;
  }
}
}  // namespace

int launch(const CommandLine& command_line, int* argc, char*** argv) {
  // Under an MPI launcher, MPI starts (a plain start never does: no MPI
  // start-up cost, no launcher needed).
  std::optional<MpiSession> mpi;
  if (launched_by_mpi()) mpi.emplace(argc, argv);
  const Communicator& world = Communicator::world();
  const auto* study = std::get_if<StudyCommand>(&command_line.command);
  if (const std::optional<int> refused = refused_launch(world, study != nullptr)) return *refused;

  const SteppingOptions* stepping = stepping_of(command_line);
  int threads = stepping ? stepping->threads : 0;
  // One thread per rank unless asked for more: ranks already share the cores.
  if (world.size() > 1 && threads == 0 && std::getenv("OMP_NUM_THREADS") == nullptr) threads = 1;
  if (world.size() > 1 && world.rank() > 0) {
    install_stop_handlers();  // a batch system's SIGTERM reaches every rank: rank 0 stops the run
    set_thread_count(choose_threads(threads, available_cores()).threads);
    return follow_rank_zero(world);
  }
  // However rank 0 leaves, the followers are released (the destructor).
  std::optional<Followers> followers;
  if (world.size() > 1) followers.emplace(world, stepping ? stepping->cut : CutChoice::automatic);
  if (study) return launch_study(study->arguments);
  return run_or_resume(command_line, threads, followers ? &*followers : nullptr);
}

}  // namespace mpsolid
