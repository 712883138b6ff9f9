#include "src/io/run_report.hpp"

#include "build_info.hpp"

namespace mpsolid {

const char* outcome_name(Outcome outcome) {
  switch (outcome) {
    case Outcome::completed:
      return "completed";
    case Outcome::interrupted:
      return "interrupted";
    case Outcome::stopped_by_sigint:
      return "stopped by SIGINT";
    case Outcome::stopped_by_sigterm:
      return "stopped by SIGTERM";
    case Outcome::unstable:
      return "unstable";
  }
  return "unknown";
}

bool stopped_by_signal(Outcome outcome) {
  return outcome == Outcome::stopped_by_sigint || outcome == Outcome::stopped_by_sigterm;
}

namespace {
// Wall seconds per phase, checkpoints included.
Json phases_json(const PhaseTimers& timers, const RunFacts& facts) {
  Json phases = Json::object();
  for (std::size_t k = 0; k < kPhaseNames.size(); ++k)
    phases[kPhaseNames[k]] = timers.seconds(static_cast<Phase>(k));
  phases["checkpoint"] = facts.checkpoint_seconds;
  return phases;
}

double rate(const RunFacts& facts) {
  return facts.wall_seconds > 0 ? static_cast<double>(facts.steps) / facts.wall_seconds : 0.0;
}

// Each rank's (or thread's) particles, its passes' time, its halo exchanges
// and the slices of the state it moved.
Json ranks_json(const std::vector<RankTimes>& all, const char* key) {
  Json ranks = Json::array();
  for (std::size_t r = 0; r < all.size(); ++r) {
    const RankTimes& t = all[r];
    ranks.push_back({{key, r},
                     {"owned_particles", static_cast<std::int64_t>(t.owned)},
                     {"ghosts", static_cast<std::int64_t>(t.ghosts)},
                     {"contact_seconds", t.contact_seconds},
                     {"strain_seconds", t.strain_seconds},
                     {"forces_seconds", t.forces_seconds},
                     {"halo_seconds", t.halo_seconds},
                     {"halo_wait_seconds", t.halo_wait_seconds},
                     {"halo_bytes_sent", t.halo_bytes_sent},
                     {"peak_memory_bytes", t.peak_memory_bytes},
                     {"slice_moves", static_cast<std::int64_t>(t.slice_moves)},
                     {"slice_bytes", t.slice_bytes}});
  }
  return ranks;
}

// Summed over the threads: time spent at the step's barriers waiting for the
// slowest (an imbalance, or a busy machine), its share of threads x wall
// time, and the wall seconds stepped at each team size (fewer than
// `threads` where waiting on a busy machine made them slower).
Json thread_facts_json(const RunFacts& facts) {
  Json sizes = Json::object();
  for (const auto& [size, seconds] : facts.team_size_seconds) sizes[std::to_string(size)] = seconds;
  const double capacity = facts.wall_seconds * facts.threads;
  Json facts_json = {
      {"thread_wait_seconds", facts.thread_wait_seconds},
      {"thread_wait_share", capacity > 0 ? facts.thread_wait_seconds / capacity : 0.0},
      {"team_size_seconds", sizes},
      {"team_size_changes", facts.team_size_changes}};
  // Over several ranks: each rank's particles, its passes' time, its halo
  // exchanges (waiting for the slowest rank included) and the bytes it sent.
  if (!facts.rank_times.empty()) {
    facts_json["per_rank"] = ranks_json(facts.rank_times, "rank");
    facts_json["rank_zero_copy"] = facts.rank_zero_copy ? "whole" : "none";
    if (!facts.cut.kind.empty())
      facts_json["cut"] = {{"kind", facts.cut.kind},
                           {"estimated_ghosts",
                            {{"slabs", facts.cut.slab_ghosts},
                             {"bands", facts.cut.band_ghosts},
                             {"blocks", facts.cut.block_ghosts}}},
                           {"split_rigid_bodies", facts.cut.split_rigid_bodies}};
  }
  // With several threads on one process, stepping as ranks: what crossed
  // between them per step (summed over the threads; each rendezvous reads
  // every other thread's counter line), and each thread's part.
  const ThreadCrossing& c = facts.thread_crossing;
  if (c.threads > 0) {
    Json halos = Json::array();
    double bytes = 0, lines = c.counter_lines_per_step();
    for (const HaloCrossing& h : c.per_step) {
      halos.push_back({{"halo", h.name}, {"bytes", h.bytes}, {"cache_lines", h.lines}});
      bytes += h.bytes;
      lines += h.lines;
    }
    facts_json["threads_as_ranks"] = {{"threads", c.threads},
                                      {"steps", static_cast<std::int64_t>(c.steps)},
                                      {"crossing_per_step",
                                       {{"bytes", bytes},
                                        {"cache_lines", lines},
                                        {"rendezvous", c.calls_per_step},
                                        {"counter_lines", c.counter_lines_per_step()},
                                        {"halos", halos}}},
                                      {"per_thread", ranks_json(c.per_thread, "thread")}};
  }
  return facts_json;
}
}  // namespace

Json segment_json(const RunReportInputs& in, const RunFacts& facts) {
  Json segment = {{"command_line", facts.command_line},
                  {"outcome", outcome_name(facts.outcome)},
                  {"threads", facts.threads},
                  {"ranks", facts.ranks},
                  {"start_step", facts.start_step},
                  {"final_step", in.state.step},
                  {"steps", facts.steps},
                  {"wall_seconds", facts.wall_seconds},
                  {"steps_per_second", rate(facts)},
                  {"frames", facts.frames},
                  {"bytes_written", facts.bytes_written},
                  {"checkpoints", facts.checkpoints},
                  {"checkpoint_bytes", facts.checkpoint_bytes},
                  {"phase_seconds", phases_json(in.timers, facts)}};
  segment.update(thread_facts_json(facts));
  return segment;
}

std::string run_report_json(const RunReportInputs& in, const RunFacts& facts,
                            const std::vector<std::string>& previous_segments) {
  const double steps_per_second = rate(facts);
  const std::size_t particles = in.particles;
  Json segments = Json::array();
  for (const std::string& s : previous_segments) segments.push_back(Json::parse(s));
  segments.push_back(segment_json(in, facts));
  Json report = {{"program", "mpsolid"},
                 {"version", build_info::version},
                 {"git_commit", build_info::git_commit},
                 {"compiler", build_info::compiler},
                 {"build_type", build_info::build_type},
                 {"flags", build_info::cxx_flags},
                 {"command_line", facts.command_line},
                 {"overrides", facts.overrides},
                 {"case", in.spec.name},
                 {"model", in.spec.model},
                 {"dimension", in.spec.dimension},
                 {"outcome", outcome_name(facts.outcome)},
                 {"threads", facts.threads},
                 {"ranks", facts.ranks},
                 {"particles", particles},
                 {"bonds", in.bonds},
                 {"dt", in.spec.dt},
                 {"steps", facts.steps},
                 {"final_step", in.state.step},
                 {"simulated_time", in.spec.time_at(in.state.step)},
                 {"start_step", facts.start_step},
                 {"frames", facts.frames},
                 {"bytes_written", facts.bytes_written},
                 {"checkpoints", facts.checkpoints},
                 {"checkpoint_bytes", facts.checkpoint_bytes},
                 {"wall_seconds", facts.wall_seconds},
                 {"steps_per_second", steps_per_second},
                 {"particle_steps_per_second", steps_per_second * static_cast<double>(particles)},
                 {"phase_seconds", phases_json(in.timers, facts)}};
  report.update(thread_facts_json(facts));
  report["segments"] = segments;
  // The estimate behind time.dt = "auto", if it was used.
  if (const StableStepEstimate& e = in.stable_step; e.iterations > 0)
    report["stable_step"] = {{"safety", in.spec.dt_safety},
                             {"dt_limit", e.dt_limit},
                             {"omega_max", e.omega_max},
                             {"iterations", e.iterations},
                             {"converged", e.converged}};
  // Contact's candidates and Verlet list (rebuilds counted since this
  // segment's set-up or resume, the build at set-up included).
  if (const ContactState& c = in.state.contact; c.enabled())
    report["contact"] = {{"candidates", c.size()},
                         {"list_entries", c.partner.size()},
                         {"rebuilds", c.rebuilds},
                         {"distance_m", c.parameters.distance},
                         {"pair_stiffness_n_per_m", c.parameters.stiffness},
                         {"skin_m", c.parameters.skin}};
  if (!in.spec.notes.empty()) report["notes"] = in.spec.notes;
  if (!facts.diagnosis_json.is_null()) report["diagnosis"] = facts.diagnosis_json;
  return report.dump(2) + "\n";
}

}  // namespace mpsolid
