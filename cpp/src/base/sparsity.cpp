#include "lagmb/sparsity.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace lagmb {

SpMat SparsityPattern::build() const {
  std::vector<std::pair<int, int>> e = entries_;
  // column-major order, duplicates removed
  std::sort(e.begin(), e.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second < b.second : a.first < b.first;
  });
  e.erase(std::unique(e.begin(), e.end()), e.end());
  SpMat A(rows_, cols_);
  // no entries (e.g. a model without bodies): a new matrix is already
  // compressed, and Eigen 3.4's reserve/makeCompressed read past the end of
  // an empty outer index there (AddressSanitizer: heap-buffer-overflow)
  if (e.empty()) return A;
  std::vector<int> per_col(cols_, 0);
  for (const auto& [r, c] : e) per_col[c]++;
  A.reserve(per_col);
  for (const auto& [r, c] : e) A.insert(r, c) = 0.0;
  A.makeCompressed();
  return A;
}

int slot(const SpMat& A, int r, int c) {
  if (r < 0 || c < 0) return -1;
  const int* inner = A.innerIndexPtr();
  const int begin = A.outerIndexPtr()[c], end = A.outerIndexPtr()[c + 1];
  const int* it = std::lower_bound(inner + begin, inner + end, r);
  if (it == inner + end || *it != r)
    throw std::logic_error("lagmb: entry (" + std::to_string(r) + ", " + std::to_string(c) +
                           ") missing from a sparsity pattern");
  return static_cast<int>(it - inner);
}

std::vector<int> embed_slots(const SpMat& part, const SpMat& whole, int row0, int col0,
                             bool transpose) {
  std::vector<int> out;
  out.reserve(part.nonZeros());
  for (int c = 0; c < part.outerSize(); ++c)
    for (SpMat::InnerIterator it(part, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      out.push_back(transpose ? slot(whole, row0 + c, col0 + r) : slot(whole, row0 + r, col0 + c));
    }
  return out;
}

}  // namespace lagmb
