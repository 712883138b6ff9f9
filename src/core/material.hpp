#pragma once
// An isotropic linear-elastic material and its plane-strain Lame constants.
#include <string>

namespace mpsolid {

struct Material {
  std::string name;
  double youngs_modulus = 0.0;  // E (Pa)
  double poisson_ratio = 0.0;   // nu
  double density = 0.0;         // rho (kg/m^3)

  // Lame constants of the 3D material (MODEL.md section 1).
  double lambda() const {
    const double nu = poisson_ratio;
    return youngs_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  }
  double mu() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
};

}  // namespace mpsolid
