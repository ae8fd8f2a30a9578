//! \file input_mesh_fuzzer.cpp
//! libFuzzer target fuzz_input_mesh: what `delmesh mesh --input-mesh` does with a mesh before
//! meshing it — validate_input_mesh (meshing/inputs/input_mesh.h), then MeshOracle's construction
//! (meshing/inputs/mesh_oracle.h) — on small closed meshes at every scale a double holds, and a few
//! oracle questions whose answers are known for any closed mesh.
//!
//! The input is a compact encoding of a perturbed base shape, so that most inputs are valid meshes
//! and reach the oracle (a text file would mostly stop at the reader, which the reader targets
//! cover):
//!   byte 0      the base shape (value mod 3: octahedron, icosahedron, the octahedron with each
//!               face split in four and the new vertices pushed out to the unit sphere); bit 2
//!               reverses every face (validation reorients the mesh), bit 3 lists the faces as
//!               quadrilaterals where two triangles share an edge (validation triangulates them)
//!   bytes 1-2   the scale exponent s = (big-endian value mod 2151) − 1075: every vertex is
//!               multiplied by 2^s, so coordinates range from 2^−1075 (subnormal, or zero) to
//!               2^1075 (overflow, which validation refuses)
//!   byte 3      the perturbation amplitude 2^−(value mod 64) / 2, relative to the unit shape
//!   byte 4      the offset exponent relative to the scale, as a signed byte r: the mesh is
//!               translated by 2^(s + r) times
//!   bytes 5-7   the offset's components, signed bytes / 128
//!   then        per vertex, per coordinate, a big-endian signed 16-bit perturbation p: the unit
//!               shape's coordinate plus amplitude · p / 32768
//! Missing bytes count as zero (an exact unit shape, no offset).  Validation may refuse the mesh
//! (InvalidInput: coordinates that overflow, collapse or cross); a valid mesh must then satisfy:
//!  - MeshOracle's construction throws nothing (validate_input_mesh ensures its preconditions);
//!  - the oracle's box is the input's times 2^-k, k its scale exponent, and if k is not 0, the
//!    box's largest side lies in [1, 2) (meshing/inputs/unit_scale.h); the questions below are asked at
//!    that scale;
//!  - the oracle counts the mesh's faces; every vertex lies on Σ (value_sign 0) and the corners of
//!    the domain box outside it (value_sign +1);
//!  - a segment between two points outside the box, through the vertices' centroid, crosses Σ an
//!    even number of times when surface_line decides every point (no undecided region);
//!  - the section by the plane z = centroid's z is a set of closed polylines of three or more
//!    points;
//!  - surface_critical over the whole box finds at least two vertices per component (its highest
//!    and lowest).
//! Any other exception, or a property that fails, is a finding: the target prints it and aborts.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "meshing/inputs/input_mesh.h"
#include "meshing/inputs/mesh_oracle.h"
#include "solvers/domain.h"

namespace {

using delmesh::Point3;

//! A unit shape: vertex coordinates and outward triangles.
struct Shape {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<std::size_t, 3>> triangles;
};

//! Orients every triangle of a shape that is star-shaped about the origin outward.
void orient_outward(Shape& shape) {
  for (auto& t : shape.triangles) {
    const auto& a = shape.vertices[t[0]];
    const auto& b = shape.vertices[t[1]];
    const auto& c = shape.vertices[t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    if (n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2]) < 0)
      std::swap(t[1], t[2]);
  }
}

Shape octahedron() {
  Shape s;
  s.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return s;
}

Shape icosahedron() {
  const double g = (1 + std::sqrt(5.0)) / 2;
  Shape s;
  s.vertices = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  const double r = std::sqrt(1 + g * g);
  for (auto& v : s.vertices)
    for (double& x : v) x /= r;
  orient_outward(s);
  return s;
}

//! The octahedron with each face split into four; the edge midpoints on the unit sphere.
Shape split_octahedron() {
  const Shape base = octahedron();
  Shape s;
  s.vertices = base.vertices;
  auto midpoint = [&](std::size_t a, std::size_t b) {
    std::array<double, 3> m{};
    for (int k = 0; k < 3; ++k) m[k] = (base.vertices[a][k] + base.vertices[b][k]) / 2;
    const double n = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    for (double& x : m) x /= n;
    for (std::size_t i = base.vertices.size(); i < s.vertices.size(); ++i)
      if (s.vertices[i] == m) return i;
    s.vertices.push_back(m);
    return s.vertices.size() - 1;
  };
  for (const auto& t : base.triangles) {
    const std::size_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    s.triangles.push_back({t[0], ab, ca});
    s.triangles.push_back({ab, t[1], bc});
    s.triangles.push_back({ca, bc, t[2]});
    s.triangles.push_back({ab, bc, ca});
  }
  return s;
}

const Shape& shape(int which) {
  static const Shape shapes[3] = {octahedron(), icosahedron(), split_octahedron()};
  return shapes[which];
}

//! The fuzzer's bytes, read in order; zero once they run out.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  std::uint16_t u16() {
    const std::uint16_t high = byte();
    return static_cast<std::uint16_t>(high << 8 | byte());
  }
  std::int16_t i16() { return static_cast<std::int16_t>(u16()); }
  std::int8_t i8() { return static_cast<std::int8_t>(byte()); }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz: %s\n", what.c_str());
  std::abort();
}

//! Runs body(); any exception is a finding.
template <class Body>
void expect_no_exception(const char* what, Body&& body) {
  try {
    body();
  } catch (const std::exception& e) {
    finding(std::string(what) + " threw " + typeid(e).name() + ": " + e.what());
  } catch (...) {
    finding(std::string(what) + " threw a non-standard exception");
  }
}

//! The queries of the file comment on a validated mesh.
void question_oracle(const delmesh::InputMesh& m) {
  std::unique_ptr<delmesh::MeshOracle> made;
  expect_no_exception("MeshOracle's construction", [&] { made = std::make_unique<delmesh::MeshOracle>(m.mesh, m.box); });
  delmesh::MeshOracle& oracle = *made;
  // The oracle's questions and answers are at unit scale: the input's coordinates times 2^-k.
  const int k = oracle.scale_exponent();
  const delmesh::Box3& box = oracle.box();
  double largest_side = 0;
  for (int i = 0; i < 3; ++i) {
    if (box.lo[i] != std::ldexp(m.box.lo[i], -k) || box.hi[i] != std::ldexp(m.box.hi[i], -k))
      finding("the oracle's box is not the input's box times 2^" + std::to_string(-k));
    largest_side = std::max(largest_side, box.hi[i] - box.lo[i]);
  }
  if (k != 0 && !(largest_side >= 1 && largest_side < 2))
    finding("scale exponent " + std::to_string(k) + " leaves the box's largest side at " + std::to_string(largest_side));

  expect_no_exception("the oracle's questions", [&] {
    const auto statistics = oracle.statistics_json();
    if (statistics.at("faces").get<std::size_t>() != m.mesh.number_of_faces())
      finding("statistics_json()[\"faces\"] is not the mesh's face count");

    std::array<double, 3> centroid{0, 0, 0};
    for (const auto v : m.mesh.vertices()) {
      const Point3& p = m.mesh.point(v);
      const delmesh::Vec3 x{std::ldexp(p.x(), -k), std::ldexp(p.y(), -k), std::ldexp(p.z(), -k)};
      if (oracle.value_sign(x) != 0) finding("value_sign of mesh vertex " + std::to_string(std::size_t(v)) + " is not 0");
      for (int i = 0; i < 3; ++i) centroid[i] += x[i] / static_cast<double>(m.mesh.number_of_vertices());
    }
    for (int corner = 0; corner < 8; ++corner) {
      const delmesh::Vec3 x{(corner & 1) ? box.hi[0] : box.lo[0], (corner & 2) ? box.hi[1] : box.lo[1],
                            (corner & 4) ? box.hi[2] : box.lo[2]};
      if (oracle.value_sign(x) != 1) finding("value_sign of corner " + std::to_string(corner) + " of the box is not +1");
    }

    // A segment from outside the box to outside it, through the centroid, in a fixed generic direction.
    const double diagonal = box.diagonal();
    if (std::isfinite(diagonal) && std::isfinite(2 * diagonal)) {
      const double norm = std::sqrt(1 + 0.3 * 0.3 + 0.17 * 0.17);
      const delmesh::Vec3 d{1 / norm, 0.3 / norm, 0.17 / norm};
      const delmesh::Vec3 p{centroid[0] - diagonal * d[0], centroid[1] - diagonal * d[1], centroid[2] - diagonal * d[2]};
      const delmesh::SolveResult line = oracle.surface_line(p, d, 0, 2 * diagonal);
      if (line.undecided.empty() && line.roots.size() % 2 != 0)
        finding("surface_line crosses the closed mesh an odd number of times (" + std::to_string(line.roots.size()) +
                ") between two points outside it");
    }

    const std::vector<delmesh::MeshOracle::Polyline> section =
        oracle.section(delmesh::Vec3{centroid[0], centroid[1], centroid[2]}, delmesh::Vec3{1, 0, 0}, delmesh::Vec3{0, 1, 0});
    for (const auto& polyline : section)
      if (!polyline.closed || polyline.points.size() < 3)
        finding("section(): a polyline that is open or has fewer than three points");

    const delmesh::Domain whole =
        delmesh::Domain::from_box({{box.lo[0], box.hi[0]}, {box.lo[1], box.hi[1]}, {box.lo[2], box.hi[2]}});
    const delmesh::SolveResult critical = oracle.surface_critical(delmesh::Vec3{0.2, -0.4, 1}, whole, 1000000);
    if (critical.roots.size() < 2 * static_cast<std::size_t>(m.report.components))
      finding("surface_critical found " + std::to_string(critical.roots.size()) + " extrema for " +
              std::to_string(m.report.components) + " component(s)");
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const std::uint8_t flags = in.byte();
  const Shape& base = shape(flags % 3);
  const bool reverse = flags & 4, quadrilaterals = flags & 8;
  const int scale = static_cast<int>(in.u16() % 2151) - 1075;
  const double amplitude = std::ldexp(0.5, -static_cast<int>(in.byte() % 64));
  const int offset_exponent = scale + in.i8();
  std::array<double, 3> offset{};
  for (double& o : offset) o = std::ldexp(in.i8() / 128.0, offset_exponent);

  std::vector<Point3> points;
  for (const auto& v : base.vertices) {
    std::array<double, 3> x{};
    for (int k = 0; k < 3; ++k) x[k] = std::ldexp(v[k] + amplitude * (in.i16() / 32768.0), scale) + offset[k];
    points.emplace_back(x[0], x[1], x[2]);
  }
  std::vector<std::vector<std::size_t>> polygons;
  for (std::size_t f = 0; f < base.triangles.size(); ++f) {
    const auto& t = base.triangles[f];
    std::vector<std::size_t> polygon(t.begin(), t.end());
    // A quadrilateral of this triangle and the next, when they share the edge t[2]-t[0] reversed.
    if (quadrilaterals && f + 1 < base.triangles.size()) {
      const auto& u = base.triangles[f + 1];
      for (int k = 0; k < 3; ++k)
        if (u[k] == t[0] && u[(k + 1) % 3] == t[2]) {
          polygon.push_back(u[(k + 2) % 3]);
          ++f;
          break;
        }
    }
    if (reverse) std::reverse(polygon.begin(), polygon.end());
    polygons.push_back(std::move(polygon));
  }

  delmesh::InputMesh mesh;
  const bool valid = delmesh::fuzz::expect_valid_or_invalid_input(
      "validate_input_mesh", [&] { mesh = delmesh::validate_input_mesh(points, polygons, "fuzzed mesh"); });
  if (valid) question_oracle(mesh);
  return 0;
}
