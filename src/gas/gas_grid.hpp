#pragma once
// A uniform Cartesian grid of square (cubic) cells in Dim dimensions, with
// two layers of ghost cells on every side (what a MUSCL face reads). Cells
// are stored axis 0 fastest; `index` takes interior cell numbers (ghosts at
// -2, -1 and n, n + 1).
#include <array>
#include <cstddef>

namespace mpsolid {

template <int Dim>
struct GasGrid {
  static constexpr int kGhost = 2;
  std::array<int, Dim> cells{};      // interior cells along each axis
  std::array<double, Dim> origin{};  // m: the interior's lower corner
  double h = 0;                      // m: the cells' side

  int extent(int axis) const { return cells[axis] + 2 * kGhost; }
  std::size_t stride(int axis) const {
    std::size_t s = 1;
    for (int d = 0; d < axis; ++d) s *= static_cast<std::size_t>(extent(d));
    return s;
  }
  std::size_t storage() const {
    return stride(Dim - 1) * static_cast<std::size_t>(extent(Dim - 1));
  }
  std::size_t interior_cells() const {
    std::size_t n = 1;
    for (int d = 0; d < Dim; ++d) n *= static_cast<std::size_t>(cells[d]);
    return n;
  }
  std::size_t index(const std::array<int, Dim>& c) const {
    std::size_t k = 0;
    for (int d = 0; d < Dim; ++d) k += static_cast<std::size_t>(c[d] + kGhost) * stride(d);
    return k;
  }
  // The centre of interior cell c.
  std::array<double, Dim> centre(const std::array<int, Dim>& c) const {
    std::array<double, Dim> x{};
    for (int d = 0; d < Dim; ++d) x[d] = origin[d] + (c[d] + 0.5) * h;
    return x;
  }
};

}  // namespace mpsolid
