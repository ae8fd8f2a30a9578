#pragma once
//! \file domain.h
//! Solver domains: an axis-aligned box in the unknowns intersected with half-spaces, i.e. a convex
//! polytope (a Voronoi facet polygon in plane coordinates (u, v); a clipped Voronoi cell in x, y, z).

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <vector>

#include "common/enum_names.h"
#include "solvers/solve_result.h"
#include "symbolic/scalar_types.h"

namespace delmesh {

//! The normal of a half-space: at most `capacity` entries (the dimension of the geometric
//! domains: facets in two unknowns, cells in three), held in place rather than on the heap,
//! since a Voronoi cell's domain has one half-space per neighbour and cells are built at every
//! insertion.  Constructing one with more entries throws PreconditionViolation.
class HalfSpaceNormal {
 public:
  static constexpr std::size_t capacity = 3;
  HalfSpaceNormal() = default;
  HalfSpaceNormal(std::initializer_list<double> entries);
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const double* data() const { return entries_.data(); }
  const double* begin() const { return entries_.data(); }
  const double* end() const { return entries_.data() + size_; }
  double operator[](std::size_t i) const { return entries_[i]; }
  double& operator[](std::size_t i) { return entries_[i]; }

 private:
  std::array<double, capacity> entries_{};
  std::size_t size_ = 0;
};

//! {u : ⟨normal, u⟩ ≤ offset} in the solver's unknowns.
struct HalfSpace {
  HalfSpaceNormal normal;
  double offset = 0;
};

//! box ∩ ⋂ half_spaces.  Roots are searched in the box and then classified as inside or outside
//! the polytope (box faces included); classification is decided exactly or the root's box is
//! refined, and a root that cannot be separated from a face is reported as boundary_root.
struct Domain {
  SolverBox box;
  std::vector<HalfSpace> half_spaces;
  std::size_t dimension() const { return box.bounds.size(); }
  //! The box [lo0,hi0]×…; no half-spaces.
  static Domain from_box(std::vector<std::array<double, 2>> bounds);
  //! Throws PreconditionViolation unless dimension() ≥ 1, every side satisfies −∞ < lo < hi < ∞,
  //! and every half-space has dimension() finite normal entries, not all zero, and a finite offset.
  void validate() const;
  //! The widest side of the box, max_i (hi_i − lo_i): the scale of relative widths.
  double scale() const;
};

//! Where a box of the unknowns lies relative to the closed polytope P = box ∩ half-spaces.
enum class DomainSide {
  inside,   //!< every point of the box is strictly inside every face of P
  outside,  //!< every point of the box is strictly outside one face of P (box ∩ P = ∅)
  boundary  //!< neither could be proved (the box meets or nearly meets a face)
};
constexpr auto enum_names(DomainSide) {
  return name_table<DomainSide>("DomainSide", {{DomainSide::inside, "inside"}, {DomainSide::outside, "outside"},
                                               {DomainSide::boundary, "boundary"}});
}
inline std::ostream& operator<<(std::ostream& out, DomainSide side) { return write_enum(out, side); }

//! Classifies the interval box `box` (domain.dimension() entries) against the faces of the domain:
//! the 2n box faces u_i = lo_i, u_i = hi_i and the hyperplanes ⟨normal, u⟩ = offset, each side
//! evaluated in interval arithmetic.  Precondition: a RoundingGuard is alive.  Rigorous: inside
//! and outside are proofs; boundary means undecided.
DomainSide classify(const Domain& domain, const Interval* box);

//! Half-spaces whose test classify(domain, box, active) can skip: bit i stands for
//! domain.half_spaces[i], i < this; half-spaces beyond it are tested every time.
inline constexpr std::size_t classify_mask_bits = 64;

//! classify() for a sub-box of a box already classified: bit i of `active` clear means that
//! half-space i strictly contains an enclosing box, hence this one (a half-space that strictly
//! contains a box strictly contains each of its sub-boxes), and it is not evaluated again.  The
//! bits of the half-spaces proved to contain `box` strictly are cleared, for its sub-boxes.
//! Start a subdivision with all_half_spaces_active(domain).  The answer is classify()'s.
DomainSide classify(const Domain& domain, const Interval* box, std::uint64_t& active);
//! The mask of classify() with every half-space to be tested.
std::uint64_t all_half_spaces_active(const Domain& domain);

}  // namespace delmesh
