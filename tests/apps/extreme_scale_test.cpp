// Whole-command runs at the extremes of double precision: input meshes of size 1e-200 to 1e100,
// expressions with a constant factor of 1e±200 and 1e±300, and `check` on a mesh scaled by
// 1e200 and 1e-300.  None may die by a signal or end with an internal error (exit 4).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "meshing/core/mesh_checker.h"
#include "meshing/inputs/mesh_io.h"
#include "tests/apps/run_delmesh.h"
#include "tests/meshing/known_meshes.h"

using namespace delmesh::test;

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = std::array<double, 3>;

//! The icosphere of known_meshes.h with two levels: 162 vertices on the unit sphere, 320
//! triangles, outward oriented.
void unit_icosphere(std::vector<P3>& points, std::vector<std::array<int, 3>>& faces) {
  const Soup sphere = icosphere(2);
  points.clear();
  faces.clear();
  for (const auto& p : sphere.points) points.push_back({p.x(), p.y(), p.z()});
  for (const auto& t : sphere.triangles)
    faces.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
}

//! Points and triangles as OFF text, every coordinate with 17 significant digits.
std::string off_text(const std::vector<P3>& points, const std::vector<std::array<int, 3>>& faces) {
  std::string text = "OFF\n" + std::to_string(points.size()) + " " + std::to_string(faces.size()) + " 0\n";
  char line[128];
  for (const auto& p : points) {
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
    text += line;
  }
  for (const auto& f : faces) text += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
  return text;
}

//! The largest distance from a point of `points` to the triangles of the unit icosphere, each
//! point first divided by `radius`.
double largest_distance_to_icosphere(const std::vector<delmesh::Point3>& points, double radius) {
  std::vector<P3> sphere;
  std::vector<std::array<int, 3>> faces;
  unit_icosphere(sphere, faces);
  double largest = 0;
  for (const auto& x : points) {
    const Kernel::Point_3 p(x.x() / radius, x.y() / radius, x.z() / radius);
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& f : faces) {
      const Kernel::Triangle_3 t({sphere[f[0]][0], sphere[f[0]][1], sphere[f[0]][2]},
                                 {sphere[f[1]][0], sphere[f[1]][1], sphere[f[1]][2]},
                                 {sphere[f[2]][0], sphere[f[2]][1], sphere[f[2]][2]});
      nearest = std::min(nearest, std::sqrt(CGAL::squared_distance(p, t)));
    }
    largest = std::max(largest, nearest);
  }
  return largest;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(extreme_scale)

// The icosphere scaled by r: remeshed (exit 0, 3 or 5 with a mesh of genus 0 whose vertices lie
// on the input), or refused with the documented coordinate range; never a signal or exit 4.
BOOST_AUTO_TEST_CASE(input_mesh_at_extreme_scales) {
  std::vector<P3> unit;
  std::vector<std::array<int, 3>> faces;
  unit_icosphere(unit, faces);
  BOOST_REQUIRE(unit.size() == 162);
  for (const double radius : {1e-100, 1e-200, 1e80, 1e100}) {
    BOOST_TEST_CONTEXT("radius " << radius) {
      TempDir dir;
      std::vector<P3> points = unit;
      for (auto& p : points)
        for (double& c : p) c *= radius;
      write_text(dir / "ico.off", off_text(points, faces));
      const RunResult r = run_delmesh({"mesh", "--input-mesh", "ico.off", "--max-points", "300", "--time-limit", "20",
                                       "--quiet", "--out", "m.off", "--stats", "m.json"},
                                      dir.path);
      BOOST_TEST(!r.signalled);
      BOOST_TEST(r.exit_code != 4, "stderr: " << r.err);
      if (r.exit_code == 2) {
        require_invalid_input(r, "above 1e100 in magnitude");
        continue;
      }
      BOOST_TEST((r.exit_code == 0 || r.exit_code == 3 || r.exit_code == 5), "exit " << r.exit_code << ": " << r.err);
      const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "m.json"));
      BOOST_TEST(stats.at("genus_per_component") == nlohmann::json::array({0}), stats.at("genus_per_component").dump());
      delmesh::TriangleSoup soup;
      BOOST_REQUIRE_NO_THROW(soup = delmesh::read_triangle_soup((dir / "m.off").string()));
      BOOST_TEST(soup.points.size() >= 4u);
      BOOST_TEST(delmesh::check_mesh(soup.points, soup.triangles).has_topology({0}));
      // The output's vertices lie on the input surface, at its scale.
      BOOST_TEST(largest_distance_to_icosphere(soup.points, radius) < 1e-9);
      const auto& clip = stats.at("clip_box");
      BOOST_TEST(clip.at(1).get<double>() > 0.9 * radius);
      BOOST_TEST(clip.at(1).get<double>() < 1.5 * radius);
    }
  }
}

// A constant factor of E does not change the surface: a unit sphere times 1e±200 or 1e±300 is
// meshed as the unit sphere (never refused as "empty").
BOOST_AUTO_TEST_CASE(scaled_expressions_mesh_the_surface) {
  for (const std::string factor : {"1e200", "1e-200", "1e300", "1e-300"}) {
    BOOST_TEST_CONTEXT("factor " << factor) {
      TempDir dir;
      const RunResult r = run_delmesh({"mesh", "--expr", factor + "*(x^2+y^2+z^2-1)", "--box", "-2,2,-2,2,-2,2",
                                       "--max-points", "2000", "--time-limit", "60", "--quiet", "--out", "m.off",
                                       "--stats", "m.json"},
                                      dir.path);
      BOOST_TEST(!r.signalled);
      BOOST_TEST(r.err.find("empty") == std::string::npos, r.err);
      BOOST_TEST(r.exit_code == 0, "exit " << r.exit_code << ": " << r.err);
      if (r.exit_code != 0) continue;
      const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "m.json"));
      BOOST_TEST(stats.at("genus_per_component") == nlohmann::json::array({0}));
      delmesh::TriangleSoup soup;
      BOOST_REQUIRE_NO_THROW(soup = delmesh::read_triangle_soup((dir / "m.off").string()));
      for (const auto& p : soup.points) BOOST_TEST(std::abs(std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z()) - 1) < 1e-6);
    }
  }
}

// Seed regions that cannot be projected onto the surface (E's values overflow double precision
// and no constant factor can be taken out of the sum) leave the run uncertified, with the regions
// in the unsettled list: never "the surface is empty".
BOOST_AUTO_TEST_CASE(unprojectable_seed_regions_are_uncertified_not_empty) {
  TempDir dir;
  const RunResult r = run_delmesh({"mesh", "--expr", "1e200*(x^2+y^2+z^2-1)+1e-300*sin(x)", "--box", "-2,2,-2,2,-2,2",
                                   "--max-points", "500", "--time-limit", "60", "--quiet", "--out", "m.off",
                                   "--stats", "m.json"},
                                  dir.path);
  BOOST_TEST(!r.signalled);
  BOOST_TEST(r.exit_code == 5, "exit " << r.exit_code << ": " << r.err);
  BOOST_TEST(r.err.find("empty") == std::string::npos, r.err);
  if (r.exit_code != 5) return;
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "m.json"));
  BOOST_TEST(stats.at("status") == "uncertified");
  BOOST_TEST(stats.at("unsettled").at("by_reason").value("unprojectable_region", 0) > 0, stats.at("unsettled").dump());
  BOOST_TEST(stats.at("unsettled").at("regions").at(0).at("check") == "seed");
}

// `check --lambda 0.06` on a good sphere mesh and on the same mesh scaled by 1e200 and 1e-300:
// the same verdict and the same measures.
BOOST_AUTO_TEST_CASE(check_verdict_does_not_depend_on_scale) {
  TempDir dir;
  const RunResult made = run_delmesh({"mesh", "--surface", "sphere", "--quiet", "--out", "sphere.off", "--stats", "s.json"},
                                     dir.path);
  BOOST_REQUIRE(made.exit_code == 0);
  delmesh::TriangleSoup soup = delmesh::read_triangle_soup((dir / "sphere.off").string());
  std::vector<P3> unit;
  for (const auto& p : soup.points) unit.push_back({p.x(), p.y(), p.z()});
  std::vector<std::array<int, 3>> faces;
  for (const auto& t : soup.triangles) faces.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});

  std::map<double, nlohmann::json> answers;
  std::map<double, int> exits;
  for (const double scale : {1.0, 1e200, 1e-300}) {
    std::vector<P3> points = unit;
    for (auto& p : points)
      for (double& c : p) c *= scale;
    write_text(dir / "scaled.off", off_text(points, faces));
    const RunResult r = run_delmesh({"check", "scaled.off", "--lambda", "0.06", "--json"}, dir.path);
    BOOST_TEST(!r.signalled);
    exits[scale] = r.exit_code;
    answers[scale] = nlohmann::json::parse(r.out);
  }
  BOOST_TEST(exits[1.0] == 0);
  for (const double scale : {1e200, 1e-300}) {
    BOOST_TEST_CONTEXT("scale " << scale) {
      BOOST_TEST(exits[scale] == exits[1.0]);
      for (const char* key : {"min_angle_deg", "max_radius_edge_ratio", "max_roughness_rad"}) {
        BOOST_TEST(answers[scale].at(key).is_number(), key);
        if (!answers[scale].at(key).is_number()) continue;
        const double scaled = answers[scale].at(key).get<double>(), unscaled = answers[1.0].at(key).get<double>();
        BOOST_TEST(std::abs(scaled - unscaled) <= 1e-9, key << ": " << scaled << " against " << unscaled);
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
