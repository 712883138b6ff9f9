#pragma once
// A compressible ideal gas on a uniform grid: finite volumes, MUSCL
// reconstruction of the primitive variables with van Leer's limiter, HLLC
// fluxes, and the two-stage strong-stability-preserving Runge-Kutta step
// (Heun's). Each face's flux is computed once, and each cell sums its faces
// axis by axis in a fixed order, so the bits do not depend on how the loops
// are shared. docs/MODEL.md has the equations and the reasons for each
// choice.
#include <array>
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

template <int Dim>
struct GasTotals {
  double mass = 0;                     // kg (per metre of depth in 2D)
  std::array<double, Dim> momentum{};  // kg m/s
  double energy = 0;                   // J
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
  // Conserved variable v (0: rho, 1..Dim: momentum, Dim + 1: E) over the
  // grid's storage, ghosts included.
  const std::vector<double>& conserved(int v) const { return q_[static_cast<std::size_t>(v)]; }

 private:
  using Fields = std::array<std::vector<double>, kVars>;
  void fill_ghosts(Fields& q) const;
  void residual(Fields& q, Fields& rhs);
  bool axis_active(int axis) const;
  void check(const Fields& q) const;

  GasGrid<Dim> grid_;
  double gamma_;
  Boundaries boundaries_;
  Fields q_, stage_, rhs_, flux_;
  Fields w_;  // primitives of the state being differenced: rho, u, p
};

extern template class GasSolver<2>;
extern template class GasSolver<3>;

}  // namespace mpsolid
