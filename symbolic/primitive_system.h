#pragma once
//! \file primitive_system.h
//! A numerical primitive of §5.2 as a polynomial (or analytic) system, derived once per surface
//! with the per-query quantities (line point and direction, plane frame, directions) left as
//! symbolic parameters, and with dimension reduced (a line → t; a plane → (u, v)).

#include <array>
#include <string>
#include <vector>

#include <ginac/ginac.h>

namespace delmesh {

struct PrimitiveSystem {
  std::string name;                   //!< e.g. "surface_line"
  std::vector<GiNaC::symbol> unknowns;   //!< t | u, v | x, y, z
  std::vector<GiNaC::symbol> parameters; //!< documented per primitive in primitives.h
  std::vector<GiNaC::ex> equations;      //!< m equations, m ≥ n = unknowns.size()
  GiNaC::matrix jacobian{1, 1};          //!< m × n, ∂equations_i / ∂unknowns_j, exact
  //! World point (x, y, z) as expressions in unknowns and parameters, e.g. o + u a + v b.
  std::array<GiNaC::ex, 3> world_point;

  std::size_t n_unknowns() const { return unknowns.size(); }
  std::size_t n_parameters() const { return parameters.size(); }
  std::size_t n_equations() const { return equations.size(); }
  bool is_square() const { return equations.size() == unknowns.size(); }
};

}  // namespace delmesh
