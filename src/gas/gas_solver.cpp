#include "src/gas/gas_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "src/core/parallel.hpp"
#include "src/gas/hllc_flux.hpp"
#include "src/gas/wall_riemann.hpp"

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

// The same over the threads: the box's cells, in storage order, shared out
// in contiguous blocks (by cells, not rows: a grid of a few hundred rows
// still splits). f writes only the outputs of its own cell or face, so any
// split gives the same bits.
template <int Dim, class F>
void for_each_cell_parallel(const GasGrid<Dim>& g, std::type_identity_t<std::array<int, Dim>> lo,
                            std::type_identity_t<std::array<int, Dim>> hi, F&& f) {
  std::size_t cells = 1;
  for (int d = 0; d < Dim; ++d) {
    if (lo[d] >= hi[d]) return;
    cells *= static_cast<std::size_t>(hi[d] - lo[d]);
  }
  parallel_blocks(0, cells, [&](std::size_t b, std::size_t e) {
    // The block's first cell, then along its rows.
    std::array<int, Dim> c = lo;
    std::size_t rest = b;
    for (int d = 0; d < Dim; ++d) {
      const auto span = static_cast<std::size_t>(hi[d] - lo[d]);
      c[d] = lo[d] + static_cast<int>(rest % span);
      rest /= span;
    }
    std::size_t k = g.index(c);
    for (std::size_t n = b; n < e; ++n) {
      f(c, k);
      if (++c[0] < hi[0]) {
        ++k;
        continue;
      }
      c[0] = lo[0];
      for (int d = 1; d < Dim && ++c[d] == hi[d]; ++d) c[d] = lo[d];
      k = g.index(c);
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
void GasSolver<Dim>::set_conserved(int v, const std::vector<double>& values) {
  if (v < 0 || v >= kVars || values.size() != grid_.storage())
    throw std::invalid_argument("set_conserved: not a variable of this grid");
  q_[static_cast<std::size_t>(v)] = values;
}

template <int Dim>
GasPrimitive<Dim> GasSolver<Dim>::primitive(const std::array<int, Dim>& cell) const {
  return primitive_at(grid_.index(cell));
}

template <int Dim>
GasPrimitive<Dim> GasSolver<Dim>::primitive_at(std::size_t k) const {
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
  for_each_cell(grid_, lo, hi, [&](const std::array<int, Dim>& c, std::size_t k) {
    if (!pushes(k)) return;
    const GasPrimitive<Dim> w = primitive(c);
    const double sound = sound_speed(w.rho, w.p, gamma_);
    double rate = 0;
    for (int d = 0; d < Dim; ++d)
      if (axis_active(d)) rate += std::abs(w.u[d]) + sound;
    worst = std::max(worst, rate / fraction(k));
  });
  // A wall pushed hard into its gas sends a shock faster than the gas's own
  // |u| + c (a piston started impulsively): the cells on each closed face.
  for (const ClosedFace& f : blocked_)
    for (const double side : {-1.0, 1.0}) {  // the cell below, above the face
      const std::size_t k = side < 0 ? f.k - grid_.stride(f.axis) : f.k;
      if (!pushes(k)) continue;
      const GasPrimitive<Dim> w = primitive_at(k);
      double un = 0, wall_un = 0, spread = 0;  // toward the wall; the axes the wave crosses
      for (int d = 0; d < Dim; ++d) {
        un -= side * w.u[d] * f.n[d];
        wall_un -= side * f.v[d] * f.n[d];
        spread += std::abs(f.n[d]);
      }
      const double wave = wall_wave_speed(w.rho, un, w.p, gamma_, wall_un) * spread;
      worst = std::max(worst, wave / fraction(k));
    }
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
  stage_inflow_ = {};
  const double inv_h = 1 / grid_.h;
  for (int a = 0; a < Dim; ++a) {
    if (!axis_active(a)) continue;
    const std::size_t s = grid_.stride(a);
    // The flux through each cell's lower face along a (k the upper cell).
    std::array<int, Dim> lo{}, hi = grid_.cells;
    hi[a] += 1;
    const std::vector<std::int32_t>* closed = blocked_.empty() ? nullptr : &closed_[a];
    const auto is_closed = [&](std::size_t face) { return closed && (*closed)[face] >= 0; };
    for_each_cell_parallel(grid_, lo, hi, [&](const std::array<int, Dim>&, std::size_t k) {
      if (is_closed(k)) {
        close_face(blocked_[static_cast<std::size_t>((*closed)[k])]);
        return;
      }
      std::array<double, kVars> lv, rv;  // rho, u, p on each side of the face
      // No slope reads across a closed face: first order on that side.
      const bool flat_l = is_closed(k - s), flat_r = is_closed(k + s);
      for (int v = 0; v < kVars; ++v) {
        const std::vector<double>& w = w_[v];
        const double w0 = w[k - 2 * s], w1 = w[k - s], w2 = w[k], w3 = w[k + s];
        lv[v] = flat_l ? w1 : w1 + 0.5 * van_leer(w1 - w0, w2 - w1);
        rv[v] = flat_r ? w2 : w2 - 0.5 * van_leer(w2 - w1, w3 - w2);
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
    add_stage_inflow(a);
    // A cell's upper face, when closed, has the flux the wall gives it. A
    // solid cell keeps its state.
    for_each_cell_parallel(grid_, std::array<int, Dim>{}, grid_.cells,
                           [&](const std::array<int, Dim>&, std::size_t k) {
                             if (!pushes(k)) return;
                             const std::size_t up = k + s;
                             const double inv_volume = inv_h / fraction(k);
                             const std::int32_t c = closed ? (*closed)[up] : -1;
                             for (int v = 0; v < kVars; ++v) {
                               const double upper =
                                   c >= 0 ? below_flux_[static_cast<std::size_t>(c)][v]
                                          : flux_[v][up];
                               rhs[v][k] -= (upper - flux_[v][k]) * inv_volume;
                             }
                           });
  }
}

// A closed face's two fluxes: the cell below sees a wall ahead along n,
// the cell above one behind it; each gets no mass, the wall pressure of its
// own half Riemann problem along the face's axis, and that pressure's work
// at the wall's velocity.
template <int Dim>
void GasSolver<Dim>::close_face(const ClosedFace& f) {
  const std::size_t s = grid_.stride(f.axis);
  const std::size_t below = f.k - s, above = f.k;
  const std::size_t i = static_cast<std::size_t>(closed_[f.axis][f.k]);
  double un_below = 0, un_above = 0, wall_un = 0;
  for (int d = 0; d < Dim; ++d) {
    un_below += w_[1 + d][below] * f.n[d];
    un_above += w_[1 + d][above] * f.n[d];
    wall_un += f.v[d] * f.n[d];
  }
  const double p_below = wall_pressure(w_[0][below], un_below, w_[Dim + 1][below], gamma_, wall_un);
  const double p_above =
      wall_pressure(w_[0][above], -un_above, w_[Dim + 1][above], gamma_, -wall_un);
  wall_pressures_[i] = {p_below, p_above};
  std::array<double, kVars>& fb = below_flux_[i];
  fb.fill(0.0);
  fb[1 + f.axis] = p_below;
  fb[Dim + 1] = p_below * f.v[f.axis];
  flux_[0][above] = 0.0;
  for (int d = 0; d < Dim; ++d) flux_[1 + d][above] = 0.0;
  flux_[1 + f.axis][above] = p_above;
  flux_[Dim + 1][above] = p_above * f.v[f.axis];
}

template <int Dim>
void GasSolver<Dim>::add_wall_forces(std::vector<std::array<double, 2 * Dim>>& forces,
                                     double weight, double dt) {
  double area = 1;  // a face's area (per metre of depth in 2D)
  for (int d = 0; d + 1 < Dim; ++d) area *= grid_.h;
  for (std::size_t i = 0; i < blocked_.size(); ++i) {
    const ClosedFace& f = blocked_[i];
    const std::size_t s = grid_.stride(f.axis);
    // The gas below pushes the wall along +axis, the gas above along -axis;
    // a solid cell pushes with the solid pressure.
    const bool gas_below = pushes(f.k - s), gas_above = pushes(f.k);
    const double below = gas_below ? wall_pressures_[i][0] : 0.0;
    const double above = gas_above ? wall_pressures_[i][1] : 0.0;
    const double solid =
        ((gas_below ? 0.0 : solid_pressure_) - (gas_above ? 0.0 : solid_pressure_)) * area;
    const double push = weight * (below - above) * area;
    std::array<double, 2 * Dim>& out = forces[f.piece];
    out[f.axis] += (1 - f.t) * (push + weight * solid);
    out[Dim + f.axis] += f.t * (push + weight * solid);
    exchange_.wall_impulse[f.axis] += push * dt;
    exchange_.wall_work += push * f.v[f.axis] * dt;
    exchange_.solid_work += weight * solid * f.v[f.axis] * dt;
  }
}

template <int Dim>
void GasSolver<Dim>::add_stage_inflow(int a) {
  // The faces on the grid's edges along a, each side's in storage order:
  // flux_ runs along +a, so it comes in at the low side and goes out at the
  // high one.
  double area = 1;
  for (int d = 0; d + 1 < Dim; ++d) area *= grid_.h;
  const std::size_t s = grid_.stride(a);
  for (int side = 0; side < 2; ++side) {
    std::array<int, Dim> lo{}, hi = grid_.cells;
    lo[a] = side == 0 ? 0 : grid_.cells[a];
    hi[a] = lo[a] + 1;
    const double sign = side == 0 ? area : -area;
    for_each_cell(grid_, lo, hi, [&](const std::array<int, Dim>&, std::size_t k) {
      if (!pushes(side == 0 ? k : k - s)) return;
      stage_inflow_.mass += sign * flux_[0][k];
      for (int d = 0; d < Dim; ++d) stage_inflow_.momentum[d] += sign * flux_[1 + d][k];
      stage_inflow_.energy += sign * flux_[Dim + 1][k];
    });
  }
}

template <int Dim>
void GasSolver<Dim>::set_walls(const std::vector<GasWallSegment>& walls) requires(Dim == 2) {
  std::vector<std::uint8_t> was;
  was.swap(solid_);
  std::array<std::vector<std::int32_t>, Dim> was_closed;
  was_closed.swap(closed_);
  blocked_.clear();
  for (auto& c : closed_) c.assign(grid_.storage(), -1);
  // Per cell: the parity of the crossings of its row between it and the
  // cell before it (or, for the row's first cell, anywhere to its left).
  std::vector<std::uint8_t> flips(grid_.storage(), 0);
  const double h = grid_.h;
  // The faces along axis a lie on the lines through the cell centres
  // across it; a segment closes the face its crossing of such a line falls
  // in (half-open in the segment, so a vertex where an outline passes
  // through a line is crossed once, and one where it only touches the line
  // twice or never).
  for (std::uint32_t piece = 0; piece < walls.size(); ++piece) {
    const GasWallSegment& w = walls[piece];
    const double dx = w.b[0] - w.a[0], dy = w.b[1] - w.a[1], length = std::hypot(dx, dy);
    if (!(length > 0)) continue;
    for (int a = 0; a < 2; ++a) {
      const int across = 1 - a;  // the axis the lines are numbered along
      const double from = w.a[across], to = w.b[across];
      if (from == to) continue;  // parallel to the lines
      std::array<double, 2> n{dy / length, -dx / length};
      if (n[a] < 0) n = {-n[0], -n[1]};
      const double lo = std::min(from, to), hi = std::max(from, to);
      // From a line before the first the division could round past: the
      // comparisons with lo and hi below decide, exactly as for the
      // segment that shares this end.
      const double first = std::floor((lo - grid_.origin[across]) / h - 0.5);
      for (int line = static_cast<int>(std::clamp(first, 0.0, double(grid_.cells[across])));
           line < grid_.cells[across]; ++line) {
        const double at = grid_.origin[across] + (line + 0.5) * h;
        if (at >= hi) break;
        if (at < lo) continue;
        const double t = (at - from) / (to - from);
        const double along = w.a[a] + t * (w.b[a] - w.a[a]);
        // The cell above the crossing along a (0 for any crossing left of
        // the first centre).
        const double upper = std::floor((along - grid_.origin[a]) / h + 0.5);
        if (upper > grid_.cells[a] - 1) continue;
        std::array<int, 2> cell{};
        cell[a] = upper < 0 ? 0 : static_cast<int>(upper);
        cell[across] = line;
        const std::size_t k = grid_.index(cell);
        if (a == 0) flips[k] ^= 1;
        if (upper < 1 || closed_[a][k] >= 0) continue;  // a grid edge, or closed already
        const double face = grid_.origin[a] + upper * h;
        ClosedFace f{k, a, piece, t, along - face, n, {}};
        for (int d = 0; d < 2; ++d) f.v[d] = (1 - t) * w.va[d] + t * w.vb[d];
        closed_[a][k] = static_cast<std::int32_t>(blocked_.size());
        blocked_.push_back(f);
      }
    }
  }
  solid_.assign(grid_.storage(), 1);
  for (int j = 0; j < grid_.cells[1]; ++j) {
    std::uint8_t inside = 0;
    std::size_t k = grid_.index({0, j});
    for (int i = 0; i < grid_.cells[0]; ++i, ++k) solid_[k] = inside ^= flips[k];
  }
  std::vector<double> was_fraction;
  was_fraction.swap(fraction_);
  fraction_.assign(grid_.storage(), 1.0);
  for (const ClosedFace& f : blocked_) {
    const std::size_t below = f.k - grid_.stride(f.axis);
    if (!solid_[below]) fraction_[below] += f.offset / h;
    if (!solid_[f.k]) fraction_[f.k] -= f.offset / h;
  }
  for (double& v : fraction_) v = std::clamp(v, 0.5, 2.0);
  if (!was.empty()) exchange_cells(was, was_closed, was_fraction);
  below_flux_.assign(blocked_.size(), {});
  wall_pressures_.assign(blocked_.size(), {});
  wall_forces_.assign(walls.size(), {});
  stage_forces_.assign(walls.size(), {});
}

template <int Dim>
void GasSolver<Dim>::exchange_cells(const std::vector<std::uint8_t>& was,
                                    const std::array<std::vector<std::int32_t>, Dim>& was_closed,
                                    const std::vector<double>& was_fraction) {
  double volume = 1;
  for (int d = 0; d < Dim; ++d) volume *= grid_.h;
  // Work in contents (per cell volume) while the walls move: each gas cell's
  // content is its state times its old volume.
  for_each_cell(grid_, std::array<int, Dim>{}, grid_.cells,
                [&](const std::array<int, Dim>&, std::size_t k) {
                  const double f = was_fraction.empty() ? 1.0 : was_fraction[k];
                  if (was[k] || f == 1.0) return;  // a whole cell's state is its content
                  for (int v = 0; v < kVars; ++v) q_[v][k] *= f;
                });
  // The neighbours of k through faces open in `faces` that were gas (or have
  // been filled here) and are gas, in a fixed order.
  std::vector<std::uint8_t> shut = was;
  const auto neighbours = [&](std::size_t k,
                              const std::array<std::vector<std::int32_t>, Dim>& faces) {
    std::vector<std::size_t> out;
    for (int a = 0; a < Dim; ++a) {
      const std::size_t s = grid_.stride(a);
      for (const std::size_t nb : {k - s, k + s}) {
        const std::size_t face = nb < k ? k : nb;
        if (!shut[nb] && !solid_[nb] && (faces[a].empty() || faces[a][face] < 0)) out.push_back(nb);
      }
    }
    return out;
  };
  // A covered cell's gas goes to the neighbours it was open to, in equal
  // shares: the gas keeps its mass, momentum and energy, as a piston keeps
  // the gas it pushes.
  for_each_cell(grid_, std::array<int, Dim>{}, grid_.cells,
                [&](const std::array<int, Dim>&, std::size_t k) {
                  if (was[k] || !solid_[k]) return;
                  const std::vector<std::size_t> to = neighbours(k, was_closed);
                  if (to.empty()) {
                    exchange_.lost.mass += q_[0][k] * volume;
                    for (int d = 0; d < Dim; ++d)
                      exchange_.lost.momentum[d] += q_[1 + d][k] * volume;
                    exchange_.lost.energy += q_[Dim + 1][k] * volume;
                  } else {
                    for (const std::size_t nb : to)
                      for (int v = 0; v < kVars; ++v)
                        q_[v][nb] += q_[v][k] / static_cast<double>(to.size());
                  }
                  const double f = was_fraction.empty() ? 1.0 : was_fraction[k];
                  for (int v = 0; v < kVars; ++v) q_[v][k] /= f;  // its state, frozen
                });
  // An uncovered cell and the neighbours it opens to share their gas in
  // proportion to their new volumes: the gas fills the volume the wall
  // left, keeping its mass, momentum and energy. A cell filled so is gas
  // for the uncovered cells after it (passes until none is filled); one
  // that no gas reaches (a gap opening between two bodies in contact) stays
  // out of the gas, solid, until a later set of walls lets gas in.
  std::vector<std::size_t> pending;
  for_each_cell(grid_, std::array<int, Dim>{}, grid_.cells,
                [&](const std::array<int, Dim>&, std::size_t k) {
                  if (was[k] && !solid_[k]) pending.push_back(k);
                });
  for (bool filled = true; filled && !pending.empty();) {
    filled = false;
    std::vector<std::size_t> unreached;
    for (const std::size_t k : pending) {
      const std::vector<std::size_t> from = neighbours(k, closed_);
      if (from.empty()) {
        unreached.push_back(k);
        continue;
      }
      double total = fraction_[k];
      for (const std::size_t nb : from) total += fraction_[nb];
      for (int v = 0; v < kVars; ++v) {
        double sum = 0;
        for (const std::size_t nb : from) sum += q_[v][nb];
        q_[v][k] = sum * (fraction_[k] / total);
        for (const std::size_t nb : from) q_[v][nb] = sum * (fraction_[nb] / total);
      }
      shut[k] = 0;
      filled = true;
    }
    pending.swap(unreached);
  }
  for (const std::size_t k : pending) solid_[k] = 1;
  // Back to states: each gas cell's content over its new volume.
  for_each_cell(grid_, std::array<int, Dim>{}, grid_.cells,
                [&](const std::array<int, Dim>&, std::size_t k) {
                  if (solid_[k] || fraction_[k] == 1.0) return;
                  for (int v = 0; v < kVars; ++v) q_[v][k] /= fraction_[k];
                });
}

template <int Dim>
void GasSolver<Dim>::check(const Fields& q) const {
  for_each_cell(grid_, std::array<int, Dim>{}, grid_.cells,
                [&](const std::array<int, Dim>& c, std::size_t k) {
                  if (!pushes(k)) return;
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
  // Heun's SSP-RK2: U1 = U + dt L(U); U' = (U + U1 + dt L(U1)) / 2. The
  // walls get the mean of the two stages' forces, as the gas does, and the
  // exchanges are the stages' means too (kept only when the step is).
  const GasExchange<Dim> before = exchange_;
  for (auto& f : stage_forces_) f.fill(0.0);
  const auto add_inflow = [&] {
    exchange_.inflow.mass += 0.5 * dt * stage_inflow_.mass;
    for (int d = 0; d < Dim; ++d)
      exchange_.inflow.momentum[d] += 0.5 * dt * stage_inflow_.momentum[d];
    exchange_.inflow.energy += 0.5 * dt * stage_inflow_.energy;
  };
  residual(q_, rhs_);
  add_wall_forces(stage_forces_, 0.5, dt);
  add_inflow();
  const std::size_t n = grid_.storage();
  parallel_for(0, n, [&](std::size_t k) {
    for (int v = 0; v < kVars; ++v) stage_[v][k] = q_[v][k] + dt * rhs_[v][k];
  });
  try {
    check(stage_);
    residual(stage_, rhs_);
    add_wall_forces(stage_forces_, 0.5, dt);
    add_inflow();
    parallel_for(0, n, [&](std::size_t k) {
      for (int v = 0; v < kVars; ++v)
        stage_[v][k] = 0.5 * (q_[v][k] + (stage_[v][k] + dt * rhs_[v][k]));
    });
    check(stage_);
  } catch (const GasFailure&) {
    exchange_ = before;
    throw;
  }
  wall_forces_ = stage_forces_;
  std::swap(q_, stage_);
}

template <int Dim>
GasTotals<Dim> GasSolver<Dim>::totals() const {
  GasTotals<Dim> t;
  double volume = 1;
  for (int d = 0; d < Dim; ++d) volume *= grid_.h;
  for_each_cell(grid_, std::array<int, Dim>{}, grid_.cells,
                [&](const std::array<int, Dim>&, std::size_t k) {
                  if (!pushes(k)) return;
                  const double v = volume * fraction(k);
                  t.mass += q_[0][k] * v;
                  for (int d = 0; d < Dim; ++d) t.momentum[d] += q_[1 + d][k] * v;
                  t.energy += q_[Dim + 1][k] * v;
                });
  return t;
}

template class GasSolver<2>;
template class GasSolver<3>;

}  // namespace mpsolid
