#include "nvector_ops.hpp"

#include <nvector/nvector_serial.h>

#include <algorithm>
#include <cmath>

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

// z = sum_k c_k X_k, in one pass per vector (z may be X_0)
int linear_combination(int nvec, Real* c, N_Vector* X, N_Vector z) {
  Real* zd = data(z);
  const Index n = length(z);
  if (X[0] == z) {
    if (c[0] != Real(1))
      for (Index i = 0; i < n; ++i) zd[i] *= c[0];
  } else {
    const Real* x0 = data(X[0]);
    for (Index i = 0; i < n; ++i) zd[i] = c[0] * x0[i];
  }
  int k = 1;
  for (; k + 1 < nvec; k += 2) {  // two at a time: half the passes over z
    const Real *a = data(X[k]), *b = data(X[k + 1]);
    const Real ca = c[k], cb = c[k + 1];
    for (Index i = 0; i < n; ++i) zd[i] += ca * a[i] + cb * b[i];
  }
  if (k < nvec) {
    const Real* a = data(X[k]);
    for (Index i = 0; i < n; ++i) zd[i] += c[k] * a[i];
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
