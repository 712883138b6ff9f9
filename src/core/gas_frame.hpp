#pragma once
// The gas's fields at one instant, for a frame of frames.h5: cell-centred
// values on the gas's uniform grid, row by row (x fastest), NaN in the cells
// inside a body (solid: 1). Empty (nx = 0) without a gas.
#include <cstdint>
#include <vector>

namespace mpsolid {

struct GasFrame {
  int nx = 0, ny = 0;
  double x0 = 0, y0 = 0;         // m: the grid's lower-left corner
  double h = 0;                  // m: the cells' side
  std::vector<double> density;   // kg/m^3
  std::vector<double> velocity;  // m/s, (u, v) per cell
  std::vector<double> pressure;  // Pa
  std::vector<std::int8_t> solid;
  bool empty() const { return nx == 0; }
};

}  // namespace mpsolid
