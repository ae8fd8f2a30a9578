#pragma once
//! \file feature_meshes.h
//! Meshes with known sharp features, shared by the tests of sharp_features.h and
//! protecting_balls.h.

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>

#include <boost/test/unit_test.hpp>

#include "tests/meshing/known_meshes.h"
#include "tests/temp_dir.h"

namespace delmesh::test {

//! The cube [0, 1]³ with every face an n × n grid of squares, each split into two triangles,
//! outward oriented: 6n² + 2 vertices, 12n² triangles, 12n sharp edges, 8 corners.
inline Soup grid_cube(int n) {
  Soup s;
  std::map<std::array<int, 3>, std::size_t> index;
  const auto vertex = [&](std::array<int, 3> g) {
    const auto [it, added] = index.emplace(g, s.points.size());
    if (added) s.points.emplace_back(double(g[0]) / n, double(g[1]) / n, double(g[2]) / n);
    return it->second;
  };
  // Face of the axis `axis` at side `side` (0 or n): the grid over the two other axes, oriented
  // so that its normal points away from the cube.
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {0, n}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          std::array<std::size_t, 4> q;
          const int corners[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          for (int k = 0; k < 4; ++k) {
            std::array<int, 3> g{};
            g[axis] = side;
            g[u] = corners[k][0];
            g[v] = corners[k][1];
            q[k] = vertex(g);
          }
          // (u, v, axis) is right-handed, so q is counter-clockwise seen from +axis.
          if (side == n) {
            s.triangles.push_back({q[0], q[1], q[2]});
            s.triangles.push_back({q[0], q[2], q[3]});
          } else {
            s.triangles.push_back({q[0], q[2], q[1]});
            s.triangles.push_back({q[0], q[3], q[2]});
          }
        }
    }
  return s;
}

//! An open sheet of two planar strips [−1, 0] × [0, 1] and [0, 1] × [0, 1] (in x, y) meeting along
//! the crease x = 0, the second turned about the y axis so that the normals of the two strips
//! differ by `angle_deg`; each strip an n × n grid of squares split in two.  Its border is one
//! loop through the crease's two ends.
inline Soup crease(double angle_deg, int n) {
  Soup s;
  const double a = angle_deg * M_PI / 180;
  std::map<std::pair<int, int>, std::size_t> index;
  const auto vertex = [&](int i, int j) {  // i in [−n, n], j in [0, n]
    const auto [it, added] = index.emplace(std::make_pair(i, j), s.points.size());
    if (added) {
      const double x = double(i) / n, y = double(j) / n;
      if (i <= 0)
        s.points.emplace_back(x, y, 0.0);
      else
        s.points.emplace_back(x * std::cos(a), y, x * std::sin(a));
    }
    return it->second;
  };
  for (int i = -n; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::size_t p = vertex(i, j), q = vertex(i + 1, j), r = vertex(i + 1, j + 1), t = vertex(i, j + 1);
      s.triangles.push_back({p, q, r});
      s.triangles.push_back({p, r, t});
    }
  return s;
}

//! Extracts data/meshes/<name>.off from CGAL's data archive (libcgal-demo) into `dir` and returns
//! its path; fails the test if the archive is missing.
inline std::string cgal_data_mesh(const std::string& name, const TempDir& dir) {
  const std::string archive = "/usr/share/doc/libcgal-dev/data.tar.gz";
  BOOST_REQUIRE_MESSAGE(std::filesystem::exists(archive), archive + " is missing (install libcgal-demo)");
  const std::string member = "data/meshes/" + name + ".off";
  const std::string command = "tar -xzf " + archive + " -C '" + dir.path.string() + "' " + member;
  BOOST_REQUIRE(std::system(command.c_str()) == 0);
  return (dir.path / member).string();
}

}  // namespace delmesh::test
