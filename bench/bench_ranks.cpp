// The decomposed step's speed (docs/mpi.md): the rod (paper model) stepped
// on every rank of the launcher, against the same rod on one rank with
// OpenMP threads. Run under mpirun:
//   mpirun -np 2 build/release/bench/bench_ranks [l0_m] [steps] [model]
// Prints, on rank 0, the median time per step of 5 rounds.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "src/core/parallel.hpp"
#include "src/distributed/communicator.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/simulation.hpp"

int main(int argc, char** argv) {
  using namespace mpsolid;
  MpiSession mpi(&argc, &argv);
  const Communicator& world = Communicator::world();
  const std::string l0 = argc > 1 ? argv[1] : "0.002";
  const long steps = argc > 2 ? std::stol(argv[2]) : 2000;
  const std::string model_name = argc > 3 ? argv[3] : "paper";
  set_thread_count(1);
  const CaseSpec spec = load_case(std::string(MPSOLID_SOURCE_DIR) + "/cases/shock_rod.toml",
                                  {"l0=" + l0, "model=" + model_name});
  Simulation base(spec);
  RankPart part = make_rank_part(spec, base.state(), world);
  std::vector<double> per_step;
  for (int round = 0; round < 5; ++round) {
    world.barrier();
    const auto start = std::chrono::steady_clock::now();
    advance_rank_part(part, world, spec.dt, steps);
    world.barrier();
    per_step.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
        static_cast<double>(steps));
  }
  std::sort(per_step.begin(), per_step.end());
  // One rank: the team step (Simulation::advance, one thread) beside it.
  double team = 0;
  if (world.size() == 1) {
    std::vector<double> rounds;
    for (int round = 0; round < 5; ++round) {
      const auto start = std::chrono::steady_clock::now();
      base.advance(steps);
      rounds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
          static_cast<double>(steps));
    }
    std::sort(rounds.begin(), rounds.end());
    team = rounds[2];
  }
  if (world.rank() == 0)
    fmt::print(
        "bench_ranks: {} rank(s), l0 = {} m, {} particles ({} owned on rank 0, {} "
        "ghosts), {}: {:.2f} us per step (median of 5 rounds of {} steps)\n",
        world.size(), l0, base.particles().size(), part.layout.owned.size(),
        part.layout.size() - part.layout.owned.size(), model_name, per_step[2] * 1e6, steps);
  // Each rank's halo per step: its exchanges' wall time and bytes sent.
  const double total_steps = 5.0 * static_cast<double>(steps);
  const std::vector<double> halo = world.all_gather(
      {part.halo_cost.seconds / total_steps, part.halo_cost.bytes_sent / total_steps});
  if (world.rank() == 0)
    for (int r = 0; r < world.size(); ++r)
      fmt::print("bench_ranks:   rank {}: halo {:.2f} us and {:.0f} bytes sent per step\n", r,
                 halo[2 * static_cast<std::size_t>(r)] * 1e6,
                 halo[2 * static_cast<std::size_t>(r) + 1]);
  if (team > 0)
    fmt::print("bench_ranks: the team step at 1 thread: {:.2f} us per step\n", team * 1e6);
  return 0;
}
