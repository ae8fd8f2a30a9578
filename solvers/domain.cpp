#include "solvers/domain.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.h"
#include "solvers/detail/interval_box.h"

namespace delmesh {

Domain Domain::from_box(std::vector<std::array<double, 2>> bounds) {
  Domain domain;
  domain.box.bounds = std::move(bounds);
  domain.validate();
  return domain;
}

HalfSpaceNormal::HalfSpaceNormal(std::initializer_list<double> entries) : size_(entries.size()) {
  if (size_ > capacity)
    throw PreconditionViolation("HalfSpaceNormal: " + std::to_string(size_) + " entries, at most " +
                                std::to_string(capacity) + " are held");
  std::copy(entries.begin(), entries.end(), entries_.begin());
}

void Domain::validate() const {
  if (box.bounds.empty()) throw PreconditionViolation("solver domain: the box has no sides");
  for (std::size_t i = 0; i < box.bounds.size(); ++i) {
    const auto& side = box.bounds[i];
    if (!std::isfinite(side[0]) || !std::isfinite(side[1]) || !(side[0] < side[1]))
      throw PreconditionViolation("solver domain: side " + std::to_string(i) + " is not a finite interval lo < hi");
  }
  for (std::size_t k = 0; k < half_spaces.size(); ++k) {
    const HalfSpace& h = half_spaces[k];
    if (h.normal.size() != box.bounds.size())
      throw PreconditionViolation("solver domain: half-space " + std::to_string(k) + " has a normal of dimension " +
                                  std::to_string(h.normal.size()) + ", the box has " +
                                  std::to_string(box.bounds.size()));
    bool nonzero = false;
    for (double c : h.normal) {
      if (!std::isfinite(c))
        throw PreconditionViolation("solver domain: half-space " + std::to_string(k) + " is not finite");
      nonzero = nonzero || c != 0;
    }
    if (!nonzero || !std::isfinite(h.offset))
      throw PreconditionViolation("solver domain: half-space " + std::to_string(k) +
                                  " has a zero normal or infinite offset");
  }
}

double Domain::scale() const {
  double s = 0;
  for (const auto& side : box.bounds) s = std::max(s, side[1] - side[0]);
  return s;
}

DomainSide classify(const Domain& domain, const Interval* box) {
  std::uint64_t active = all_half_spaces_active(domain);
  return classify(domain, box, active);
}

std::uint64_t all_half_spaces_active(const Domain& domain) {
  const std::size_t k = std::min(domain.half_spaces.size(), classify_mask_bits);
  return k == classify_mask_bits ? ~std::uint64_t{0} : (std::uint64_t{1} << k) - 1;
}

namespace {

// classify() in dimension N (0: the domain's, read at run time): the same tests in the same
// order; a fixed N lets the compiler unroll the sums of half_space_excess().  The half-spaces
// under the mask are visited by their set bits.
template <std::size_t N>
DomainSide classify_in(const Domain& domain, const Interval* box, std::uint64_t& active) {
  const std::size_t n = N ? N : domain.dimension();
  bool inside = true;
  for (std::size_t i = 0; i < n; ++i) {
    const double lo = domain.box.bounds[i][0], hi = domain.box.bounds[i][1];
    if (box[i].inf() > hi || box[i].sup() < lo) return DomainSide::outside;
    if (!(box[i].inf() > lo && box[i].sup() < hi)) inside = false;
  }
  const std::size_t count = domain.half_spaces.size();
  // -1: outside; otherwise whether the half-space strictly contains the box.
  auto test = [&](std::size_t i) {
    const HalfSpace& h = domain.half_spaces[i];
    const Interval s = detail::half_space_excess(h.normal.data(), h.offset, box, n);
    if (s.inf() > 0) return -1;
    return s.sup() < 0 ? 1 : 0;
  };
  std::uint64_t contained = 0;
  const std::uint64_t under_mask = count >= classify_mask_bits ? ~std::uint64_t{0}
                                                                : (std::uint64_t{1} << count) - 1;
  for (std::uint64_t bits = active & under_mask; bits != 0; bits &= bits - 1) {
    const std::size_t i = static_cast<std::size_t>(__builtin_ctzll(bits));
    const int t = test(i);
    if (t < 0) return DomainSide::outside;
    if (t > 0)
      contained |= std::uint64_t{1} << i;
    else
      inside = false;
  }
  for (std::size_t i = classify_mask_bits; i < count; ++i) {
    const int t = test(i);
    if (t < 0) return DomainSide::outside;
    if (t == 0) inside = false;
  }
  active &= ~contained;
  return inside ? DomainSide::inside : DomainSide::boundary;
}

}  // namespace

DomainSide classify(const Domain& domain, const Interval* box, std::uint64_t& active) {
  switch (domain.dimension()) {
    case 2: return classify_in<2>(domain, box, active);
    case 3: return classify_in<3>(domain, box, active);
    default: return classify_in<0>(domain, box, active);
  }
}

}  // namespace delmesh
