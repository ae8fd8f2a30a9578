#pragma once
//! \file catalog.h
//! The catalog of named test surfaces: equation, a box containing Σ strictly inside, the number of
//! components and the genus of each, and (where known in closed form) the local feature size.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "symbolic/surface.h"

namespace delmesh {

//! Every entry is smooth (∇E ≠ 0 on Σ, certified by interval subdivision in the tests), has
//! E > 0 outside (on the unbounded side, in particular on the whole boundary of its box, also
//! certified) and E < 0 inside, and its genus per component was checked by two independent
//! computations (Morse count of a generic height function; cubical complex of {E < 0} on a grid).
struct CatalogEntry {
  std::string name;
  std::string equation;                 //!< E(x, y, z) as text, parsed by Surface::parse
  Box3 box;                             //!< Σ ⊂ interior(box)
  int components = 1;
  std::vector<int> genus_per_component; //!< sorted ascending
  std::string description;
  //! lfs(p) for p ∈ Σ when known analytically (distance from p to the medial axis of Σ, which is
  //! known in closed form for sphere, ellipsoid, torus, thin_handle, near_sheets), else empty.
  //! Precondition: p ∈ Σ (the value at other points is not meaningful).
  std::function<double(const std::array<double, 3>&)> local_feature_size;

  Surface surface() const { return Surface::parse(equation); }
};

//! All catalog entries, in a fixed order.
const std::vector<CatalogEntry>& catalog();
//! The entry called name; throws InvalidInput listing the known names if there is none.
const CatalogEntry& catalog_entry(const std::string& name);

}  // namespace delmesh
