#pragma once
// frames.xdmf: the XDMF 2 sidecar of frames.h5, so ParaView (Xdmf reader)
// opens the frames as a time series of particle point sets with every field.
// Plain text; it names the HDF5 datasets and their shapes, it holds no data.
#include <cstddef>
#include <string>
#include <vector>

namespace mpsolid {

// One per-particle dataset of a frame group.
struct XdmfField {
  std::string name;         // dataset name in the frame group
  std::string number_type;  // XDMF NumberType: Float, Int, Char
  int precision = 8;        // bytes per value
  int components = 1;       // 1 scalar, 2 or 3 a vector (x, y[, z])
};

struct XdmfFrame {
  std::string group;  // HDF5 path of the frame group, e.g. /frames/000003
  double time = 0;    // s
};

// The gas's grid: nx x ny square cells of side h from (x0, y0); nx = 0: none.
struct XdmfGasGrid {
  int nx = 0, ny = 0;
  double x0 = 0, y0 = 0, h = 0;
};

// The document for `frames` in `h5_file` (a name relative to the XDMF file),
// `particles` particles each, positions in the dataset `position` (N x 2, or
// N x 3 for `dimension` 3);
// with a gas, a second time series of the gas's grid with its cell fields
// (`gas_fields`, each ny x nx, shown under their names less "gas_").
std::string xdmf_document(const std::string& h5_file, std::size_t particles,
                          const std::vector<XdmfFrame>& frames,
                          const std::vector<XdmfField>& fields, const XdmfGasGrid& gas = {},
                          const std::vector<XdmfField>& gas_fields = {}, int dimension = 2);

}  // namespace mpsolid
