#include "lagmb/solvers/block_cholesky.hpp"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cmath>

#include "lagmb/sparsity.hpp"

namespace lagmb {

BlockCholeskyPattern::BlockCholeskyPattern(const std::vector<int>& sizes,
                                           const std::vector<std::pair<int, int>>& edges) {
  const int nb = int(sizes.size());
  // the elimination order: approximate minimum degree on the block graph
  SparsityPattern g(nb, nb);
  for (int b = 0; b < nb; ++b) g.add(b, b);
  for (auto [a, b] : edges)
    if (a != b) g.add(std::max(a, b), std::min(a, b));
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(g.build(), order);  // order.indices()[position] = block
  position_of_.resize(nb);
  std::vector<int> block_at(nb);
  for (int k = 0; k < nb; ++k) {
    block_at[k] = order.indices()[k];
    position_of_[block_at[k]] = k;
  }
  start_.resize(nb);
  size_.resize(nb);
  for (int k = 0; k < nb; ++k) {
    size_[k] = sizes[block_at[k]];
    start_[k] = rows_;
    rows_ += size_[k];
    block_at_row_.insert(block_at_row_.end(), size_[k], k);
  }
  // symbolic elimination: the later neighbours of block k become neighbours of each other
  std::vector<std::vector<int>> later(nb);
  for (auto [a, b] : edges) {
    const int pa = position_of_[a], pb = position_of_[b];
    if (pa != pb) later[std::min(pa, pb)].push_back(std::max(pa, pb));
  }
  below_begin_.push_back(0);
  for (int k = 0; k < nb; ++k) {
    std::vector<int>& p = later[k];
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    for (size_t a = 0; a < p.size(); ++a)
      for (size_t b = a + 1; b < p.size(); ++b) later[p[a]].push_back(p[b]);
    int row = size_[k];
    for (int j : p) {
      below_block_.push_back(j);
      below_row_.push_back(row);
      row += size_[j];
    }
    below_begin_.push_back(int(below_block_.size()));
    panel_.push_back(values_);
    height_.push_back(row);
    values_ += row * size_[k];
  }
  // where a panel's update lands: block i of panel k in panel j (j <= i, both below k)
  auto offset_in = [&](int j, int i) {
    if (i == j) return 0;
    for (int e = below_begin_[j]; e < below_begin_[j + 1]; ++e)
      if (below_block_[e] == i) return below_row_[e];
    return -1;  // (not reached: the elimination above added every such pair)
  };
  for (int k = 0; k < nb; ++k)
    for (int e = below_begin_[k]; e < below_begin_[k + 1]; ++e) {
      update_begin_.push_back(int(update_row_.size()));
      for (int e2 = e; e2 < below_begin_[k + 1]; ++e2) update_row_.push_back(offset_in(below_block_[e], below_block_[e2]));
    }
}

int BlockCholeskyPattern::slot(int r, int c) const {
  const int kc = block_at_row_[c], kr = block_at_row_[r];
  const int column = panel_[kc] + (c - start_[kc]) * height_[kc];
  if (kr == kc) return r >= c ? column + (r - start_[kc]) : -1;
  for (int e = below_begin_[kc]; e < below_begin_[kc + 1]; ++e)
    if (below_block_[e] == kr) return column + below_row_[e] + (r - start_[kr]);
  return -1;
}

long BlockCholeskyPattern::factor_nonzeros() const {
  long count = 0;
  for (size_t k = 0; k < start_.size(); ++k) count += long(size_[k]) * (size_[k] + 1) / 2 + long(height_[k] - size_[k]) * size_[k];
  return count;
}

/// Right-looking by block columns; within a panel, left-looking by columns:
///   L_kk L_kk^T = S_kk,   L_ik = S_ik L_kk^-T,   S_ij -= L_ik L_jk^T (i, j below k).
bool BlockCholeskyPattern::factorize(double* values, const double* diagonal, double pivot_ratio) const {
  const int nb = int(start_.size());
  for (int k = 0; k < nb; ++k) {
    double* P = values + panel_[k];
    const int H = height_[k], s = size_[k];
    for (int c = 0; c < s; ++c) {
      double* col = P + c * H;
      for (int t = 0; t < c; ++t) {
        const double* other = P + t * H;
        const double f = other[c];
        for (int r = c; r < H; ++r) col[r] -= other[r] * f;
      }
      const double d = col[c];
      if (!(d > 0.0) || !(d > pivot_ratio * diagonal[start_[k] + c])) return false;
      const double l = std::sqrt(d), inv = 1.0 / l;
      col[c] = l;
      for (int r = c + 1; r < H; ++r) col[r] *= inv;
    }
    const int end = below_begin_[k + 1];
    for (int e = below_begin_[k]; e < end; ++e) {
      const int j = below_block_[e], ra = below_row_[e], sj = size_[j], Hj = height_[j];
      double* Pj = values + panel_[j];
      const int* target = update_row_.data() + update_begin_[e] - e;
      for (int e2 = e; e2 < end; ++e2) {
        const int rb = below_row_[e2], si = size_[below_block_[e2]];
        for (int cj = 0; cj < sj; ++cj) {
          double* out = Pj + cj * Hj + target[e2];
          for (int t = 0; t < s; ++t) {
            const double* Lt = P + t * H;
            const double f = Lt[ra + cj];
            for (int ri = 0; ri < si; ++ri) out[ri] -= Lt[rb + ri] * f;
          }
        }
      }
    }
  }
  return true;
}

void BlockCholeskyPattern::solve(const double* values, double* y) const {
  const int nb = int(start_.size());
  // L z = y
  for (int k = 0; k < nb; ++k) {
    const double* P = values + panel_[k];
    const int H = height_[k], s = size_[k];
    double* yk = y + start_[k];
    for (int c = 0; c < s; ++c) {
      double v = yk[c];
      for (int t = 0; t < c; ++t) v -= P[t * H + c] * yk[t];
      yk[c] = v / P[c * H + c];
    }
    for (int e = below_begin_[k]; e < below_begin_[k + 1]; ++e) {
      const int i = below_block_[e], rb = below_row_[e];
      double* yi = y + start_[i];
      for (int t = 0; t < s; ++t) {
        const double* Lt = P + t * H + rb;
        const double f = yk[t];
        for (int ri = 0; ri < size_[i]; ++ri) yi[ri] -= Lt[ri] * f;
      }
    }
  }
  // L^T x = z
  for (int k = nb - 1; k >= 0; --k) {
    const double* P = values + panel_[k];
    const int H = height_[k], s = size_[k];
    double* yk = y + start_[k];
    for (int e = below_begin_[k]; e < below_begin_[k + 1]; ++e) {
      const int i = below_block_[e], rb = below_row_[e];
      const double* yi = y + start_[i];
      for (int t = 0; t < s; ++t) {
        const double* Lt = P + t * H + rb;
        double acc = 0.0;
        for (int ri = 0; ri < size_[i]; ++ri) acc += Lt[ri] * yi[ri];
        yk[t] -= acc;
      }
    }
    for (int c = s - 1; c >= 0; --c) {
      double v = yk[c];
      for (int t = c + 1; t < s; ++t) v -= P[c * H + t] * yk[t];
      yk[c] = v / P[c * H + c];
    }
  }
}

}  // namespace lagmb
