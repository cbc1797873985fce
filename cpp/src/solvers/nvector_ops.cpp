#include "solvers/nvector_ops.hpp"

#include <nvector/nvector_serial.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <new>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "lagmb/solvers/sundials.hpp"
#include "solvers/sun_compat.hpp"

namespace lagmb::sun {

namespace {

using Index = sunindextype;
using Real = sunrealtype;

Index length(N_Vector v) { return NV_LENGTH_S(v); }
Real* data(N_Vector v) { return NV_DATA_S(v); }

// z = a x + b y
void linear_sum(Real a, N_Vector x, Real b, N_Vector y, N_Vector z) {
  const Real *xd = data(x), *yd = data(y);
  Real* zd = data(z);
  for (Index i = 0, n = length(z); i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
}

void constant(Real c, N_Vector z) { std::fill(data(z), data(z) + length(z), c); }

void product(N_Vector x, N_Vector y, N_Vector z) {
  const Real *xd = data(x), *yd = data(y);
  Real* zd = data(z);
  for (Index i = 0, n = length(z); i < n; ++i) zd[i] = xd[i] * yd[i];
}

void quotient(N_Vector x, N_Vector y, N_Vector z) {
  const Real *xd = data(x), *yd = data(y);
  Real* zd = data(z);
  for (Index i = 0, n = length(z); i < n; ++i) zd[i] = xd[i] / yd[i];
}

void scale(Real c, N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  for (Index i = 0, n = length(z); i < n; ++i) zd[i] = c * xd[i];
}

void absolute(N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  for (Index i = 0, n = length(z); i < n; ++i) zd[i] = std::abs(xd[i]);
}

void inverse(N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  for (Index i = 0, n = length(z); i < n; ++i) zd[i] = Real(1) / xd[i];
}

void add_constant(N_Vector x, Real b, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  for (Index i = 0, n = length(z); i < n; ++i) zd[i] = xd[i] + b;
}

Real max_norm(N_Vector x) {
  const Real* xd = data(x);
  Real m = 0;
  for (Index i = 0, n = length(x); i < n; ++i) m = std::max(m, std::abs(xd[i]));
  return m;
}

// sqrt(sum (x_i w_i)^2 / n)
Real wrms_norm(N_Vector x, N_Vector w) {
  const Real *xd = data(x), *wd = data(w);
  const Index n = length(x);
  Real s = 0;
  for (Index i = 0; i < n; ++i) s += (xd[i] * wd[i]) * (xd[i] * wd[i]);
  return std::sqrt(s / Real(n));
}

// the same over the entries with id_i > 0, still divided by the full length n
Real wrms_norm_mask(N_Vector x, N_Vector w, N_Vector id) {
  const Real *xd = data(x), *wd = data(w), *idd = data(id);
  const Index n = length(x);
  Real s = 0;
  for (Index i = 0; i < n; ++i) {
    const Real p = xd[i] * wd[i];
    s += idd[i] > Real(0) ? p * p : Real(0);
  }
  return std::sqrt(s / Real(n));
}

Real dot(N_Vector x, N_Vector y) {
  const Real *xd = data(x), *yd = data(y);
  Real s = 0;
  for (Index i = 0, n = length(x); i < n; ++i) s += xd[i] * yd[i];
  return s;
}

// z = sum_k c_k X_k. z may be any of the X_k (SUNDIALS passes z = X_1 with two
// vectors), so each block of z is written only after all its terms are read.
int linear_combination(int nvec, Real* c, N_Vector* X, N_Vector z) {
  constexpr Index block = 256;
  Real sum[block];
  Real* zd = data(z);
  const Index n = length(z);
  for (Index i0 = 0; i0 < n; i0 += block) {
    const Index m = std::min(block, n - i0);
    const Real* x0 = data(X[0]) + i0;
    for (Index i = 0; i < m; ++i) sum[i] = c[0] * x0[i];
    for (int k = 1; k < nvec; ++k) {
      const Real* xk = data(X[k]) + i0;
      const Real ck = c[k];
      for (Index i = 0; i < m; ++i) sum[i] += ck * xk[i];
    }
    std::copy(sum, sum + m, zd + i0);
  }
  return 0;
}

// Z_k = a_k x + Y_k
int scale_add_multi(int nvec, Real* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  const Real* xd = data(x);
  const Index n = length(x);
  for (int k = 0; k < nvec; ++k) {
    const Real* yd = data(Y[k]);
    Real* zd = data(Z[k]);
    for (Index i = 0; i < n; ++i) zd[i] = a[k] * xd[i] + yd[i];
  }
  return 0;
}

// Z_k = a X_k + b Y_k
int linear_sum_vector_array(int nvec, Real a, N_Vector* X, Real b, N_Vector* Y, N_Vector* Z) {
  for (int k = 0; k < nvec; ++k) linear_sum(a, X[k], b, Y[k], Z[k]);
  return 0;
}

int scale_vector_array(int nvec, Real* c, N_Vector* X, N_Vector* Z) {
  for (int k = 0; k < nvec; ++k) scale(c[k], X[k], Z[k]);
  return 0;
}

}  // namespace

void use_compiled_vector_ops(N_Vector v) {
  N_Vector_Ops o = v->ops;
  o->nvlinearsum = linear_sum;
  o->nvconst = constant;
  o->nvprod = product;
  o->nvdiv = quotient;
  o->nvscale = scale;
  o->nvabs = absolute;
  o->nvinv = inverse;
  o->nvaddconst = add_constant;
  o->nvmaxnorm = max_norm;
  o->nvwrmsnorm = wrms_norm;
  o->nvwrmsnormmask = wrms_norm_mask;
  o->nvdotprod = dot;
  o->nvlinearcombination = linear_combination;
  o->nvscaleaddmulti = scale_add_multi;
  o->nvlinearsumvectorarray = linear_sum_vector_array;
  o->nvscalevectorarray = scale_vector_array;
}

}  // namespace lagmb::sun

namespace lagmb {

namespace {

// Serial vectors with random entries in [-1, 1], or (for weights and masks) [0, 1] / {-1, 1}.
struct VectorSet {
  VectorSet(SUNContext ctx, sunindextype n, int count, bool ours) {
    for (int k = 0; k < count; ++k) {
      N_Vector v = N_VNew_Serial(n, ctx);
      if (!v) throw std::bad_alloc();
      if (ours)
        sun::use_compiled_vector_ops(v);
      else
        N_VEnableFusedOps_Serial(v, SUNTRUE);  // SUNDIALS' own fused kernels as the reference
      v_.push_back(v);
    }
  }
  ~VectorSet() {
    for (N_Vector v : v_) N_VDestroy(v);
  }
  VectorSet(const VectorSet&) = delete;
  VectorSet& operator=(const VectorSet&) = delete;
  N_Vector operator[](int k) const { return v_[k]; }
  std::vector<N_Vector> v_;
};

}  // namespace

std::map<std::string, double> compare_vector_operations(int n, unsigned seed) {
  if (n < 1) throw std::invalid_argument("compare_vector_operations: n must be positive");
  sun::Context ctx;
  constexpr int count = 16;
  VectorSet A(ctx, n, count, true), B(ctx, n, count, false);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  auto fill = [&]() {
    for (int k = 0; k < count; ++k)
      for (int i = 0; i < n; ++i) {
        double x = uniform(random);
        if (k == 14) x = std::abs(x) + 0.1;  // weights
        if (k == 15) x = x > 0 ? 1.0 : -1.0;  // mask: differential (1) or algebraic (-1)
        NV_Ith_S(A[k], i) = NV_Ith_S(B[k], i) = x;
      }
  };
  // the largest difference over all vectors, relative to the largest entry
  auto differ = [&]() {
    double d = 0, scale = 0;
    for (int k = 0; k < count; ++k)
      for (int i = 0; i < n; ++i) {
        d = std::max(d, std::abs(NV_Ith_S(A[k], i) - NV_Ith_S(B[k], i)));
        scale = std::max(scale, std::abs(NV_Ith_S(B[k], i)));
      }
    return d / std::max(scale, 1e-300);
  };
  auto relative = [](double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); };
  std::map<std::string, double> result;
  auto check = [&](const std::string& name, auto&& op) {
    fill();
    op(A);
    op(B);
    result[name] = std::max(result[name], differ());
  };
  auto check_value = [&](const std::string& name, auto&& op) {
    fill();
    result[name] = std::max(result[name], relative(op(A), op(B)));
  };
  std::vector<double> c(13);
  for (double& ck : c) ck = uniform(random);
  auto vectors = [](const VectorSet& S, std::initializer_list<int> ks) {
    std::vector<N_Vector> v;
    for (int k : ks) v.push_back(S[k]);
    return v;
  };
  check("linear_sum", [](const VectorSet& S) { N_VLinearSum(0.3, S[0], -1.7, S[1], S[2]); });
  check("linear_sum", [](const VectorSet& S) { N_VLinearSum(1.0, S[0], -1.0, S[1], S[0]); });
  check("linear_sum", [](const VectorSet& S) { N_VLinearSum(0.5, S[0], 1.0, S[1], S[1]); });
  check("constant", [](const VectorSet& S) { N_VConst(2.5, S[3]); });
  check("product", [](const VectorSet& S) { N_VProd(S[0], S[1], S[2]); });
  check("quotient", [](const VectorSet& S) { N_VDiv(S[0], S[14], S[2]); });
  check("scale", [](const VectorSet& S) { N_VScale(-0.7, S[0], S[2]); });
  check("scale", [](const VectorSet& S) { N_VScale(-0.7, S[0], S[0]); });
  check("abs", [](const VectorSet& S) { N_VAbs(S[0], S[2]); });
  check("inverse", [](const VectorSet& S) { N_VInv(S[14], S[2]); });
  check("add_constant", [](const VectorSet& S) { N_VAddConst(S[0], 0.25, S[2]); });
  check_value("max_norm", [](const VectorSet& S) { return N_VMaxNorm(S[0]); });
  check_value("wrms_norm", [](const VectorSet& S) { return N_VWrmsNorm(S[0], S[14]); });
  check_value("wrms_norm_mask", [](const VectorSet& S) { return N_VWrmsNormMask(S[0], S[14], S[15]); });
  check_value("dot", [](const VectorSet& S) { return N_VDotProd(S[0], S[1]); });
  for (int nvec : {1, 2, 3, 6, 13})
    for (int target : {13, 0, 1}) {  // z apart, z = X_0, z = X_1 (defined by SUNDIALS for two vectors)
      if (target == 1 && nvec != 2) continue;
      check("linear_combination", [&](const VectorSet& S) {
        std::vector<N_Vector> X;
        for (int k = 0; k < nvec; ++k) X.push_back(S[k]);
        std::vector<double> ck(c.begin(), c.begin() + nvec);
        N_VLinearCombination(nvec, ck.data(), X.data(), S[target]);
      });
    }
  check("linear_combination", [&](const VectorSet& S) {  // z = X_0 with c_0 = 1: an update in place
    auto X = vectors(S, {0, 1, 2, 3});
    double ck[] = {1.0, c[1], c[2], c[3]};
    N_VLinearCombination(4, ck, X.data(), S[0]);
  });
  check("scale_add_multi", [&](const VectorSet& S) {
    auto Y = vectors(S, {1, 2, 3}), Z = vectors(S, {4, 5, 6});
    N_VScaleAddMulti(3, c.data(), S[0], Y.data(), Z.data());
  });
  check("scale_add_multi", [&](const VectorSet& S) {  // Z = Y
    auto Y = vectors(S, {1, 2, 3});
    N_VScaleAddMulti(3, c.data(), S[0], Y.data(), Y.data());
  });
  check("linear_sum_vector_array", [&](const VectorSet& S) {
    auto X = vectors(S, {0, 1}), Y = vectors(S, {2, 3}), Z = vectors(S, {4, 5});
    N_VLinearSumVectorArray(2, 0.4, X.data(), -1.1, Y.data(), Z.data());
  });
  check("scale_vector_array", [&](const VectorSet& S) {
    auto X = vectors(S, {0, 1}), Z = vectors(S, {4, 5});
    N_VScaleVectorArray(2, c.data(), X.data(), Z.data());
  });
  return result;
}

}  // namespace lagmb
