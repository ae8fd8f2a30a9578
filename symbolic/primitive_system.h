#pragma once
//! \file primitive_system.h
//! A numerical primitive of §5.2 as a polynomial (or analytic) system, derived once per surface
//! with the per-query quantities (line point and direction, plane frame, directions) left as
//! symbolic parameters, and with dimension reduced (a line → t; a plane → (u, v)).
//!
//! A primitive's builder (solvers/primitive_registry.h) states the unknowns, the parameters, the
//! equations, the world point and optionally side conditions; derive_jacobian() adds the exact
//! Jacobian (the registry calls it on every builder's result).  The helpers below are the
//! vocabulary builders use: vector parameters, the world unknowns (x, y, z), a plane
//! o + u a + v b, dot and cross products of expression vectors.

#include <array>
#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "symbolic/surface.h"

namespace delmesh {

struct PrimitiveSystem {
  std::string name;                   //!< e.g. "surface_line"
  std::vector<GiNaC::symbol> unknowns;   //!< t | u, v | x, y, z
  std::vector<GiNaC::symbol> parameters; //!< documented per primitive in its registry row
  std::vector<GiNaC::ex> equations;      //!< m equations, m ≥ n = unknowns.size()
  GiNaC::matrix jacobian{1, 1};          //!< m × n, ∂equations_i / ∂unknowns_j, exact
  //! World point (x, y, z) as expressions in unknowns and parameters, e.g. o + u a + v b.
  std::array<GiNaC::ex, 3> world_point;
  //! Expressions in the unknowns and parameters that vanish at every root the primitive stands
  //! for, but not at every root of the equations (the root filter): a certified root on whose
  //! box one of them is proved non-zero is spurious and dropped (drop_spurious_roots() in
  //! solvers/primitive_query.h).  Empty for most primitives.
  std::vector<GiNaC::ex> side_conditions;

  std::size_t n_unknowns() const { return unknowns.size(); }
  std::size_t n_parameters() const { return parameters.size(); }
  std::size_t n_equations() const { return equations.size(); }
  bool is_square() const { return equations.size() == unknowns.size(); }
};

//! Sets system.jacobian to the exact m × n matrix ∂equations_i/∂unknowns_j.
void derive_jacobian(PrimitiveSystem& system);

using ExVec3 = std::array<GiNaC::ex, 3>;

//! Appends three fresh parameter symbols name0, name1, name2 (a vector parameter) to
//! system.parameters and returns them as expressions.
ExVec3 add_vector_parameter(PrimitiveSystem& system, const std::string& name);

//! Makes the coordinates x, y, z of surface.h the unknowns and the world point (a 3 × 3 system).
void use_world_unknowns(PrimitiveSystem& system);

//! A plane {o + u a + v b}: E and ∇E restricted to it (the world point substituted).
struct PlaneRestriction {
  GiNaC::ex E;
  ExVec3 gradient;
  ExVec3 o, a, b;  //!< the plane's parameters
};
//! Makes (u, v) the unknowns, appends the parameters o, a, b (o0 … b2) and sets the world point
//! o + u a + v b; returns E and ∇E at that point.
PlaneRestriction use_plane(PrimitiveSystem& system, const Surface& surface);

//! e with x, y, z replaced by the system's world point.
GiNaC::ex at_world_point(const PrimitiveSystem& system, const GiNaC::ex& e);
//! The same for each component of v.
ExVec3 at_world_point(const PrimitiveSystem& system, const ExVec3& v);

//! ⟨p, q⟩.
GiNaC::ex dot(const ExVec3& p, const ExVec3& q);
//! p × q.
ExVec3 cross(const ExVec3& p, const ExVec3& q);
//! (x, y, z) − c, the vector from c to the world coordinates x, y, z.
ExVec3 from_point(const ExVec3& c);

}  // namespace delmesh
