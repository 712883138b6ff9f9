#include "src/io/run_report.hpp"

#include <fmt/format.h>

#include "build_info.hpp"

namespace mpsolid {

std::string json_quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<int>(c));
      continue;
    }
    out += c;
  }
  return out + "\"";
}

namespace {
// Wall seconds per phase, checkpoints included, as JSON members.
std::string phases_json(const Simulation& sim, const RunFacts& facts, const char* separator) {
  std::string phases;
  for (std::size_t k = 0; k < kPhaseNames.size(); ++k)
    phases += fmt::format("{}{}: {:.6g}", k ? separator : "", json_quoted(kPhaseNames[k]),
                          sim.timers().seconds(static_cast<Phase>(k)));
  return phases + fmt::format("{}\"checkpoint\": {:.6g}", separator, facts.checkpoint_seconds);
}

double rate(const RunFacts& facts) {
  return facts.wall_seconds > 0 ? static_cast<double>(facts.steps) / facts.wall_seconds : 0.0;
}
}  // namespace

std::string segment_json(const Simulation& sim, const RunFacts& facts) {
  return fmt::format(
      "{{\"command_line\": {}, \"outcome\": {}, \"threads\": {}, \"start_step\": {}, "
      "\"final_step\": {}, \"steps\": {}, \"wall_seconds\": {:.6g}, \"steps_per_second\": "
      "{:.6g}, \"frames\": {}, \"bytes_written\": {}, \"checkpoints\": {}, "
      "\"checkpoint_bytes\": {}, \"phase_seconds\": {{{}}}}}",
      json_quoted(facts.command_line), json_quoted(facts.outcome), facts.threads, facts.start_step,
      sim.step(), facts.steps, facts.wall_seconds, rate(facts), facts.frames, facts.bytes_written,
      facts.checkpoints, facts.checkpoint_bytes, phases_json(sim, facts, ", "));
}

// The estimate behind time.dt = "auto", if it was used.
std::string stable_step_json(const Simulation& sim) {
  const StableStepEstimate& e = sim.stable_step();
  if (e.iterations == 0) return "";
  return fmt::format(
      ",\n  \"stable_step\": {{\"safety\": {:.17g}, \"dt_limit\": {:.17g}, \"omega_max\": {:.17g}, "
      "\"iterations\": {}, \"converged\": {}}}",
      sim.spec().dt_safety, e.dt_limit, e.omega_max, e.iterations, e.converged);
}

std::string run_report_json(const Simulation& sim, const RunFacts& facts,
                            const std::vector<std::string>& previous_segments) {
  const double steps_per_second = rate(facts);
  const std::string phases = "    " + phases_json(sim, facts, ",\n    ");
  std::string segments;
  for (const std::string& s : previous_segments) segments += "    " + s + ",\n";
  segments += "    " + segment_json(sim, facts);
  const std::size_t particles = sim.particles().size();
  return fmt::format(
      "{{\n"
      "  \"program\": \"mpsolid\",\n"
      "  \"version\": {},\n"
      "  \"git_commit\": {},\n"
      "  \"compiler\": {},\n"
      "  \"build_type\": {},\n"
      "  \"flags\": {},\n"
      "  \"command_line\": {},\n"
      "  \"case\": {},\n"
      "  \"model\": {},\n"
      "  \"outcome\": {},\n"
      "  \"threads\": {},\n"
      "  \"particles\": {},\n"
      "  \"bonds\": {},\n"
      "  \"dt\": {:.17g},\n"
      "  \"steps\": {},\n"
      "  \"final_step\": {},\n"
      "  \"simulated_time\": {:.17g},\n"
      "  \"start_step\": {},\n"
      "  \"frames\": {},\n"
      "  \"bytes_written\": {},\n"
      "  \"checkpoints\": {},\n"
      "  \"checkpoint_bytes\": {},\n"
      "  \"wall_seconds\": {:.6g},\n"
      "  \"steps_per_second\": {:.6g},\n"
      "  \"particle_steps_per_second\": {:.6g},\n"
      "  \"phase_seconds\": {{\n{}\n  }},\n"
      "  \"segments\": [\n{}\n  ]{}{}\n"
      "}}\n",
      json_quoted(build_info::version), json_quoted(build_info::git_commit),
      json_quoted(build_info::compiler), json_quoted(build_info::build_type),
      json_quoted(build_info::cxx_flags), json_quoted(facts.command_line),
      json_quoted(sim.spec().name), json_quoted(sim.spec().model), json_quoted(facts.outcome),
      facts.threads, particles, sim.state().bonds.entry_count() / 2, sim.state().dt, facts.steps,
      sim.step(), sim.time(), facts.start_step, facts.frames, facts.bytes_written,
      facts.checkpoints, facts.checkpoint_bytes, facts.wall_seconds, steps_per_second,
      steps_per_second * static_cast<double>(particles), phases, segments, stable_step_json(sim),
      facts.diagnosis_json.empty() ? "" : ",\n  \"diagnosis\": " + facts.diagnosis_json);
}

}  // namespace mpsolid
