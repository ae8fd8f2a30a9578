#include "symbolic/primitives.h"

#include <sstream>

#include "common/errors.h"

namespace delmesh {

namespace {

using GiNaC::ex;
using GiNaC::symbol;

//! Three fresh symbols name0, name1, name2: a vector parameter of a primitive.
std::array<symbol, 3> vector_symbol(const std::string& name) {
  return {symbol(name + "0"), symbol(name + "1"), symbol(name + "2")};
}

void append(std::vector<symbol>& to, const std::array<symbol, 3>& v) { to.insert(to.end(), v.begin(), v.end()); }

template <class A, class B>
ex dot(const A& a, const B& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

std::array<ex, 3> cross(const std::array<ex, 3>& a, const std::array<ex, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

//! The substitution x, y, z ↦ world point.
GiNaC::lst world_substitution(const std::array<ex, 3>& w) {
  return GiNaC::lst{coordinate_x() == w[0], coordinate_y() == w[1], coordinate_z() == w[2]};
}

std::array<ex, 3> substitute(const std::array<ex, 3>& v, const GiNaC::lst& s) {
  return {v[0].subs(s), v[1].subs(s), v[2].subs(s)};
}

std::array<ex, 3> as_ex(const std::array<symbol, 3>& v) { return {v[0], v[1], v[2]}; }

//! Fills the exact Jacobian ∂equations_i/∂unknowns_j.
void derive_jacobian(PrimitiveSystem& system) {
  const std::size_t m = system.equations.size(), n = system.unknowns.size();
  system.jacobian = GiNaC::matrix(static_cast<unsigned>(m), static_cast<unsigned>(n));
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < n; ++j)
      system.jacobian(static_cast<unsigned>(i), static_cast<unsigned>(j)) = system.equations[i].diff(system.unknowns[j]);
}

//! Unknowns x, y, z themselves (the 3 × 3 systems).
void use_world_unknowns(PrimitiveSystem& system) {
  system.unknowns = {coordinate_x(), coordinate_y(), coordinate_z()};
  system.world_point = {coordinate_x(), coordinate_y(), coordinate_z()};
}

//! A plane system: unknowns (u, v), parameters o, a, b first, world point o + u a + v b.
//! Returns E and ∇E restricted to the plane.
struct PlaneFrame {
  symbol u{"u"}, v{"v"};
  std::array<symbol, 3> o = vector_symbol("o"), a = vector_symbol("a"), b = vector_symbol("b");
  ex E;
  std::array<ex, 3> gradient;
};
PlaneFrame use_plane(PrimitiveSystem& system, const Surface& surface) {
  PlaneFrame f;
  system.unknowns = {f.u, f.v};
  append(system.parameters, f.o);
  append(system.parameters, f.a);
  append(system.parameters, f.b);
  for (int i = 0; i < 3; ++i) system.world_point[i] = f.o[i] + f.u * f.a[i] + f.v * f.b[i];
  const GiNaC::lst s = world_substitution(system.world_point);
  f.E = surface.E().subs(s);
  f.gradient = substitute(surface.gradient(), s);
  return f;
}

}  // namespace

PrimitiveSystem surface_critical_system(const Surface& surface) {
  PrimitiveSystem system;
  system.name = "surface_critical";
  use_world_unknowns(system);
  const auto a = vector_symbol("a"), b = vector_symbol("b");
  append(system.parameters, a);
  append(system.parameters, b);
  system.equations = {surface.E(), dot(surface.gradient(), a), dot(surface.gradient(), b)};
  derive_jacobian(system);
  return system;
}

PrimitiveSystem surface_line_system(const Surface& surface) {
  PrimitiveSystem system;
  system.name = "surface_line";
  const symbol t("t");
  const auto p = vector_symbol("p"), v = vector_symbol("v");
  system.unknowns = {t};
  append(system.parameters, p);
  append(system.parameters, v);
  for (int i = 0; i < 3; ++i) system.world_point[i] = p[i] + t * v[i];
  system.equations = {surface.E().subs(world_substitution(system.world_point))};
  derive_jacobian(system);
  return system;
}

PrimitiveSystem surface_plane_contact_system(const Surface& surface) {
  PrimitiveSystem system;
  system.name = "surface_plane_contact";
  const PlaneFrame f = use_plane(system, surface);
  system.equations = {f.E, dot(f.gradient, f.a), dot(f.gradient, f.b)};
  derive_jacobian(system);
  return system;
}

PrimitiveSystem curve_critical_system(const Surface& surface) {
  PrimitiveSystem system;
  system.name = "curve_critical";
  const PlaneFrame f = use_plane(system, surface);
  system.equations = {f.E, dot(f.gradient, f.b)};
  derive_jacobian(system);
  return system;
}

PrimitiveSystem silhouette_plane_system(const Surface& surface) {
  PrimitiveSystem system;
  system.name = "silhouette_plane";
  const PlaneFrame f = use_plane(system, surface);
  const auto d = vector_symbol("d");
  append(system.parameters, d);
  system.equations = {f.E, dot(f.gradient, d)};
  derive_jacobian(system);
  return system;
}

PrimitiveSystem silhouette_critical_system(const Surface& surface) {
  PrimitiveSystem system;
  system.name = "silhouette_critical";
  use_world_unknowns(system);
  const auto d = vector_symbol("d"), e = vector_symbol("e");  // e stands for d'
  append(system.parameters, d);
  append(system.parameters, e);
  const GiNaC::matrix& H = surface.hessian();
  // G = ⟨∇E, d⟩ and ∇G = H d (H symmetric).
  std::array<ex, 3> grad_G;
  for (unsigned i = 0; i < 3; ++i) grad_G[i] = H(i, 0) * d[0] + H(i, 1) * d[1] + H(i, 2) * d[2];
  system.equations = {surface.E(), dot(surface.gradient(), d), dot(cross(grad_G, surface.gradient()), as_ex(e))};
  derive_jacobian(system);
  return system;
}

const std::vector<PrimitiveInfo>& primitive_registry() {
  static const std::vector<PrimitiveInfo> registry = {
      {"surface_critical", surface_critical_system,
       "critical points of Σ in direction d: E = <∇E,a> = <∇E,b> = 0; unknowns x,y,z; params a(3), b(3) ⟂ d"},
      {"surface_line", surface_line_system, "Σ ∩ line p + t v: E(p + t v) = 0; unknown t; params p(3), v(3)"},
      {"surface_plane_contact", surface_plane_contact_system,
       "tangential contacts of Σ with plane o + u a + v b: E = ∂uE = ∂vE = 0; unknowns u,v; params o, a, b"},
      {"curve_critical", curve_critical_system,
       "critical points of Σ ∩ plane in direction a: E = <∇E,b> = 0; unknowns u,v; params o, a, b"},
      {"silhouette_plane", silhouette_plane_system,
       "silhouette J_d ∩ plane: E = <∇E,d> = 0; unknowns u,v; params o, a, b, d(3)"},
      {"silhouette_critical", silhouette_critical_system,
       "critical points of J_d in direction d': E = G = <∇G × ∇E, d'> = 0, G = <∇E,d>; unknowns x,y,z; "
       "params d(3), d'(3)"},
  };
  return registry;
}

PrimitiveSystem build_primitive(const std::string& name, const Surface& surface) {
  std::ostringstream known;
  for (const PrimitiveInfo& info : primitive_registry()) {
    if (info.name == name) return info.build(surface);
    known << (known.tellp() > 0 ? ", " : "") << info.name;
  }
  throw InvalidInput("unknown primitive '" + name + "'; known primitives: " + known.str());
}

}  // namespace delmesh
