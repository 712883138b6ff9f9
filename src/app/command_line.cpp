#include "src/app/command_line.hpp"

#include <CLI/CLI.hpp>

#include "src/app/exit_codes.hpp"
#include "src/app/version.hpp"

namespace mpsolid {

namespace {
// The options `run` and `resume` share; `set_help` says what --set may change.
void add_stepping_options(CLI::App& command, SteppingOptions& o, const std::string& set_help) {
  command
      .add_option("--threads", o.threads,
                  "OpenMP threads (default: OMP_NUM_THREADS if set, else all cores)")
      ->check(CLI::Range(1, 4096));
  command.add_flag(
      "--fixed-threads", o.fixed_threads,
      "keep --threads for the whole run (by default the run tries fewer now and then and keeps "
      "them where they are faster, as on a busy machine; the results are the same bits either "
      "way)");
  command
      .add_option_function<std::string>(
          "--cut",
          [&o](const std::string& name) {
            o.cut = name == "slabs"    ? CutChoice::slabs
                    : name == "bands"  ? CutChoice::bands
                    : name == "blocks" ? CutChoice::blocks
                                       : CutChoice::automatic;
          },
          "how several MPI ranks cut the case: auto (the cut whose halo is estimated smallest), "
          "slabs (of storage), bands (across the longest extent) or blocks (recursive "
          "bisection); the same bits either way (default: auto; one rank ignores it)")
      ->check(CLI::IsMember({"auto", "slabs", "bands", "blocks"}));
  command.add_option("--set", o.overrides, set_help)
      ->allow_extra_args(false)
      ->type_name("KEY=VALUE");
}
}  // namespace

std::variant<CommandLine, int> parse_command_line(int argc, char** argv) {
  CLI::App app{
      "mpsolid: elastic MPS solver for shock-loaded elastic bodies (in plane strain or in space)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", version_text());

  RunCommand run;
  CLI::App* run_app = app.add_subcommand("run", "run a case file");
  run_app->add_option("case", run.case_path, "case file (TOML)")->required();
  run_app->add_option("--out", run.out_dir,
                      "output folder (default: out/<case name>, plus a hash of the --set values)");
  run_app->add_flag("--force", run.force,
                    "replace the results of an earlier run in the output folder");
  add_stepping_options(*run_app, run.stepping, "override a case key: --set time.end=0.002");

  ResumeCommand resume;
  CLI::App* resume_app = app.add_subcommand(
      "resume", "continue a run from its last checkpoint (DIR/checkpoint.h5), to the same bits");
  resume_app->add_option("dir", resume.dir, "the run's output folder")->required();
  add_stepping_options(*resume_app, resume.stepping,
                       "go on to a later end: --set time.end=0.02 (also "
                       "output.checkpoint_interval, output.compression)");

  CLI::App* study_app = app.add_subcommand(
      "study",
      "run a grid of a case's runs, one folder each, then study.csv and study.png (mpsolid study "
      "--help: every option)");
  study_app->prefix_command();  // every argument goes to the study, --help included
  study_app->set_help_flag();

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

  CommandLine parsed;
  for (int k = 0; k < argc; ++k) parsed.text += (k ? " " : "") + std::string(argv[k]);
  if (run_app->parsed())
    parsed.command = std::move(run);
  else if (resume_app->parsed())
    parsed.command = std::move(resume);
  else
    parsed.command = StudyCommand{study_app->remaining()};
  return parsed;
}

}  // namespace mpsolid
