#pragma once
// A compressible ideal gas on a uniform grid: finite volumes, MUSCL
// reconstruction of the primitive variables with van Leer's limiter, HLLC
// fluxes, and the two-stage strong-stability-preserving Runge-Kutta step
// (Heun's). Each face's flux is computed once, and each cell sums its faces
// axis by axis in a fixed order, so the bits do not depend on how the loops
// are shared. docs/MODEL.md has the equations and the reasons for each
// choice.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "src/gas/gas_grid.hpp"
#include "src/gas/ideal_gas.hpp"

namespace mpsolid {

enum class GasBoundaryKind {
  slip_wall,  // the normal velocity mirrored: no mass or energy through it
  inflow,     // a given state outside
  outflow,    // transmissive: the nearest cell's state continued outside
};

template <int Dim>
struct GasBoundary {
  GasBoundaryKind kind = GasBoundaryKind::slip_wall;
  GasPrimitive<Dim> state{};  // outside the face, for inflow
};

// A gas state that cannot go on: where, what and its value.
class GasFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A wall inside the grid that the gas cannot cross (2D): a segment, its
// ends' velocities, and the gas's force on it.
struct GasWallSegment {
  std::array<double, 2> a{}, b{};    // m
  std::array<double, 2> va{}, vb{};  // m/s
};

template <int Dim>
struct GasTotals {
  double mass = 0;                     // kg (per metre of depth in 2D)
  std::array<double, Dim> momentum{};  // kg m/s
  double energy = 0;                   // J
};

// What the gas exchanged with the world since it was made: through the
// grid's open boundaries, with the walls inside it, and the gas of cells a
// wall covered with no gas next to them. The gas's totals change by exactly
// inflow - (wall_impulse, wall_work) - lost, round-off aside.
template <int Dim>
struct GasExchange {
  GasTotals<Dim> inflow;                   // into the grid through its boundaries
  std::array<double, Dim> wall_impulse{};  // N s: the gas's impulse on the walls
  double wall_work = 0;                    // J: the gas's work on the walls
  // J: the work of the solid cells' pressure (set_solid_pressure) on the
  // walls: not the gas's; the walls get wall_work + solid_work.
  double solid_work = 0;
  GasTotals<Dim> lost;  // in cells covered with no gas next to them
};

template <int Dim>
class GasSolver {
 public:
  static constexpr int kVars = Dim + 2;                                 // rho, the momentum, E
  using Boundaries = std::array<std::array<GasBoundary<Dim>, 2>, Dim>;  // [axis][low, high]

  GasSolver(GasGrid<Dim> grid, double gamma, Boundaries boundaries);

  const GasGrid<Dim>& grid() const { return grid_; }
  double gamma() const { return gamma_; }
  void set(const std::array<int, Dim>& cell, const GasPrimitive<Dim>& w);
  GasPrimitive<Dim> primitive(const std::array<int, Dim>& cell) const;
  // The largest step the CFL number allows: cfl / max_cells sum_axes (|u| + c) / h.
  double stable_dt(double cfl) const;
  // One step of dt. Throws GasFailure, the state unchanged, when a cell's
  // density or pressure would go non-positive or non-finite.
  void advance(double dt);
  // Over the interior cells, summed in storage order.
  GasTotals<Dim> totals() const;

  // Walls inside the grid (2D): the bodies' outlines, closed polygons
  // (several may cross the grid's edges). An interior face whose two cell
  // centres lie on either side of a segment is closed: each of its cells
  // gets the flux of a wall (no mass; the pressure of the half Riemann
  // problem along the segment's normal, moving at the segment's velocity
  // there), and no reconstruction reads across it; the gas cell on either
  // side reaches to the wall (a volume of 0.5 to 2 cells). A cell whose centre is
  // inside an odd number of outlines (counted along its row from the left,
  // crossings left of the grid included) is solid: not stepped, not in the
  // totals, pushing no wall. Replaces the walls set before; a cell that was
  // solid and is gas again takes the mean of its gas neighbours through open
  // faces (GasFailure when it has none: a wall moved more than a cell).
  void set_walls(const std::vector<GasWallSegment>& walls) requires(Dim == 2);
  std::size_t closed_faces() const { return blocked_.size(); }
  bool solid(const std::array<int, Dim>& cell) const {
    return !solid_.empty() && solid_[grid_.index(cell)] != 0;
  }
  // Whether the lower face of `cell` along `axis` is closed.
  bool closed(const std::array<int, Dim>& cell, int axis) const {
    return !blocked_.empty() && closed_[axis][grid_.index(cell)] >= 0;
  }
  const GasExchange<Dim>& exchange() const { return exchange_; }
  // A saved gas put back (after set_walls with the walls it had): conserved
  // variable v over the whole storage, and the exchange so far.
  void set_conserved(int v, const std::vector<double>& values);
  void set_exchange(const GasExchange<Dim>& x) { exchange_ = x; }
  // The pressure a solid cell pushes its walls with (0 by default): a
  // body's unstressed state at an ambient pressure feels only the gas's
  // excess over it.
  void set_solid_pressure(double p) { solid_pressure_ = p; }
  // The gas's force on each wall segment over the last step (the mean of
  // its stages'), split between the segment's ends as the closed faces lie
  // along it: [segment][end a x, end a y, end b x, end b y], N per metre of
  // depth in 2D.
  const std::vector<std::array<double, 2 * Dim>>& wall_forces() const { return wall_forces_; }
  // Conserved variable v (0: rho, 1..Dim: momentum, Dim + 1: E) over the
  // grid's storage, ghosts included.
  const std::vector<double>& conserved(int v) const { return q_[static_cast<std::size_t>(v)]; }

 private:
  using Fields = std::array<std::vector<double>, kVars>;
  // A closed face: the lower face of cell k along `axis`, crossed by wall
  // segment `piece` at parameter t, where the wall's unit normal (pointing
  // along +axis) is n and its velocity v.
  struct ClosedFace {
    std::size_t k;
    int axis;
    std::uint32_t piece;
    double t;
    double offset;  // m: the crossing's place along the axis less the face's
    std::array<double, Dim> n, v;
  };
  GasPrimitive<Dim> primitive_at(std::size_t k) const;  // of storage index k
  void fill_ghosts(Fields& q) const;
  void residual(Fields& q, Fields& rhs);
  bool axis_active(int axis) const;
  void check(const Fields& q) const;
  void close_face(const ClosedFace& f);
  bool pushes(std::size_t k) const { return solid_.empty() || solid_[k] == 0; }
  // Adds the closed faces' forces on the walls in this stage, and their
  // work over dt, with `weight`.
  void add_wall_forces(std::vector<std::array<double, 2 * Dim>>& forces, double weight, double dt);
  // Sums the fluxes through the grid's edges along axis a into stage_inflow_.
  void add_stage_inflow(int a);
  // The cells a new set of walls covers and uncovers (the previous mask
  // `was` and closed faces `was_closed`).
  void exchange_cells(const std::vector<std::uint8_t>& was,
                      const std::array<std::vector<std::int32_t>, Dim>& was_closed,
                      const std::vector<double>& was_fraction);
  double fraction(std::size_t k) const { return fraction_.empty() ? 1.0 : fraction_[k]; }

  GasGrid<Dim> grid_;
  double gamma_;
  Boundaries boundaries_;
  Fields q_, stage_, rhs_, flux_;
  Fields w_;  // primitives of the state being differenced: rho, u, p
  std::vector<ClosedFace> blocked_;
  // Per axis and storage index: the closed face below cell k, or -1.
  std::array<std::vector<std::int32_t>, Dim> closed_;
  // Each closed face's flux into the cell below it, and the two sides' wall
  // pressures, in the stage being differenced.
  std::vector<std::array<double, kVars>> below_flux_;
  std::vector<std::array<double, 2>> wall_pressures_;
  std::vector<std::array<double, 2 * Dim>> stage_forces_, wall_forces_;
  // Per storage index: 1 for a solid cell or a ghost, once walls are set.
  std::vector<std::uint8_t> solid_;
  // Per storage index: a gas cell's volume in cells (1 without walls): a
  // cell next to a wall reaches to the wall's crossing of the line between
  // the centres, not to the closed face, so the gas it holds is compressed
  // and expanded as the wall moves (the density is its content over this).
  std::vector<double> fraction_;
  GasExchange<Dim> exchange_;
  double solid_pressure_ = 0;
  GasTotals<Dim> stage_inflow_;  // the stage being differenced: per second
};

extern template class GasSolver<2>;
extern template class GasSolver<3>;

}  // namespace mpsolid
