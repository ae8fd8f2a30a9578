#include "meshing/input_validation.h"

#include <cmath>
#include <sstream>
#include <vector>

#include "common/errors.h"
#include "common/tolerances.h"
#include "solvers/subdivision_solver.h"
#include "symbolic/compiled_system.h"

namespace delmesh {

namespace {

CompiledSystem gradient_system(const Surface& surface) {
  const auto& g = surface.gradient();
  return CompiledSystem(std::vector<GiNaC::ex>{surface.E(), g[0], g[1], g[2]},
                        std::vector<GiNaC::symbol>{coordinate_x(), coordinate_y(), coordinate_z()},
                        std::vector<GiNaC::symbol>{});
}

std::string face_name(int axis, bool upper, const Box3& box) {
  std::ostringstream s;
  s << "xyz"[axis] << " = " << (upper ? box.hi[axis] : box.lo[axis]);
  return s.str();
}

}  // namespace

void validate_box_faces(const Surface& surface, const Box3& box) {
  const CompiledSystem system = gradient_system(surface);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const double fixed = side ? box.hi[axis] : box.lo[axis];
      const int i = (axis + 1) % 3, j = (axis + 2) % 3;
      struct Rect { double u0, u1, v0, v1; int depth; };
      std::vector<Rect> stack{{box.lo[i], box.hi[i], box.lo[j], box.hi[j], 0}};
      bool positive = false, negative = false, undecided = false;
      std::size_t budget = tolerances::mesher_box_budget_global;
      while (!stack.empty()) {
        const Rect r = stack.back();
        stack.pop_back();
        // E at the rectangle's centre (double) records the signs met on the face.
        std::array<double, 3> c{};
        c[axis] = fixed;
        c[i] = 0.5 * (r.u0 + r.u1);
        c[j] = 0.5 * (r.v0 + r.v1);
        double values[4];
        system.values<double>(c.data(), nullptr, values);
        if (values[0] > 0) positive = true;
        if (values[0] < 0) negative = true;
        if (values[0] == 0 || (positive && negative)) {
          throw InvalidInput("the surface meets the boundary of the box on the face " +
                             face_name(axis, side, box) + "; enlarge the box so that it contains Σ strictly inside");
        }
        bool excluded = false;
        {
          RoundingGuard guard;
          std::array<Interval, 3> x;
          x[axis] = Interval(fixed);
          x[i] = Interval(r.u0, r.u1);
          x[j] = Interval(r.v0, r.v1);
          Interval out[4];
          system.values<Interval>(x.data(), nullptr, out);
          excluded = out[0].inf() > 0 || out[0].sup() < 0;
        }
        if (excluded) continue;
        if (r.depth >= tolerances::box_face_max_depth || budget == 0) {
          undecided = true;
          continue;
        }
        --budget;
        const double um = 0.5 * (r.u0 + r.u1), vm = 0.5 * (r.v0 + r.v1);
        stack.push_back({r.u0, um, r.v0, vm, r.depth + 1});
        stack.push_back({um, r.u1, r.v0, vm, r.depth + 1});
        stack.push_back({r.u0, um, vm, r.v1, r.depth + 1});
        stack.push_back({um, r.u1, vm, r.v1, r.depth + 1});
      }
      if (undecided)
        throw InvalidInput("cannot certify that the surface stays away from the face " +
                           face_name(axis, side, box) + " of the box; enlarge the box");
    }
}

void validate_regular(const Surface& surface, const Box3& box) {
  const CompiledSystem system = gradient_system(surface);
  SubdivisionOptions options;
  options.exclusion_mode = true;
  options.box_budget = tolerances::mesher_box_budget_global;
  const Domain domain = Domain::from_box({{box.lo[0], box.hi[0]}, {box.lo[1], box.hi[1]}, {box.lo[2], box.hi[2]}});
  const auto result = solve_subdivision(system, {}, domain, options);
  if (result.undecided.empty()) return;
  const auto& u = result.undecided.front();
  std::ostringstream s;
  if (result.status == SolveStatus::box_limit || result.status == SolveStatus::time_limit) {
    s << "cannot certify that the gradient of E is non-zero on the surface (budget exhausted, " << result.undecided.size()
      << " regions left, first near (" << u.world[0] << ", " << u.world[1] << ", " << u.world[2] << "))";
  } else {
    s << "the surface is singular: the gradient of E vanishes on it near (" << u.world[0] << ", " << u.world[1]
      << ", " << u.world[2] << ")";
  }
  throw InvalidInput(s.str());
}

void validate_input(const Surface& surface, const Box3& box) {
  validate_box_faces(surface, box);
  validate_regular(surface, box);
}

}  // namespace delmesh
