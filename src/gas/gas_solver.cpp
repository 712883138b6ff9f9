#include "src/gas/gas_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "src/core/parallel.hpp"
#include "src/gas/hllc_flux.hpp"

namespace mpsolid {

namespace {
// Calls f(cell, index) for every cell of the box lo <= c < hi, axis 0
// fastest (storage order).
template <int Dim, class F>
void for_each_cell(const GasGrid<Dim>& g, std::type_identity_t<std::array<int, Dim>> lo,
                   std::type_identity_t<std::array<int, Dim>> hi, F&& f) {
  for (int d = 0; d < Dim; ++d)
    if (lo[d] >= hi[d]) return;
  std::array<int, Dim> c = lo;
  while (true) {
    c[0] = lo[0];
    std::size_t k = g.index(c);
    for (; c[0] < hi[0]; ++c[0], ++k) f(c, k);
    int d = 1;
    for (; d < Dim; ++d) {
      if (++c[d] < hi[d]) break;
      c[d] = lo[d];
    }
    if (d == Dim) return;
  }
}

// The same over the threads: the box's rows along axis 0 shared out in
// contiguous blocks. f writes only the outputs of its own cell or face, so
// any split gives the same bits.
template <int Dim, class F>
void for_each_cell_parallel(const GasGrid<Dim>& g, std::type_identity_t<std::array<int, Dim>> lo,
                            std::type_identity_t<std::array<int, Dim>> hi, F&& f) {
  std::size_t rows = 1;
  for (int d = 0; d < Dim; ++d) {
    if (lo[d] >= hi[d]) return;
    if (d > 0) rows *= static_cast<std::size_t>(hi[d] - lo[d]);
  }
  parallel_blocks(0, rows, [&](std::size_t b, std::size_t e) {
    for (std::size_t row = b; row < e; ++row) {
      std::array<int, Dim> c = lo;
      std::size_t rest = row;
      for (int d = 1; d < Dim; ++d) {
        const auto span = static_cast<std::size_t>(hi[d] - lo[d]);
        c[d] = lo[d] + static_cast<int>(rest % span);
        rest /= span;
      }
      std::size_t k = g.index(c);
      for (; c[0] < hi[0]; ++c[0], ++k) f(c, k);
    }
  });
}

// van Leer's limited slope from the two one-sided differences.
inline double van_leer(double a, double b) {
  return a * b > 0 ? 2 * a * b / (a + b) : 0.0;
}
}  // namespace

template <int Dim>
GasSolver<Dim>::GasSolver(GasGrid<Dim> grid, double gamma, Boundaries boundaries)
    : grid_(grid), gamma_(gamma), boundaries_(boundaries) {
  if (!(gamma > 1)) throw std::invalid_argument("a gas's gamma must be above 1");
  for (int d = 0; d < Dim; ++d)
    if (grid.cells[d] < 1) throw std::invalid_argument("a gas grid needs a cell along every axis");
  if (!(grid.h > 0)) throw std::invalid_argument("a gas grid's cell size must be positive");
  // Every cell, the corner ghosts no stencil reads included, starts as a
  // valid state, so the primitives of the whole storage are finite.
  const GasConserved<Dim> unit = to_conserved(GasPrimitive<Dim>{1.0, {}, 1.0}, gamma);
  for (Fields* f : {&q_, &stage_, &rhs_, &flux_, &w_})
    for (auto& v : *f) v.assign(grid.storage(), 0.0);
  for (std::size_t k = 0; k < grid.storage(); ++k) {
    for (Fields* f : {&q_, &stage_}) {
      (*f)[0][k] = unit.rho;
      (*f)[Dim + 1][k] = unit.E;
    }
  }
}

template <int Dim>
void GasSolver<Dim>::set(const std::array<int, Dim>& cell, const GasPrimitive<Dim>& w) {
  if (!(w.rho > 0) || !(w.p > 0))
    throw std::invalid_argument("a gas state needs a positive density and pressure");
  const GasConserved<Dim> q = to_conserved(w, gamma_);
  const std::size_t k = grid_.index(cell);
  q_[0][k] = q.rho;
  for (int d = 0; d < Dim; ++d) q_[1 + d][k] = q.m[d];
  q_[Dim + 1][k] = q.E;
}

template <int Dim>
GasPrimitive<Dim> GasSolver<Dim>::primitive(const std::array<int, Dim>& cell) const {
  const std::size_t k = grid_.index(cell);
  GasConserved<Dim> q;
  q.rho = q_[0][k];
  for (int d = 0; d < Dim; ++d) q.m[d] = q_[1 + d][k];
  q.E = q_[Dim + 1][k];
  return to_primitive(q, gamma_);
}

template <int Dim>
bool GasSolver<Dim>::axis_active(int axis) const {
  // One cell between two slip walls: no flux difference along the axis.
  return grid_.cells[axis] > 1 || boundaries_[axis][0].kind != GasBoundaryKind::slip_wall ||
         boundaries_[axis][1].kind != GasBoundaryKind::slip_wall;
}

template <int Dim>
double GasSolver<Dim>::stable_dt(double cfl) const {
  double worst = 0;
  std::array<int, Dim> lo{}, hi = grid_.cells;
  for_each_cell(grid_, lo, hi, [&](const std::array<int, Dim>& c, std::size_t) {
    const GasPrimitive<Dim> w = primitive(c);
    const double sound = sound_speed(w.rho, w.p, gamma_);
    double rate = 0;
    for (int d = 0; d < Dim; ++d)
      if (axis_active(d)) rate += std::abs(w.u[d]) + sound;
    worst = std::max(worst, rate);
  });
  return worst > 0 ? cfl * grid_.h / worst : 0.0;
}

template <int Dim>
void GasSolver<Dim>::fill_ghosts(Fields& q) const {
  constexpr int g = GasGrid<Dim>::kGhost;
  for (int a = 0; a < Dim; ++a) {
    const std::size_t s = grid_.stride(a);
    const int n = grid_.cells[a];
    for (int side = 0; side < 2; ++side) {
      const GasBoundary<Dim>& b = boundaries_[a][side];
      GasConserved<Dim> outside{};
      if (b.kind == GasBoundaryKind::inflow) outside = to_conserved(b.state, gamma_);
      // The interior's face cells on this side, every other axis interior.
      std::array<int, Dim> lo{}, hi = grid_.cells;
      lo[a] = side == 0 ? 0 : n - 1;
      hi[a] = lo[a] + 1;
      for_each_cell(grid_, lo, hi, [&](const std::array<int, Dim>&, std::size_t k) {
        for (int layer = 1; layer <= g; ++layer) {
          // Ghost `layer` outside the face, and its mirror image inside.
          const std::size_t ghost = side == 0 ? k - layer * s : k + layer * s;
          const std::size_t image = side == 0 ? k + (layer - 1) * s : k - (layer - 1) * s;
          switch (b.kind) {
            case GasBoundaryKind::slip_wall:
              for (int v = 0; v < kVars; ++v) q[v][ghost] = q[v][image];
              q[1 + a][ghost] = -q[1 + a][image];
              break;
            case GasBoundaryKind::outflow:
              for (int v = 0; v < kVars; ++v) q[v][ghost] = q[v][k];
              break;
            case GasBoundaryKind::inflow:
              q[0][ghost] = outside.rho;
              for (int d = 0; d < Dim; ++d) q[1 + d][ghost] = outside.m[d];
              q[Dim + 1][ghost] = outside.E;
              break;
          }
        }
      });
    }
  }
}

template <int Dim>
void GasSolver<Dim>::residual(Fields& q, Fields& rhs) {
  fill_ghosts(q);
  parallel_for(0, grid_.storage(), [&](std::size_t k) {
    const double rho = q[0][k];
    double m2 = 0;
    w_[0][k] = rho;
    for (int d = 0; d < Dim; ++d) {
      w_[1 + d][k] = q[1 + d][k] / rho;
      m2 += q[1 + d][k] * q[1 + d][k];
    }
    w_[Dim + 1][k] = (gamma_ - 1) * (q[Dim + 1][k] - 0.5 * m2 / rho);
  });
  parallel_for(0, grid_.storage(), [&](std::size_t k) {
    for (int v = 0; v < kVars; ++v) rhs[v][k] = 0.0;
  });
  const double inv_h = 1 / grid_.h;
  for (int a = 0; a < Dim; ++a) {
    if (!axis_active(a)) continue;
    const std::size_t s = grid_.stride(a);
    // The flux through each cell's lower face along a (k the upper cell).
    std::array<int, Dim> lo{}, hi = grid_.cells;
    hi[a] += 1;
    for_each_cell_parallel(grid_, lo, hi, [&](const std::array<int, Dim>&, std::size_t k) {
      std::array<double, kVars> lv, rv;  // rho, u, p on each side of the face
      for (int v = 0; v < kVars; ++v) {
        const std::vector<double>& w = w_[v];
        const double w0 = w[k - 2 * s], w1 = w[k - s], w2 = w[k], w3 = w[k + s];
        lv[v] = w1 + 0.5 * van_leer(w1 - w0, w2 - w1);
        rv[v] = w2 - 0.5 * van_leer(w2 - w1, w3 - w2);
      }
      if (!(lv[0] > 0 && lv[kVars - 1] > 0 && rv[0] > 0 && rv[kVars - 1] > 0)) {
        for (int v = 0; v < kVars; ++v) {  // first order at this face
          lv[v] = w_[v][k - s];
          rv[v] = w_[v][k];
        }
      }
      GasPrimitive<Dim> l, r;
      l.rho = lv[0];
      r.rho = rv[0];
      for (int d = 0; d < Dim; ++d) {
        l.u[d] = lv[1 + d];
        r.u[d] = rv[1 + d];
      }
      l.p = lv[kVars - 1];
      r.p = rv[kVars - 1];
      const GasConserved<Dim> f = hllc_flux(l, r, gamma_, a);
      flux_[0][k] = f.rho;
      for (int d = 0; d < Dim; ++d) flux_[1 + d][k] = f.m[d];
      flux_[Dim + 1][k] = f.E;
    });
    for_each_cell_parallel(grid_, std::array<int, Dim>{}, grid_.cells,
                           [&](const std::array<int, Dim>&, std::size_t k) {
                             for (int v = 0; v < kVars; ++v)
                               rhs[v][k] -= (flux_[v][k + s] - flux_[v][k]) * inv_h;
                           });
  }
}

template <int Dim>
void GasSolver<Dim>::check(const Fields& q) const {
  for_each_cell(grid_, std::array<int, Dim>{}, grid_.cells,
                [&](const std::array<int, Dim>& c, std::size_t k) {
                  const double rho = q[0][k];
                  double m2 = 0;
                  for (int d = 0; d < Dim; ++d) m2 += q[1 + d][k] * q[1 + d][k];
                  const double p = (gamma_ - 1) * (q[Dim + 1][k] - 0.5 * m2 / rho);
                  if (rho > 0 && p > 0 && std::isfinite(rho) && std::isfinite(p)) return;
                  std::string where;
                  for (int d = 0; d < Dim; ++d) where += fmt::format("{}{}", d ? ", " : "", c[d]);
                  throw GasFailure(fmt::format(
                      "the gas went unphysical in cell ({}): density {:.6g} kg/m^3, pressure "
                      "{:.6g} Pa",
                      where, rho, p));
                });
}

template <int Dim>
void GasSolver<Dim>::advance(double dt) {
  // Heun's SSP-RK2: U1 = U + dt L(U); U' = (U + U1 + dt L(U1)) / 2.
  residual(q_, rhs_);
  const std::size_t n = grid_.storage();
  parallel_for(0, n, [&](std::size_t k) {
    for (int v = 0; v < kVars; ++v) stage_[v][k] = q_[v][k] + dt * rhs_[v][k];
  });
  check(stage_);
  residual(stage_, rhs_);
  parallel_for(0, n, [&](std::size_t k) {
    for (int v = 0; v < kVars; ++v)
      stage_[v][k] = 0.5 * (q_[v][k] + (stage_[v][k] + dt * rhs_[v][k]));
  });
  check(stage_);
  std::swap(q_, stage_);
}

template <int Dim>
GasTotals<Dim> GasSolver<Dim>::totals() const {
  GasTotals<Dim> t;
  double volume = 1;
  for (int d = 0; d < Dim; ++d) volume *= grid_.h;
  for_each_cell(grid_, std::array<int, Dim>{}, grid_.cells,
                [&](const std::array<int, Dim>&, std::size_t k) {
                  t.mass += q_[0][k] * volume;
                  for (int d = 0; d < Dim; ++d) t.momentum[d] += q_[1 + d][k] * volume;
                  t.energy += q_[Dim + 1][k] * volume;
                });
  return t;
}

template class GasSolver<2>;
template class GasSolver<3>;

}  // namespace mpsolid
