// Bodies (body.hpp); their kinds, how users add them, are in elements/body.cpp.
#include "lagmb/model/body.hpp"

#include <Eigen/Eigenvalues>

namespace lagmb {

bool Body::has_mass_and_inertia() const {
  if (!(mass > 0)) return false;
  if (particle) return true;
  if (!spatial) return inertia > 0;
  const Vec3 moments = Eigen::SelfAdjointEigenSolver<Mat3>(inertia_tensor).eigenvalues();
  return moments.minCoeff() > 1e-12 * moments.maxCoeff();
}

}  // namespace lagmb
