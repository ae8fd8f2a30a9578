#include "solvers/query_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "common/errors.h"
#include "common/tolerances.h"

namespace delmesh {

namespace {

double dot(const Vec3& p, const Vec3& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }

Vec3 cross(const Vec3& p, const Vec3& q) {
  return {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
}

double cross2(const std::array<double, 2>& o, const std::array<double, 2>& p,
              const std::array<double, 2>& q) {
  return (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0]);
}

// The shortest decimal text that reads back as exactly x.
std::string shortest(double x) {
  if (x == 0) return "0";
  char buffer[64];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (std::strtod(buffer, nullptr) == x) return buffer;
  }
  return buffer;
}

// The largest |d_i|; InvalidInput if d is zero or not finite (the text is made only then: this
// runs on hot paths).
double direction_size(const Vec3& d) {
  auto text = [&] { return "direction (" + shortest(d[0]) + ", " + shortest(d[1]) + ", " + shortest(d[2]) + ")"; };
  double largest = 0;
  for (double c : d) {
    if (!std::isfinite(c)) throw InvalidInput(text() + " is not finite");
    largest = std::max(largest, std::abs(c));
  }
  if (largest == 0) throw InvalidInput(text() + " is zero");
  return largest;
}

// d scaled by a power of two (exact) so that its largest component lies in [1, 2): then |d|²
// neither overflows nor underflows.  InvalidInput if d is zero or not finite.
Vec3 scaled_direction(const Vec3& d) {
  const int e = std::ilogb(direction_size(d));
  return {std::scalbn(d[0], -e), std::scalbn(d[1], -e), std::scalbn(d[2], -e)};
}

}  // namespace

Vec3 unit_vector(const Vec3& d) {
  // The plain quotient where |d|² is a normal double; otherwise on d scaled by a power of two
  // (a direction of length 1e308 or 1e-320 has the same unit vector).
  const double norm_squared = dot(d, d);
  if (std::isfinite(norm_squared) && norm_squared >= std::numeric_limits<double>::min()) {
    const double norm = std::sqrt(norm_squared);
    return {d[0] / norm, d[1] / norm, d[2] / norm};
  }
  const Vec3 s = scaled_direction(d);
  const double norm = std::sqrt(dot(s, s));
  return {s[0] / norm, s[1] / norm, s[2] / norm};
}

OrthonormalFrame orthonormal_frame(const Vec3& direction) {
  OrthonormalFrame frame;
  frame.d = unit_vector(direction);
  int k = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(frame.d[i]) < std::abs(frame.d[k])) k = i;
  }
  Vec3 axis{0, 0, 0};
  axis[k] = 1;
  frame.a = unit_vector(cross(axis, frame.d));
  frame.b = cross(frame.d, frame.a);
  return frame;
}

std::optional<std::array<double, 2>> clip_line_to_box(const Vec3& p, const Vec3& v, const Box3& box) {
  (void)direction_size(v);  // throws if v is zero or not finite
  double t0 = -std::numeric_limits<double>::infinity();
  double t1 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (v[i] == 0.0) {
      if (p[i] < box.lo[i] || p[i] > box.hi[i]) return std::nullopt;
      continue;
    }
    double a = (box.lo[i] - p[i]) / v[i];
    double b = (box.hi[i] - p[i]) / v[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  if (!(t0 < t1)) return std::nullopt;
  return std::array<double, 2>{t0, t1};
}

std::optional<PlaneSection> plane_box_section(const Vec3& origin, const Vec3& normal, const Box3& box) {
  return plane_box_section(origin, orthonormal_frame(normal), box);
}

std::vector<Vec3> plane_box_edge_points(const Vec3& origin, const Vec3& normal, const Box3& box) {
  const double offset = dot(normal, origin);
  // The 8 corners, indexed by bits (x, y, z) = (bit 0, bit 1, bit 2).
  std::array<Vec3, 8> corner;
  std::array<double, 8> side;
  for (int c = 0; c < 8; ++c) {
    for (int i = 0; i < 3; ++i) corner[c][i] = (c >> i) & 1 ? box.hi[i] : box.lo[i];
    side[c] = dot(normal, corner[c]) - offset;
  }
  // Points of the plane on the 12 edges (corner pairs differing in one bit).
  std::vector<Vec3> points;
  points.reserve(12);  // at most one point per edge, or a corner instead of its three edges
  for (int c = 0; c < 8; ++c) {
    if (side[c] == 0.0) points.push_back(corner[c]);
    for (int i = 0; i < 3; ++i) {
      const int e = c | (1 << i);
      if (e == c) continue;
      if ((side[c] < 0 && side[e] > 0) || (side[c] > 0 && side[e] < 0)) {
        const double s = side[c] / (side[c] - side[e]);
        Vec3 x;
        for (int j = 0; j < 3; ++j) x[j] = corner[c][j] + s * (corner[e][j] - corner[c][j]);
        points.push_back(x);
      }
    }
  }
  return points;
}

std::optional<PlaneSection> plane_box_section(const Vec3& origin, const OrthonormalFrame& frame,
                                              const Box3& box) {
  PlaneSection section;
  section.origin = origin;
  section.frame = frame;
  const std::vector<Vec3> corners = plane_box_edge_points(origin, section.frame.d, box);
  std::vector<std::array<double, 2>> points;
  points.reserve(corners.size());
  for (const Vec3& x : corners) {
    const Vec3 w{x[0] - origin[0], x[1] - origin[1], x[2] - origin[2]};
    points.push_back({dot(w, section.frame.a), dot(w, section.frame.b)});
  }
  if (points.size() < 3) return std::nullopt;

  // Convex hull (Andrew's monotone chain), counter-clockwise, collinear points dropped.
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return std::nullopt;
  std::vector<std::array<double, 2>> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  if (hull.size() < 3) return std::nullopt;
  double area = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& p = hull[i];
    const auto& q = hull[(i + 1) % hull.size()];
    area += p[0] * q[1] - p[1] * q[0];
  }
  // A section thinner than rounding noise of the box's size is an edge or a corner, not a polygon.
  const double scale = box.diagonal();
  if (!(area / 2 > tolerances::degenerate_section_relative_area * scale * scale)) return std::nullopt;
  section.polygon = std::move(hull);
  return section;
}

Domain polygon_domain(const std::vector<std::array<double, 2>>& polygon) {
  if (polygon.size() < 3) {
    throw PreconditionViolation("a polygon domain needs at least 3 vertices, got " + std::to_string(polygon.size()));
  }
  std::array<double, 2> lo = polygon.front(), hi = polygon.front();
  for (const auto& w : polygon) {
    for (int i = 0; i < 2; ++i) {
      lo[i] = std::min(lo[i], w[i]);
      hi[i] = std::max(hi[i], w[i]);
    }
  }
  Domain domain = Domain::from_box({{lo[0], hi[0]}, {lo[1], hi[1]}});
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const auto& p = polygon[i];
    const auto& q = polygon[(i + 1) % polygon.size()];
    // Counter-clockwise: the interior is on the left, the outward normal is (dy, -dx).
    HalfSpace h;
    h.normal = {q[1] - p[1], p[0] - q[0]};
    h.offset = h.normal[0] * p[0] + h.normal[1] * p[1];
    domain.half_spaces.push_back(std::move(h));
  }
  return domain;
}

Domain box_domain(const Box3& box) {
  return Domain::from_box({{box.lo[0], box.hi[0]}, {box.lo[1], box.hi[1]}, {box.lo[2], box.hi[2]}});
}

}  // namespace delmesh
