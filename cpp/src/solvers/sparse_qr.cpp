// SparseQR (sparse_qr.hpp): a row-by-row Givens QR (George and Heath 1980)
// in a fill-reducing column order, with Heath's rule for dependent columns.
//
// Why our own: SuiteSparseQR is GPL-2+ and needs CHOLMOD and a BLAS/LAPACK;
// Eigen's SparseQR grew as N^2.6 on a chain's Jacobian. The matrices here are
// constraint Jacobians (a few entries per row, columns coupled along the
// joints' graph), for which the column order of approximate minimum degree
// on A^T A keeps R as sparse as the Cholesky factor of A^T A: linear in a
// chain's length.
#include "lagmb/solvers/sparse_qr.hpp"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace lagmb {

struct SparseQR::Impl {
  /// A sparse row: column positions ascending, with their values.
  struct SparseRow {
    std::vector<int> at;
    std::vector<double> value;
    bool empty() const { return at.empty(); }
  };

  int rows = 0, cols = 0;
  SpMat A;                    // (for the solve's refinement)
  std::vector<int> col_at;    // col_at[position] = column of A
  std::vector<int> position;  // position[column]
  std::vector<SparseRow> R;   // R[k]: row k of R, R[k].at[0] == k when present
  std::vector<char> dead;     // dead[k]: column at position k is dependent
  int rank = 0;

  /// Rotates row w into R (Givens), the rows of R it meets changing with it:
  /// at its leading position j, [R_j; w] <- G [R_j; w] with G the rotation
  /// that zeroes w_j; w then starts later. An R row that is empty takes w.
  void absorb(SparseRow w) {
    SparseRow merged_r, merged_w;
    while (!w.empty()) {
      if (w.value[0] == 0.0) {  // (an exact zero: nothing to rotate)
        w.at.erase(w.at.begin());
        w.value.erase(w.value.begin());
        continue;
      }
      const int j = w.at[0];
      SparseRow& rj = R[j];
      if (rj.empty()) {
        rj = std::move(w);
        return;
      }
      const double a = rj.value[0], b = w.value[0], h = std::hypot(a, b);
      const double c = a / h, s = b / h;
      merged_r.at.clear(), merged_r.value.clear(), merged_w.at.clear(), merged_w.value.clear();
      size_t p = 0, q = 0;
      while (p < rj.at.size() || q < w.at.size()) {
        const int ip = p < rj.at.size() ? rj.at[p] : std::numeric_limits<int>::max();
        const int iq = q < w.at.size() ? w.at[q] : std::numeric_limits<int>::max();
        const int i = std::min(ip, iq);
        const double x = ip == i ? rj.value[p++] : 0.0;
        const double y = iq == i ? w.value[q++] : 0.0;
        merged_r.at.push_back(i);
        merged_r.value.push_back(c * x + s * y);
        if (i != j) {  // (w_j becomes 0 by construction)
          merged_w.at.push_back(i);
          merged_w.value.push_back(-s * x + c * y);
        }
      }
      merged_r.value[0] = h;
      std::swap(rj, merged_r);
      std::swap(w, merged_w);
    }
  }

  /// Solves R^T R x = c on the live positions (x in positions; dead ones 0).
  VecX solve_normal(VecX y) const {
    for (int k = 0; k < cols; ++k) {  // R^T z = y, R^T lower triangular
      if (dead[k]) {
        y[k] = 0.0;
        continue;
      }
      y[k] /= R[k].value[0];
      for (size_t e = 1; e < R[k].at.size(); ++e) y[R[k].at[e]] -= R[k].value[e] * y[k];
    }
    for (int k = cols - 1; k >= 0; --k) {  // R x = z
      if (dead[k]) continue;
      double sum = y[k];
      for (size_t e = 1; e < R[k].at.size(); ++e)
        if (!dead[R[k].at[e]]) sum -= R[k].value[e] * y[R[k].at[e]];
      y[k] = sum / R[k].value[0];
    }
    return y;
  }

  /// x (in A's columns) from the normal equations of A x = b on the live columns.
  VecX least_squares_step(const VecX& b) const {
    const VecX c = A.transpose() * b;
    VecX y(cols);
    for (int k = 0; k < cols; ++k) y[k] = c[col_at[k]];
    const VecX z = solve_normal(y);
    VecX x(cols);
    for (int k = 0; k < cols; ++k) x[col_at[k]] = z[k];
    return x;
  }
};

SparseQR::SparseQR(const SpMat& A, double tol) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.rows = int(A.rows());
  s.cols = int(A.cols());
  s.A = A;
  s.A.makeCompressed();
  const int m = s.cols;
  s.R.resize(m);
  s.dead.assign(m, 0);
  if (m == 0) return;

  // column order: approximate minimum degree on the pattern of A^T A
  SpMat pattern = s.A;
  for (int k = 0; k < pattern.nonZeros(); ++k) pattern.valuePtr()[k] = 1.0;  // (no cancellation in B^T B)
  const SpMat gram = pattern.transpose() * pattern;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(gram, order);  // order.indices()[position] = column
  s.col_at.assign(order.indices().data(), order.indices().data() + m);
  s.position.resize(m);
  for (int k = 0; k < m; ++k) s.position[s.col_at[k]] = k;

  // A's rows in positions, taken in the order of their leading positions (less fill)
  using SparseRow = Impl::SparseRow;
  std::vector<SparseRow> rows(s.rows);
  double largest_norm = 0.0;
  for (int c = 0; c < m; ++c) {
    double norm2 = 0.0;
    for (SpMat::InnerIterator it(s.A, c); it; ++it) {
      rows[it.row()].at.push_back(s.position[c]);
      rows[it.row()].value.push_back(it.value());
      norm2 += it.value() * it.value();
    }
    largest_norm = std::max(largest_norm, std::sqrt(norm2));
  }
  for (SparseRow& r : rows) {
    std::vector<int> idx(r.at.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](int a, int b) { return r.at[a] < r.at[b]; });
    SparseRow sorted;
    for (int i : idx) sorted.at.push_back(r.at[i]), sorted.value.push_back(r.value[i]);
    r = std::move(sorted);
  }
  std::vector<int> row_order(s.rows);
  std::iota(row_order.begin(), row_order.end(), 0);
  auto lead = [&](int i) { return rows[i].empty() ? m : rows[i].at[0]; };
  std::stable_sort(row_order.begin(), row_order.end(), [&](int a, int b) { return lead(a) < lead(b); });
  for (int i : row_order) s.absorb(std::move(rows[i]));

  // Heath's rule: a column whose remaining norm |R_kk| is at most tol is
  // dependent on those before it; its row's other entries belong to the
  // columns after it and go on into their rows (what eliminating without it
  // leaves: A_rest^T A_rest = r^T r + R_22^T R_22).
  if (tol < 0.0) tol = 20.0 * (s.rows + s.cols) * std::numeric_limits<double>::epsilon() * largest_norm;
  for (int k = 0; k < m; ++k) {
    SparseRow& rk = s.R[k];
    if (!rk.empty() && std::abs(rk.value[0]) > tol) continue;
    s.dead[k] = 1;
    SparseRow rest;
    if (!rk.empty()) {
      rest.at.assign(rk.at.begin() + 1, rk.at.end());
      rest.value.assign(rk.value.begin() + 1, rk.value.end());
    }
    rk = SparseRow();
    s.absorb(std::move(rest));
  }
  s.rank = m - int(std::count(s.dead.begin(), s.dead.end(), 1));
}

SparseQR::~SparseQR() = default;

bool SparseQR::ok() const {
  for (const auto& r : impl_->R)
    for (double v : r.value)
      if (!std::isfinite(v)) return false;
  return true;
}

int SparseQR::rank() const { return impl_->rank; }

std::vector<int> SparseQR::dependent_columns() const {
  std::vector<int> out;
  for (int k = 0; k < impl_->cols; ++k)
    if (impl_->dead[k]) out.push_back(impl_->col_at[k]);
  std::sort(out.begin(), out.end());
  return out;
}

long SparseQR::nonzeros() const {
  long n = 0;
  for (const auto& r : impl_->R) n += long(r.at.size());
  return n;
}

VecX SparseQR::solve(const VecX& b) const {
  // corrected semi-normal equations (Bjorck 1987): R^T R x = A^T b with R from
  // the QR, then one refinement on the residual; as accurate as applying Q^T
  // to b, without keeping Q
  const Impl& s = *impl_;
  VecX x = s.least_squares_step(b);
  x += s.least_squares_step(b - s.A * x);
  return x;
}

}  // namespace lagmb
