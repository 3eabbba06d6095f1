// Walker's alias method, Vose's construction (alias_table.h).
#include "phyir/render/alias_table.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"

namespace phyir::render {

AliasTable::AliasTable(const std::vector<float>& weights) : bins_(weights.size()) {
  const size_t n = weights.size();
  std::vector<double> p(n);
  for (size_t i = 0; i < n; ++i) {
    p[i] = std::isfinite(weights[i]) ? std::max(double(weights[i]), 0.0) : 0.0;
    total_ += p[i];
  }
  if (!(total_ > 0.0)) return;
  // scaled[i] = n p_i: bins below 1 ("small") are topped up by one above ("large").
  std::vector<double> scaled(n);
  std::vector<size_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    p[i] /= total_;
    bins_[i].pmf = static_cast<float>(p[i]);
    scaled[i] = p[i] * double(n);
    (scaled[i] < 1.0 ? small : large).push_back(i);
  }
  while (!small.empty() && !large.empty()) {
    const size_t s = small.back(), l = large.back();
    small.pop_back();
    large.pop_back();
    bins_[s].keep = static_cast<float>(scaled[s]);
    bins_[s].alias = static_cast<int>(l);
    scaled[l] -= 1.0 - scaled[s];
    (scaled[l] < 1.0 ? small : large).push_back(l);
  }
  // What is left is 1 up to rounding: kept whole. A zero-weight bin cannot be left (its
  // deficit of 1 would need as much rounding), but is sent to a drawable bin all the same.
  for (const std::vector<size_t>* rest : {&small, &large})
    for (size_t i : *rest) bins_[i] = {p[i] > 0.0 ? 1.0f : 0.0f, static_cast<int>(i), bins_[i].pmf, 0.0f};
  const int fallback = static_cast<int>(std::max_element(p.begin(), p.end()) - p.begin());
  for (Bin& b : bins_) {
    if (b.keep <= 0.0f && p[size_t(b.alias)] <= 0.0) b.alias = fallback;
    b.alias_pmf = bins_[size_t(b.alias)].pmf;
  }
}

int AliasTable::bin_of(float u_bin) const {
  return std::clamp(static_cast<int>(u_bin * static_cast<float>(bins_.size())), 0, size() - 1);
}

int AliasTable::prefetch(float u_bin) const {
  if (empty()) return -1;
  const int i = bin_of(u_bin);
  __builtin_prefetch(&bins_[size_t(i)]);
  return i;
}

int AliasTable::sample(float u_bin, float u_keep, float* pmf, float* remapped) const {
  if (empty()) {
    if (pmf) *pmf = 0.0f;
    return -1;
  }
  const int i = bin_of(u_bin);
  const float frac = std::clamp(u_keep, 0.0f, kOneMinusEpsilon);
  const Bin& b = bins_[size_t(i)];
  if (frac < b.keep) {
    if (pmf) *pmf = b.pmf;
    if (remapped) *remapped = std::min(frac / b.keep, kOneMinusEpsilon);
    return i;
  }
  if (pmf) *pmf = b.alias_pmf;
  if (remapped) *remapped = std::min((frac - b.keep) / (1.0f - b.keep), kOneMinusEpsilon);
  return b.alias;
}

float AliasTable::pmf(int index) const {
  if (empty() || index < 0 || index >= size()) return 0.0f;
  return bins_[size_t(index)].pmf;
}

}  // namespace phyir::render
