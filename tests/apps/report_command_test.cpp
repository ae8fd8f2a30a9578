// `delmesh report`: the per-triangle measures and histograms of apps/report_measures.h, and the
// page the program writes (its embedded data, self-containment, bad inputs).  The page drawn in a
// browser is tests/apps/report_render_test.py.
#include <cmath>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "apps/report_measures.h"
#include "tests/apps/run_delmesh.h"

using namespace delmesh::test;
using delmesh::Vec3;
using delmesh::app::histogram;
using delmesh::app::triangle_measures;

namespace {

const double inv_sqrt3 = 1 / std::sqrt(3.0);

//! The JSON of the page's <script id="mesh-data"> element.
nlohmann::json page_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"mesh-data\">";
  const std::size_t begin = html.find(open);
  BOOST_REQUIRE(begin != std::string::npos);
  const std::size_t end = html.find("</script>", begin);
  BOOST_REQUIRE(end != std::string::npos);
  return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
}

//! False (with a message) when the program was built without three.js: `report` then refuses.
bool report_available(const TempDir& dir) {
  write_text(dir / "probe.off", octahedron_off);
  const RunResult r = run_delmesh({"report", "probe.off", "--out", "probe.html"}, dir.path);
  if (r.exit_code == 2 && r.err.find("built without three.js") != std::string::npos) {
    BOOST_TEST(r.single_error_line(), r.err);
    BOOST_TEST_MESSAGE("delmesh was built without three.js: the page is not tested");
    return false;
  }
  return true;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(report_command)

BOOST_AUTO_TEST_CASE(equilateral_triangle) {
  const auto m = triangle_measures({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0});
  for (const double a : m.angles_deg) BOOST_TEST(a == 60.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.min_angle_deg == 60.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.radius_edge_ratio == inv_sqrt3, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.area == std::sqrt(3.0) / 4, boost::test_tools::tolerance(1e-12));
}

// A right isosceles triangle: angles 90, 45, 45 in corner order; circumradius half the
// hypotenuse, so ratio √2/2 against the legs.
BOOST_AUTO_TEST_CASE(right_isosceles_triangle) {
  const auto m = triangle_measures({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  BOOST_TEST(m.angles_deg[0] == 90.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.angles_deg[1] == 45.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.angles_deg[2] == 45.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.min_angle_deg == 45.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.radius_edge_ratio == std::sqrt(0.5), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.area == 0.5, boost::test_tools::tolerance(1e-12));
}

// A thin triangle's small angle is accurate (atan2, not acos of a rounded cosine).
BOOST_AUTO_TEST_CASE(thin_triangle_angle) {
  const double h = 1e-9;
  const auto m = triangle_measures({0, 0, 0}, {1, 0, 0}, {0.5, h, 0});
  BOOST_TEST(m.min_angle_deg == std::atan(2 * h) * 180 / std::acos(-1.0), boost::test_tools::tolerance(1e-6));
}

// The measures do not depend on the scale: at 1e200 and 1e-300 (where squared lengths overflow
// or underflow) the angles and the ratio are those at scale 1.
BOOST_AUTO_TEST_CASE(measures_are_scale_free) {
  const Vec3 a{0.1, 0.2, 0.3}, b{1.3, -0.4, 0.7}, c{0.2, 0.9, -0.5};
  const auto unit = triangle_measures(a, b, c);
  for (const double s : {1e200, 1e-300}) {
    const auto scale = [s](const Vec3& p) { return Vec3{p[0] * s, p[1] * s, p[2] * s}; };
    const auto m = triangle_measures(scale(a), scale(b), scale(c));
    for (int i = 0; i < 3; ++i) BOOST_TEST(m.angles_deg[i] == unit.angles_deg[i], boost::test_tools::tolerance(1e-12));
    BOOST_TEST(m.radius_edge_ratio == unit.radius_edge_ratio, boost::test_tools::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(degenerate_triangles) {
  const auto collinear = triangle_measures({0, 0, 0}, {1, 0, 0}, {3, 0, 0});
  BOOST_TEST(std::isinf(collinear.radius_edge_ratio));
  BOOST_TEST(collinear.min_angle_deg == 0.0);
  BOOST_TEST(collinear.angles_deg[1] == 180.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(collinear.area == 0.0);
  const auto point = triangle_measures({1, 1, 1}, {1, 1, 1}, {1, 1, 1});
  BOOST_TEST(std::isinf(point.radius_edge_ratio));
  BOOST_TEST(point.min_angle_deg == 0.0);
}

BOOST_AUTO_TEST_CASE(histogram_bins) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const auto h = histogram({-1, 0, 0.5, 4.99, 5, 9.999, 10, 10.5, inf, nan}, 0, 10, 2);
  BOOST_TEST(h.counts.size() == 2u);
  BOOST_TEST(h.counts[0] == 3u);  // 0, 0.5, 4.99
  BOOST_TEST(h.counts[1] == 3u);  // 5, 9.999, 10 (the upper end is in the last bin)
  BOOST_TEST(h.below == 1u);
  BOOST_TEST(h.above == 3u);  // 10.5, inf, nan
  BOOST_TEST(h.largest() == 3u);
}

// The octahedron's page: self-contained, its data is the mesh (centred, unit half-diagonal) with
// every triangle's min angle 60° and radius-edge ratio 1/√3, and it opens coloured as asked.
BOOST_AUTO_TEST_CASE(octahedron_page) {
  TempDir dir;
  if (!report_available(dir)) return;
  write_text(dir / "octahedron.off", octahedron_off);
  const RunResult r = run_delmesh({"report", "octahedron.off", "--color", "radius-edge", "--out", "o.html"}, dir.path);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.empty(), r.err);
  BOOST_TEST(r.out.empty(), r.out);
  const std::string html = read_text(dir / "o.html");
  BOOST_TEST(html.rfind("<!DOCTYPE html>", 0) == 0u);
  BOOST_TEST(html.find("</html>") != std::string::npos);
  // Nothing is loaded from elsewhere: no script or stylesheet by address.
  BOOST_TEST(!std::regex_search(html, std::regex("<(script|link|img|iframe)[^>]*(src|href)\\s*=", std::regex::icase)));
  // three.js is embedded (its module exports WebGLRenderer), and the SVG histograms are there.
  BOOST_TEST(html.find("WebGLRenderer") != std::string::npos);
  BOOST_TEST(html.find("<svg class=\"hist\"") != std::string::npos);
  const nlohmann::json data = page_data(html);
  BOOST_TEST(data.at("color").get<std::string>() == "radius-edge");
  BOOST_TEST(data.at("triangles").size() == 24u);
  BOOST_TEST(data.at("positions").size() == 18u);
  // The octahedron's box is [-1,1]^3, half-diagonal √3: the vertex (1,0,0) is at 1/√3.
  BOOST_TEST(data.at("positions")[0].get<double>() == inv_sqrt3, boost::test_tools::tolerance(1e-6));
  BOOST_TEST(data.at("measures").at("min-angle").size() == 8u);
  for (const auto& a : data.at("measures").at("min-angle")) BOOST_TEST(a.get<double>() == 60.0, boost::test_tools::tolerance(1e-5));
  for (const auto& q : data.at("measures").at("radius-edge")) BOOST_TEST(q.get<double>() == inv_sqrt3, boost::test_tools::tolerance(1e-5));
  for (const auto& s : data.at("measures").at("area")) BOOST_TEST(s.get<double>() == 1.0, boost::test_tools::tolerance(1e-3));
  // Without --stats the page says how to add them.
  BOOST_TEST(html.find("No statistics given") != std::string::npos);
}

// A quadrilateral face is triangulated as `check` does it, and a degenerate triangle gets ratio
// null (∞) in the data.
BOOST_AUTO_TEST_CASE(polygons_and_degenerate_triangles) {
  TempDir dir;
  if (!report_available(dir)) return;
  write_text(dir / "quad.off", "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n4 0 1 2 3\n3 0 1 4\n");
  const RunResult r = run_delmesh({"report", "quad.off", "--out", "q.html"}, dir.path);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const nlohmann::json data = page_data(read_text(dir / "q.html"));
  BOOST_TEST(data.at("triangles").size() == 9u);
  const auto& ratios = data.at("measures").at("radius-edge");
  BOOST_TEST(ratios[0].get<double>() == std::sqrt(0.5), boost::test_tools::tolerance(1e-5));
  BOOST_TEST(ratios[2].is_null());
}

// With the statistics of `delmesh mesh`: the run, the distance certificate, Theorem 6.1's bounds
// checked on the file, and every top-level key among the tables; statistics of another mesh give
// one warning and a note on the page.
BOOST_AUTO_TEST_CASE(torus_with_statistics) {
  TempDir dir;
  if (!report_available(dir)) return;
  const RunResult mesh = run_delmesh({"mesh", "--surface", "torus", "--out", "torus.off", "--stats", "torus.json", "--quiet"}, dir.path);
  BOOST_TEST_REQUIRE(mesh.exit_code == 0, mesh.err);
  const RunResult r = run_delmesh({"report", "torus.off", "--stats", "torus.json", "--out", "t.html"}, dir.path);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.empty(), r.err);
  const std::string html = read_text(dir / "t.html");
  for (const char* text : {"Hausdorff distance", "<span class=\"badge good\">certified</span>",
                           "<span class=\"badge good\">complete</span>", "Theorem 6.1's bounds, on this file", "(x^2+y^2+z^2+0.84)^2",
                           "<summary>solver (", "<summary>insertions (", "<summary>general (", "<th>peak memory</th>",
                           " B per vertex)"})
    BOOST_TEST(html.find(text) != std::string::npos, text);
  BOOST_TEST(html.find("badge bad") == std::string::npos);  // every bound passes
  BOOST_TEST(page_data(html).at("color").get<std::string>() == "min-angle");

  write_text(dir / "octahedron.off", octahedron_off);
  const RunResult other = run_delmesh({"report", "octahedron.off", "--stats", "torus.json", "--out", "o.html"}, dir.path);
  BOOST_TEST(other.exit_code == 0, other.err);
  BOOST_TEST(other.err_lines().size() == 1u, other.err);
  BOOST_TEST(other.err.rfind("warning: the statistics torus.json describe a mesh of", 0) == 0u, other.err);
  BOOST_TEST(read_text(dir / "o.html").find("class=\"notes\"") != std::string::npos);
}

// Bad inputs: one error line, exit code 2, and an existing page left as it was.
BOOST_AUTO_TEST_CASE(bad_inputs) {
  TempDir dir;
  if (!report_available(dir)) return;
  write_text(dir / "octahedron.off", octahedron_off);
  write_text(dir / "page.html", "old\n");
  write_text(dir / "broken.json", "{\"status\": ");
  write_text(dir / "list.json", "[1, 2]");
  write_text(dir / "truncated.off", "OFF\n6 8 0\n1 0 0\n");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"report", "missing.off", "--out", "page.html"}, "missing.off"},
      {{"report", "truncated.off", "--out", "page.html"}, "truncated.off"},
      {{"report", "octahedron.off", "--stats", "missing.json", "--out", "page.html"}, "missing.json"},
      {{"report", "octahedron.off", "--stats", "broken.json", "--out", "page.html"}, "not a JSON file"},
      {{"report", "octahedron.off", "--stats", "list.json", "--out", "page.html"}, "expected a JSON object"},
      {{"report", "octahedron.off", "--color", "curvature", "--out", "page.html"}, "--color"},
      {{"report", "octahedron.off", "--out", "octahedron.off"}, "is the mesh file itself"},
      {{"report", "octahedron.off", "--out", "no_such_directory/page.html"}, "--out"},
      {{"report", "octahedron.off"}, "--out"},
  };
  for (const auto& [args, mention] : cases) {
    BOOST_TEST_CONTEXT(args[1] << " " << args.back()) {
      require_invalid_input(run_delmesh(args, dir.path), mention);
      BOOST_TEST(read_text(dir / "page.html") == "old\n");
    }
  }
  BOOST_TEST(read_text(dir / "octahedron.off") == octahedron_off);
}

BOOST_AUTO_TEST_SUITE_END()
