#include "symbolic/primitive_system.h"

namespace delmesh {

void derive_jacobian(PrimitiveSystem& system) {
  const std::size_t m = system.equations.size(), n = system.unknowns.size();
  system.jacobian = GiNaC::matrix(static_cast<unsigned>(m), static_cast<unsigned>(n));
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < n; ++j)
      system.jacobian(static_cast<unsigned>(i), static_cast<unsigned>(j)) = system.equations[i].diff(system.unknowns[j]);
}

ExVec3 add_vector_parameter(PrimitiveSystem& system, const std::string& name) {
  ExVec3 v;
  for (int i = 0; i < 3; ++i) {
    const GiNaC::symbol s(name + std::to_string(i));
    system.parameters.push_back(s);
    v[i] = s;
  }
  return v;
}

void use_world_unknowns(PrimitiveSystem& system) {
  system.unknowns = {coordinate_x(), coordinate_y(), coordinate_z()};
  system.world_point = {coordinate_x(), coordinate_y(), coordinate_z()};
}

PlaneRestriction use_plane(PrimitiveSystem& system, const Surface& surface) {
  const GiNaC::symbol u("u"), v("v");
  system.unknowns = {u, v};
  PlaneRestriction plane;
  plane.o = add_vector_parameter(system, "o");
  plane.a = add_vector_parameter(system, "a");
  plane.b = add_vector_parameter(system, "b");
  for (int i = 0; i < 3; ++i) system.world_point[i] = plane.o[i] + u * plane.a[i] + v * plane.b[i];
  plane.E = at_world_point(system, surface.E());
  plane.gradient = at_world_point(system, surface.gradient());
  return plane;
}

GiNaC::ex at_world_point(const PrimitiveSystem& system, const GiNaC::ex& e) {
  const GiNaC::lst s{coordinate_x() == system.world_point[0], coordinate_y() == system.world_point[1],
                     coordinate_z() == system.world_point[2]};
  return e.subs(s);
}

ExVec3 at_world_point(const PrimitiveSystem& system, const ExVec3& v) {
  return {at_world_point(system, v[0]), at_world_point(system, v[1]), at_world_point(system, v[2])};
}

GiNaC::ex dot(const ExVec3& p, const ExVec3& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }

ExVec3 cross(const ExVec3& p, const ExVec3& q) {
  return {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
}

ExVec3 from_point(const ExVec3& c) {
  return {coordinate_x() - c[0], coordinate_y() - c[1], coordinate_z() - c[2]};
}

}  // namespace delmesh
