// Sod's shock tube (Toro's test 1 on [0, 1], diaphragm at 0.5, to t = 0.2)
// with the gas solver alone, for bench/compare_rhocentralfoam.py: for each
// cell count on the command line, the wall time of the run (median of
// --reps), its steps and the L1 error of density against the exact
// solution, one JSON object per line.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include "src/core/parallel.hpp"
#include "src/gas/exact_riemann.hpp"
#include "src/gas/gas_solver.hpp"

namespace {
using namespace mpsolid;

struct Result {
  double seconds = 0, l1 = 0;
  long long steps = 0;
};

Result run(int n, double cfl) {
  const GasState1D left{1.0, 0.0, 1.0}, right{0.125, 0.0, 0.1};
  GasGrid<2> g;
  g.cells = {n, 1};
  g.h = 1.0 / n;
  GasSolver<2>::Boundaries b;
  b[0][0].kind = b[0][1].kind = GasBoundaryKind::outflow;
  GasSolver<2> gas(g, 1.4, b);
  for (int i = 0; i < n; ++i) {
    const GasState1D s = g.centre({i, 0})[0] < 0.5 ? left : right;
    gas.set({i, 0}, {s.rho, {s.u, 0.0}, s.p});
  }
  Result r;
  const auto start = std::chrono::steady_clock::now();
  for (double t = 0; t < 0.2; ++r.steps) {
    const double dt = std::min(gas.stable_dt(cfl), 0.2 - t);
    gas.advance(dt);
    t += dt;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const ExactRiemann exact(left, right, 1.4);
  for (int i = 0; i < n; ++i)
    r.l1 +=
        std::abs(gas.primitive({i, 0}).rho - exact.sample((g.centre({i, 0})[0] - 0.5) / 0.2).rho) /
        n;
  return r;
}
}  // namespace

int main(int argc, char** argv) {
  int reps = 3, threads = 1;
  double cfl = 0.8;
  std::vector<int> cells;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--reps" && k + 1 < argc)
      reps = std::atoi(argv[++k]);
    else if (a == "--threads" && k + 1 < argc)
      threads = std::atoi(argv[++k]);
    else if (a == "--cfl" && k + 1 < argc)
      cfl = std::atof(argv[++k]);
    else
      cells.push_back(std::atoi(a.c_str()));
  }
  if (cells.empty()) cells = {100, 200, 400, 800, 1600};
  set_thread_count(threads);
  for (const int n : cells) {
    std::vector<double> seconds;
    Result r;
    for (int k = 0; k < reps; ++k) {
      r = run(n, cfl);
      seconds.push_back(r.seconds);
    }
    std::sort(seconds.begin(), seconds.end());
    fmt::print(
        "{{\"cells\": {}, \"steps\": {}, \"seconds\": {:.6g}, \"l1_density\": {:.6g}, "
        "\"threads\": {}, \"cfl\": {}}}\n",
        n, r.steps, seconds[seconds.size() / 2], r.l1, threads, cfl);
  }
}
