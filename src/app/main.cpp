// mpsolid: the command line.
//   mpsolid run CASE [--out DIR] [--threads N] [--set KEY=VALUE]...
//   mpsolid resume DIR [--threads N] [--set time.end=VALUE]...
//   mpsolid study CASE --vary KEY=V1,V2,... [...]   (python/mpsolid/study.py)
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <cstdlib>
#include <exception>
#include <new>
#include <optional>

#include "src/app/progress.hpp"
#include "src/app/run.hpp"
#include "src/app/signals.hpp"
#include "src/app/study_launcher.hpp"
#include "src/app/thread_choice.hpp"
#include "src/app/version.hpp"
#include "src/core/parallel.hpp"
#include "src/distributed/communicator.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/ranked_stepper.hpp"

namespace {
// The thread count, with a warning on stderr when it exceeds the cores.
int chosen_threads(int requested) {
  using namespace mpsolid;
  const ThreadChoice choice = choose_threads(requested, available_cores());
  if (!choice.warning.empty()) fmt::print(stderr, "mpsolid: warning: {}\n", choice.warning);
  return choice.threads;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace mpsolid;
  CLI::App app{"mpsolid: elastic MPS solver for shock-loaded elastic bodies (2D plane strain)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", version_text());
  std::string case_path, out_dir;
  int threads = 0;
  std::vector<std::string> overrides;
  CLI::App* run = app.add_subcommand("run", "run a case file");
  run->add_option("case", case_path, "case file (TOML)")->required();
  run->add_option("--out", out_dir,
                  "output folder (default: out/<case name>, plus a hash of the --set values)");
  bool force = false;
  run->add_flag("--force", force, "replace the results of an earlier run in the output folder");
  run->add_option("--threads", threads,
                  "OpenMP threads (default: OMP_NUM_THREADS if set, else all cores)")
      ->check(CLI::Range(1, 4096));
  bool fixed_threads = false;
  const char* fixed_help =
      "keep --threads for the whole run (by default the run tries fewer now and then and keeps "
      "them where they are faster, as on a busy machine; the results are the same bits either "
      "way)";
  run->add_flag("--fixed-threads", fixed_threads, fixed_help);
  run->add_option("--set", overrides, "override a case key: --set time.end=0.002")
      ->allow_extra_args(false)
      ->type_name("KEY=VALUE");
  std::string resume_dir;
  CLI::App* resume = app.add_subcommand(
      "resume", "continue a run from its last checkpoint (DIR/checkpoint.h5), to the same bits");
  resume->add_option("dir", resume_dir, "the run's output folder")->required();
  resume
      ->add_option("--threads", threads,
                   "OpenMP threads (default: OMP_NUM_THREADS if set, else all cores)")
      ->check(CLI::Range(1, 4096));
  resume->add_flag("--fixed-threads", fixed_threads, fixed_help);
  resume
      ->add_option("--set", overrides,
                   "go on to a later end: --set time.end=0.02 (also output.checkpoint_interval, "
                   "output.compression)")
      ->allow_extra_args(false)
      ->type_name("KEY=VALUE");

  CLI::App* study = app.add_subcommand(
      "study",
      "run a grid of a case's runs, one folder each, then study.csv and study.png (mpsolid study "
      "--help: every option)");
  study->prefix_command();  // every argument goes to the study, --help included
  study->set_help_flag();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }

  // Under an MPI launcher, MPI starts (a plain start never does: no MPI
  // start-up cost, no launcher needed). Rank 0 runs the command as always;
  // the other ranks follow it (src/solver/ranked_stepper.hpp, docs/mpi.md).
  std::optional<MpiSession> mpi;
  if (launched_by_mpi()) mpi.emplace(&argc, &argv);
  const Communicator& world = Communicator::world();
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
  // One thread per rank unless asked for more: ranks already share the cores.
  if (world.size() > 1 && threads == 0 && std::getenv("OMP_NUM_THREADS") == nullptr) threads = 1;
  if (world.size() > 1 && study->parsed()) {
    if (world.rank() == 0)
      fmt::print(stderr,
                 "mpsolid: error: mpsolid study runs on one rank (its runs use the "
                 "cores); start it without mpirun\n");
    return kExitBadInput;
  }
  if (world.size() > 1 && world.rank() > 0) {
    install_stop_handlers();  // a batch system's SIGTERM reaches every rank: rank 0 stops the run
    set_thread_count(choose_threads(threads, available_cores()).threads);
    return follow_rank_zero(world);
  }
  // However rank 0 leaves, the followers are released (its destructor).
  std::optional<Followers> followers;
  if (world.size() > 1) followers.emplace(world);

  if (study->parsed()) return launch_study(study->remaining());

  std::string command_line;
  for (int k = 0; k < argc; ++k) command_line += (k ? " " : "") + std::string(argv[k]);
  try {
    install_stop_handlers();
    RunOptions options;
    options.threads = chosen_threads(threads);
    options.adaptive_threads = !fixed_threads;
    options.progress = stderr_is_terminal();
    options.command_line = command_line;
    options.overrides = overrides;
    options.followers = followers ? &*followers : nullptr;
    if (resume->parsed()) {
      options.out_dir = resume_dir;
      return resume_run(overrides, options);
    }
    const CaseSpec spec = load_case(case_path, overrides);
    options.out_dir =
        out_dir.empty() ? default_out_dir(spec.name, overrides) : std::filesystem::path(out_dir);
    options.force = force;
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
