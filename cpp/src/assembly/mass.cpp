// The mass matrix M(q) (assembly.hpp): constant diagonal entries, and the
// 4 x 4 blocks of spatial bodies' Euler parameters (elements/spatial_body.hpp).
#include "lagmb/assembly/assembly.hpp"
#include "lagmb/elements/spatial_body.hpp"

namespace lagmb {

void init_mass(const Model& model, Data& d) {
  const VecX& diagonal = model.mass_diagonal();
  const std::vector<int>& slots = model.mass_diagonal_slots();
  d.M.coeffs().setZero();
  d.M_inv.coeffs().setZero();
  d.M_qa.coeffs().setZero();
  for (int i = 0; i < model.n_coordinates(); ++i) {
    d.M.valuePtr()[slots[i]] = diagonal[i];
    d.M_inv.valuePtr()[slots[i]] = diagonal[i] > 0.0 ? 1.0 / diagonal[i] : 0.0;
  }
  if (model.constant_mass()) return;
  const VecX q = model.initial_q();
  assemble_mass(model, d, q.data());
  assemble_mass_inverse(model, d, q.data());
}

void assemble_mass(const Model& model, Data& d, const double* q) {
  double* M = d.M.valuePtr();
  for (const Model::SpatialMass& s : model.spatial_masses()) {
    const Mat4 block = rotational_mass::block(Eigen::Map<const Vec4>(q + s.p), s.J);
    for (int a = 0; a < 16; ++a) M[s.slots[a]] = block.data()[a];
  }
}

void assemble_mass_inverse(const Model& model, Data& d, const double* q) {
  double* M_inv = d.M_inv.valuePtr();
  for (const Model::SpatialMass& s : model.spatial_masses()) {
    if (!(s.jbar > 0.0)) continue;
    const Mat4 inverse = rotational_mass::inverse(Eigen::Map<const Vec4>(q + s.p), s.J_inverse, s.jbar);
    for (int a = 0; a < 16; ++a) M_inv[s.slots[a]] = inverse.data()[a];
  }
}

namespace {
/// y = A x for a compressed column-major A (y zeroed first).
void times(const SpMat& A, const double* x, double* y) {
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* val = A.valuePtr();
  std::fill(y, y + A.rows(), 0.0);
  for (int c = 0; c < A.cols(); ++c)
    for (int k = outer[c]; k < outer[c + 1]; ++k) y[inner[k]] += val[k] * x[c];
}
}  // namespace

void mass_times(const Data& d, const double* a, double* y) { times(d.M, a, y); }

void mass_inverse_times(const Data& d, const double* b, double* y) { times(d.M_inv, b, y); }

void assemble_mass_derivative(const Model& model, Data& d, const double* q, const double* a) {
  double* D = d.M_qa.valuePtr();
  for (const Model::SpatialMass& s : model.spatial_masses()) {
    const Mat4 block = rotational_mass::derivative(Eigen::Map<const Vec4>(q + s.p), s.J, Eigen::Map<const Vec4>(a + s.p));
    for (int k = 0; k < 16; ++k) D[s.slots[k]] = block.data()[k];
  }
}

double kinetic_energy(const Model& model, const double* q, const double* v) {
  const VecX& M = model.mass_diagonal();
  double T = 0.0;
  for (int i = 0; i < M.size(); ++i) T += M[i] * v[i] * v[i];  // 0 at Euler parameters
  T *= 0.5;
  for (const Model::SpatialMass& s : model.spatial_masses())
    T += rotational_mass::kinetic_energy(Eigen::Map<const Vec4>(q + s.p), Eigen::Map<const Vec4>(v + s.p), s.J);
  return T;
}

}  // namespace lagmb
