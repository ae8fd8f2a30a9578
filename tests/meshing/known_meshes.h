#pragma once
//! \file known_meshes.h
//! Small triangle soups with known topology and geometry, shared by the meshing tests.

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <cstddef>
#include <vector>

#include "meshing/core/surface_mesh.h"

namespace delmesh::test {

struct Soup {
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;

  //! Appends other with its indices shifted (a disjoint union).
  void append(const Soup& other) {
    const std::size_t shift = points.size();
    points.insert(points.end(), other.points.begin(), other.points.end());
    for (auto t : other.triangles) triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
  }
  Soup translated(double dx, double dy, double dz) const {
    Soup out = *this;
    for (Point3& p : out.points) p = Point3(p.x() + dx, p.y() + dy, p.z() + dz);
    return out;
  }
  SurfaceMesh to_surface_mesh() const {
    SurfaceMesh mesh;
    std::vector<SurfaceMesh::Vertex_index> v;
    for (const Point3& p : points) v.push_back(mesh.add_vertex(p));
    for (auto t : triangles) mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
    return mesh;
  }
};

//! Regular tetrahedron, outward oriented, edge length 2√2.
inline Soup tetrahedron() {
  return {{Point3(1, 1, 1), Point3(1, -1, -1), Point3(-1, 1, -1), Point3(-1, -1, 1)},
          {{{0, 1, 2}}, {{0, 3, 1}}, {{0, 2, 3}}, {{1, 3, 2}}}};
}

//! Regular octahedron with vertices ±e_i, outward oriented (volume 4/3).
inline Soup octahedron() {
  Soup s;
  s.points = {Point3(1, 0, 0), Point3(-1, 0, 0), Point3(0, 1, 0),
              Point3(0, -1, 0), Point3(0, 0, 1), Point3(0, 0, -1)};
  // For each octant (sx, sy, sz) the triangle (x, y, z) is outward iff sx*sy*sz > 0.
  for (int sx : {0, 1})
    for (int sy : {0, 1})
      for (int sz : {0, 1}) {
        std::array<std::size_t, 3> t{std::size_t(sx), std::size_t(2 + sy), std::size_t(4 + sz)};
        if ((sx + sy + sz) % 2 == 1) std::swap(t[1], t[2]);
        s.triangles.push_back(t);
      }
  return s;
}

//! Regular icosahedron inscribed in the unit sphere, outward oriented.
inline Soup icosahedron() {
  const double phi = (1 + std::sqrt(5.0)) / 2, s = 1 / std::sqrt(1 + phi * phi);
  Soup m;
  const double c[12][3] = {{-1, phi, 0}, {1, phi, 0},  {-1, -phi, 0}, {1, -phi, 0},
                           {0, -1, phi}, {0, 1, phi},  {0, -1, -phi}, {0, 1, -phi},
                           {phi, 0, -1}, {phi, 0, 1},  {-phi, 0, -1}, {-phi, 0, 1}};
  for (const auto& p : c) m.points.emplace_back(s * p[0], s * p[1], s * p[2]);
  m.triangles = {{{0, 11, 5}}, {{0, 5, 1}},  {{0, 1, 7}},   {{0, 7, 10}}, {{0, 10, 11}},
                 {{1, 5, 9}},  {{5, 11, 4}}, {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},
                 {{3, 9, 4}},  {{3, 4, 2}},  {{3, 2, 6}},   {{3, 6, 8}},  {{3, 8, 9}},
                 {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}},  {{8, 6, 7}},  {{9, 8, 1}}};
  return m;
}

//! The icosahedron with each triangle split into four `levels` times, every new vertex (an edge's
//! midpoint) pushed out onto the unit sphere: 10·4^levels + 2 vertices, outward oriented.
inline Soup icosphere(int levels) {
  Soup m = icosahedron();
  auto on_sphere = [](const Point3& p) {
    const double n = std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z());
    return Point3(p.x() / n, p.y() / n, p.z() / n);
  };
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> middle;
    auto mid = [&](std::size_t a, std::size_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      if (auto it = middle.find(key); it != middle.end()) return it->second;
      m.points.push_back(on_sphere(CGAL::midpoint(m.points[a], m.points[b])));
      return middle[key] = m.points.size() - 1;
    };
    std::vector<std::array<std::size_t, 3>> finer;
    for (const auto& t : m.triangles) {
      const std::size_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    m.triangles = std::move(finer);
  }
  return m;
}

//! The n × m grid on [0,n]×[0,m] with the cell (i, j) split along its diagonal, vertices
//! identified by index(i, j) (which implements the wrap-around), placed at position(i, j).
template <class Index, class Position>
Soup grid(int n, int m, int rows, Index index, Position position) {
  Soup s;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < rows; ++j) s.points.push_back(position(i, j));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const std::size_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      s.triangles.push_back({a, b, c});
      s.triangles.push_back({a, c, d});
    }
  return s;
}

//! Torus (R = 2, r = 1) triangulated by an n × m grid (n, m ≥ 3): χ = 0, genus 1, outward.
inline Soup torus(int n, int m) {
  const double two_pi = 2 * std::acos(-1.0);
  return grid(
      n, m, m, [n, m](int i, int j) { return std::size_t(((i % n) * m) + (j % m)); },
      [&](int i, int j) {
        const double u = two_pi * i / n, v = two_pi * j / m;
        return Point3((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v));
      });
}

//! Möbius strip: a strip of n cells (two rows of vertices) glued with a half twist.  Non-orientable,
//! with boundary (one boundary circle of 2n edges), χ = 0.
inline Soup mobius_strip(int n) {
  const double pi = std::acos(-1.0);
  return grid(
      n, 1, 2,
      [n](int i, int j) {
        // Crossing i = n flips the row: (n, j) ~ (0, 1 − j).
        return i >= n ? std::size_t(0 * 2 + (1 - j)) : std::size_t(i * 2 + j);
      },
      [&](int i, int j) {
        const double u = 2 * pi * i / n, w = j - 0.5;
        const double r = 2 + w * std::cos(u / 2);
        return Point3(r * std::cos(u), r * std::sin(u), w * std::sin(u / 2));
      });
}

//! Klein bottle as an abstract n × m grid (combinatorics only; the points lie on a torus, the
//! checker's topology does not depend on them): closed, manifold, non-orientable, χ = 0.
inline Soup klein_bottle(int n, int m) {
  const double two_pi = 2 * std::acos(-1.0);
  return grid(
      n, m, m,
      [n, m](int i, int j) {
        const int jj = i >= n ? (m - (j % m)) % m : j % m;
        return std::size_t((i % n) * m + jj);
      },
      [&](int i, int j) {
        const double u = two_pi * i / n, v = two_pi * j / m;
        return Point3((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v));
      });
}

//! An open disk: a fan of k triangles around a centre (χ = 1, k boundary edges).
inline Soup open_disk(int k) {
  const double two_pi = 2 * std::acos(-1.0);
  Soup s;
  s.points.emplace_back(0, 0, 0);
  for (int i = 0; i < k; ++i) s.points.emplace_back(std::cos(two_pi * i / k), std::sin(two_pi * i / k), 0);
  for (int i = 0; i < k; ++i)
    s.triangles.push_back({0, std::size_t(1 + i), std::size_t(1 + (i + 1) % k)});
  return s;
}

//! Two triangles sharing only one vertex (a bow-tie).
inline Soup bow_tie() {
  return {{Point3(0, 0, 0), Point3(1, 0.5, 0), Point3(1, -0.5, 0), Point3(-1, 0.5, 0), Point3(-1, -0.5, 0)},
          {{{0, 1, 2}}, {{0, 4, 3}}}};
}

//! Two equilateral triangles (unit edges) sharing the edge (0,0,0)–(1,0,0) with internal
//! dihedral angle phi; consistently oriented unless flip_second.
inline Soup hinge(double phi, bool flip_second = false) {
  const double h = std::sqrt(3.0) / 2;
  Soup s;
  s.points = {Point3(0, 0, 0), Point3(1, 0, 0), Point3(0.5, h, 0),
              Point3(0.5, h * std::cos(phi), h * std::sin(phi))};
  s.triangles = {{{0, 1, 2}}};
  s.triangles.push_back(flip_second ? std::array<std::size_t, 3>{0, 1, 3} : std::array<std::size_t, 3>{1, 0, 3});
  return s;
}

}  // namespace delmesh::test
