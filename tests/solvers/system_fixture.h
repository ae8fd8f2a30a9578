#pragma once
// Small polynomial systems for the solver tests: make_system() builds a PrimitiveSystem from
// equations in the catalog's coordinate symbols, with its Jacobian and the unknowns (zero-padded)
// as its world point.
#include <vector>

#include <ginac/ginac.h>

#include "symbolic/catalog.h"
#include "symbolic/primitive_system.h"

namespace delmesh::test {

inline const GiNaC::symbol& X() { return coordinate_x(); }
inline const GiNaC::symbol& Y() { return coordinate_y(); }

inline PrimitiveSystem make_system(std::vector<GiNaC::ex> equations, std::vector<GiNaC::symbol> unknowns) {
  PrimitiveSystem s;
  s.name = "test";
  s.unknowns = std::move(unknowns);
  s.equations = std::move(equations);
  s.jacobian = GiNaC::matrix(s.equations.size(), s.unknowns.size());
  for (std::size_t i = 0; i < s.equations.size(); ++i)
    for (std::size_t j = 0; j < s.unknowns.size(); ++j) s.jacobian(i, j) = s.equations[i].diff(s.unknowns[j]);
  for (std::size_t k = 0; k < 3; ++k) s.world_point[k] = k < s.unknowns.size() ? GiNaC::ex(s.unknowns[k]) : GiNaC::ex(0);
  return s;
}

}  // namespace delmesh::test
