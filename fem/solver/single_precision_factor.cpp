#include "fem/solver/single_precision_factor.hpp"

#include <cmath>
#include <stdexcept>

extern "C" {
// The reference BLAS interface (OpenBLAS here, as CHOLMOD's own calls).
void strsv_(const char* uplo, const char* trans, const char* diag, const int* n, const float* a, const int* lda,
            float* x, const int* incx);
void sgemv_(const char* trans, const int* m, const int* n, const float* alpha, const float* a, const int* lda,
            const float* x, const int* incx, const float* beta, float* y, const int* incy);
}

namespace softarm::fem {

void SinglePrecisionFactor::clear() {
  n_ = 0;
  perm_.clear(), super_.clear(), row_start_.clear(), rows_.clear(), value_start_.clear(), values_.clear();
}

bool SinglePrecisionFactor::assign(const cholmod_factor& L) {
  clear();
  if (!L.is_super || !L.is_ll || L.itype != CHOLMOD_INT || L.xtype != CHOLMOD_REAL || L.dtype != CHOLMOD_DOUBLE ||
      !L.x || L.n == 0)
    return false;
  const int n = static_cast<int>(L.n), nsuper = static_cast<int>(L.nsuper);
  const int* perm = static_cast<const int*>(L.Perm);
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  const int* px = static_cast<const int*>(L.px);
  const int* s = static_cast<const int*>(L.s);
  const double* x = static_cast<const double*>(L.x);
  perm_.assign(perm, perm + n);
  super_.assign(super, super + nsuper + 1);
  row_start_.assign(pi, pi + nsuper + 1);
  rows_.assign(s, s + pi[nsuper]);
  value_start_.assign(px, px + nsuper + 1);
  values_.resize(static_cast<std::size_t>(px[nsuper]));
  for (std::size_t k = 0; k < values_.size(); ++k) values_[k] = static_cast<float>(x[k]);
  y_.resize(static_cast<std::size_t>(n));
  n_ = n;
  return true;
}

Eigen::VectorXd SinglePrecisionFactor::solve(const Eigen::VectorXd& b) const {
  if (b.size() != n_) throw std::logic_error("SinglePrecisionFactor::solve: b's size is not the factor's");
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n_);
  // Unit norm first: single precision's range (10⁻³⁸–10³⁸) then holds any residual a path meets.
  const double scale = b.norm();
  if (!(scale > 0) || !std::isfinite(scale)) return out * scale;  // zero stays zero, NaN NaN
  for (int k = 0; k < n_; ++k) y_[k] = static_cast<float>(b[perm_[k]] / scale);
  const int one = 1;
  const float plus = 1, minus = -1, zero = 0;
  const int nsuper = static_cast<int>(super_.size()) - 1;
  // L y = Pb: each supernode's diagonal block solved, then its rows below updated.
  for (int s = 0; s < nsuper; ++s) {
    const int first = super_[s], ncol = super_[s + 1] - first;
    const int nrow = row_start_[s + 1] - row_start_[s], nbelow = nrow - ncol;
    const float* block = values_.data() + value_start_[s];
    strsv_("L", "N", "N", &ncol, block, &nrow, &y_[first], &one);
    if (nbelow == 0) continue;
    below_.resize(static_cast<std::size_t>(nbelow));
    sgemv_("N", &nbelow, &ncol, &plus, block + ncol, &nrow, &y_[first], &one, &zero, below_.data(), &one);
    const int* rows = rows_.data() + row_start_[s] + ncol;
    for (int i = 0; i < nbelow; ++i) y_[rows[i]] -= below_[i];
  }
  // Lᵀ z = y, the supernodes in reverse: the rows below gathered into the block's, then its solve.
  for (int s = nsuper - 1; s >= 0; --s) {
    const int first = super_[s], ncol = super_[s + 1] - first;
    const int nrow = row_start_[s + 1] - row_start_[s], nbelow = nrow - ncol;
    const float* block = values_.data() + value_start_[s];
    if (nbelow > 0) {
      below_.resize(static_cast<std::size_t>(nbelow));
      const int* rows = rows_.data() + row_start_[s] + ncol;
      for (int i = 0; i < nbelow; ++i) below_[i] = y_[rows[i]];
      sgemv_("T", &nbelow, &ncol, &minus, block + ncol, &nrow, below_.data(), &one, &plus, &y_[first], &one);
    }
    strsv_("L", "T", "N", &ncol, block, &nrow, &y_[first], &one);
  }
  for (int k = 0; k < n_; ++k) out[perm_[k]] = scale * static_cast<double>(y_[k]);
  return out;
}

}  // namespace softarm::fem
