#include "meshing/verify/gradient_flow_certificate.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/driver/del_mesh.h"
#include "symbolic/catalog.h"
#include "tests/meshing/known_meshes.h"

using namespace delmesh;

namespace {

const std::string unit_sphere = "x^2+y^2+z^2-1";
const Box3 sphere_box = Box3::cube(1.5);
// The torus of radii 2 and 1 about the z axis: test::torus's surface.
const std::string torus_2_1 = "(x^2+y^2+z^2+3)^2-16*(x^2+y^2)";
const Box3 torus_box{{-3.5, -3.5, -1.5}, {3.5, 3.5, 1.5}};

FlowCertificate certify(const test::Soup& m, const std::string& e, const Box3& box) {
  return certify_gradient_flow(m.points, m.triangles, Surface::parse(e), box);
}

double norm(const Point3& p) { return std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z()); }

// The largest distance to the unit sphere over points of the mesh's triangles (barycentric grid
// of step 1/16): a lower bound on the one-sided Hausdorff distance from the mesh to the sphere.
double sampled_distance_to_unit_sphere(const test::Soup& m) {
  double worst = 0;
  for (const auto& t : m.triangles)
    for (int i = 0; i <= 16; ++i)
      for (int j = 0; i + j <= 16; ++j) {
        const double u = i / 16.0, v = j / 16.0, w = 1 - u - v;
        const Point3 &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
        const Point3 x(w * a.x() + u * b.x() + v * c.x(), w * a.y() + u * b.y() + v * c.y(),
                       w * a.z() + u * b.z() + v * c.z());
        worst = std::max(worst, std::abs(norm(x) - 1));
      }
  return worst;
}

//! delmesh's mesh of a catalog surface, and its gradient-flow certificate.
struct CertifiedCatalogMesh {
  Box3 box;
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  FlowCertificate certificate;
};

CertifiedCatalogMesh mesh_and_certify(const std::string& name, const DelMeshOptions& options) {
  const CatalogEntry& entry = catalog_entry(name);
  const Surface surface = entry.surface();
  const DelMeshResult r = del_mesh(surface, entry.box, options);
  BOOST_TEST_REQUIRE(r.status == MeshStatus::complete);
  CertifiedCatalogMesh m{entry.box, {}, {}, {}};
  mesh_to_soup(r.mesh, m.points, m.triangles);
  m.certificate = certify_gradient_flow(m.points, m.triangles, surface, entry.box);
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(gradient_flow_certificate)

// An icosphere with its vertices on the unit sphere: not the restricted Delaunay triangulation of
// its vertices in general, but isotopic to the sphere; the bound holds and is not loose.
BOOST_AUTO_TEST_CASE(an_icosphere_is_certified_with_a_sound_hausdorff_bound) {
  const test::Soup m = test::icosphere(3);
  const FlowCertificate c = certify(m, unit_sphere, sphere_box);
  BOOST_TEST_REQUIRE(c.status == FlowCertificateStatus::certified, c.reason);
  BOOST_TEST(c.mesh_components == 1u);
  BOOST_TEST(c.critical_points >= 2u);  // a maximum and a minimum of the height
  const double sampled = sampled_distance_to_unit_sphere(m);
  BOOST_TEST(c.hausdorff_upper_bound >= sampled);
  BOOST_TEST(c.hausdorff_upper_bound <= 10 * sampled, "bound " << c.hausdorff_upper_bound << ", sampled " << sampled);
  BOOST_TEST(c.triangle_distance_bounds.size() == m.triangles.size());
  for (double d : c.triangle_distance_bounds) BOOST_TEST(d <= c.hausdorff_upper_bound);
}

// Reversing every triangle changes nothing: orientation is found per component.
BOOST_AUTO_TEST_CASE(an_inward_oriented_mesh_is_certified_too) {
  test::Soup m = test::icosphere(2);
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  BOOST_TEST(certify(m, unit_sphere, sphere_box).status == FlowCertificateStatus::certified);
}

// A grid torus (vertices on the torus, 48 × 24 cells): genus 1, certified.
BOOST_AUTO_TEST_CASE(a_grid_torus_is_certified) {
  const FlowCertificate c = certify(test::torus(48, 24), torus_2_1, torus_box);
  BOOST_TEST(c.status == FlowCertificateStatus::certified, c.reason);
  BOOST_TEST(c.hausdorff_upper_bound > 0);
}

// Two nested spheres around one unit sphere: each is transverse, but the segment through a
// critical point crosses the mesh twice.
BOOST_AUTO_TEST_CASE(a_doubly_covered_sphere_is_not_certified) {
  test::Soup m = test::icosphere(2);
  test::Soup outer = test::icosphere(2);
  for (Point3& p : outer.points) p = Point3(1.01 * p.x(), 1.01 * p.y(), 1.01 * p.z());
  m.append(outer);
  const FlowCertificate c = certify(m, unit_sphere, sphere_box);
  BOOST_TEST(c.status == FlowCertificateStatus::undecided);
  BOOST_TEST(c.reason.find("2 times") != std::string::npos, c.reason);
}

// Two unit spheres, the mesh around one of them: the other component is missed.  (The mesh is
// fine enough for the tube |E| ≤ ε′ around it to stay clear of the critical point of E between
// the spheres, where E = 1.5625.)
BOOST_AUTO_TEST_CASE(a_missing_component_is_not_certified) {
  const FlowCertificate c = certify(test::icosphere(3), "(x^2+y^2+z^2-1)*((x-3)^2+y^2+z^2-1)",
                                    Box3{{-1.5, -1.5, -1.5}, {4.5, 1.5, 1.5}});
  BOOST_TEST(c.status == FlowCertificateStatus::undecided);
  BOOST_TEST(c.reason.find("0 times") != std::string::npos, c.reason);
  BOOST_REQUIRE(c.location.has_value());
  BOOST_TEST((*c.location)[0] > 1.5);  // at the sphere without a mesh
}

// A vertex moved across one of its neighbours (onto the sphere beyond it) folds the mesh: the
// triangles on the far side are crossed by ∇E the other way.  A vertex pushed in by a fifth of
// the radius is only a dimple, transverse still, and certified.
BOOST_AUTO_TEST_CASE(a_folded_vertex_is_not_certified) {
  test::Soup m = test::icosphere(2);
  std::size_t neighbour = 0;
  for (const auto& t : m.triangles)
    if (t[0] == 0) neighbour = t[1];
  BOOST_TEST_REQUIRE((neighbour != 0u));
  const Point3 &p = m.points[0], &q = m.points[neighbour];
  const Point3 beyond(2 * q.x() - p.x(), 2 * q.y() - p.y(), 2 * q.z() - p.z());
  const double r = norm(beyond);
  test::Soup folded = m;
  folded.points[0] = Point3(beyond.x() / r, beyond.y() / r, beyond.z() / r);
  const FlowCertificate c = certify(folded, unit_sphere, sphere_box);
  BOOST_TEST(c.status == FlowCertificateStatus::undecided);
  const bool names_the_flux =
      c.reason.find("transverse") != std::string::npos || c.reason.find("both directions") != std::string::npos;
  BOOST_TEST(names_the_flux, c.reason);

  test::Soup dimpled = m;
  dimpled.points[0] = Point3(0.8 * p.x(), 0.8 * p.y(), 0.8 * p.z());
  BOOST_TEST(certify(dimpled, unit_sphere, sphere_box).status == FlowCertificateStatus::certified);
}

// A sphere is not a mesh of a torus: the tube of |E| holding it holds critical points of E.
BOOST_AUTO_TEST_CASE(a_mesh_of_the_wrong_surface_is_not_certified) {
  test::Soup m = test::icosphere(2);
  for (Point3& p : m.points) p = Point3(2 * p.x(), 2 * p.y(), 0.5 * p.z());
  BOOST_TEST(certify(m, torus_2_1, torus_box).status != FlowCertificateStatus::certified);
}

// A mesh with a hole is not a closed surface, and the unit sphere provably is: refuted.
BOOST_AUTO_TEST_CASE(an_open_mesh_is_refuted) {
  test::Soup m = test::icosphere(2);
  m.triangles.pop_back();
  const FlowCertificate c = certify(m, unit_sphere, sphere_box);
  BOOST_TEST(c.status == FlowCertificateStatus::refuted);
  BOOST_TEST(c.reason.find("not a closed orientable 2-manifold") != std::string::npos, c.reason);
}

BOOST_AUTO_TEST_CASE(bad_soups_are_invalid_input) {
  const test::Soup m = test::icosphere(1);
  const Surface s = Surface::parse(unit_sphere);
  BOOST_CHECK_THROW((void)certify_gradient_flow(m.points, {}, s, sphere_box), InvalidInput);
  BOOST_CHECK_THROW((void)certify_gradient_flow(m.points, {{0, 1, 1000}}, s, sphere_box), InvalidInput);
  BOOST_CHECK_THROW((void)certify_gradient_flow(m.points, {{0, 1, 1}}, s, sphere_box), InvalidInput);
}

// delmesh's own mesh of the torus of the catalog at size bound 0.1 is certified by the flow as
// well.
BOOST_AUTO_TEST_CASE(delmesh_output_is_certified) {
  DelMeshOptions options;
  options.size_bound = 0.1;
  const CertifiedCatalogMesh m = mesh_and_certify("torus", options);
  BOOST_TEST(m.certificate.status == FlowCertificateStatus::certified, m.certificate.reason);
  BOOST_TEST(m.certificate.hausdorff_upper_bound / m.box.diagonal() < 0.01);
}

// delmesh's default mesh of the catalog ellipsoid: E's tube |E| ≤ ε′ reaches the tight box (|∇E|
// varies by a factor 4 over Σ, so a tube wide enough where ∇E is small is too wide elsewhere);
// the normalised function's tube has about the same width everywhere and certifies it.  The
// bound d of every vertex p (the global one, and each of its triangles') is checked against a
// proved lower bound of its distance: with q its nearest point on Σ, |E(p)| = |E(p) − E(q)| ≤
// max |∇E| · |p − q| on the segment, and |∇E(x)| = 2 sqrt(x²/a⁴ + y²/b⁴ + z²/c⁴) ≤ 2|x|/c² ≤
// 2(|p| + d)/c² there (c the least semi-axis), so |p − q| ≥ |E(p)| c² / (2(|p| + d)).
BOOST_AUTO_TEST_CASE(the_normalised_function_certifies_where_the_tube_of_E_reaches_the_box) {
  const CertifiedCatalogMesh m = mesh_and_certify("ellipsoid", DelMeshOptions{});
  const FlowCertificate& c = m.certificate;
  BOOST_TEST_REQUIRE(c.status == FlowCertificateStatus::certified, c.reason);
  BOOST_TEST((c.function == FlowFunction::normalized));
  BOOST_TEST(c.eta > 0);
  BOOST_TEST(c.reason_with_E.find("boundary of the box") != std::string::npos, c.reason_with_E);
  const double a2 = 2.25, b2 = 1, c2 = 0.5625;
  const auto distance_lower_bound = [&](const Point3& p, double d) {
    const double e = p.x() * p.x() / a2 + p.y() * p.y() / b2 + p.z() * p.z() / c2 - 1;
    return std::abs(e) * c2 / (2 * (norm(p) + d));
  };
  for (const Point3& p : m.points) BOOST_TEST(c.hausdorff_upper_bound >= distance_lower_bound(p, c.hausdorff_upper_bound));
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (std::size_t i : m.triangles[t]) {
      const double d = c.triangle_distance_bounds[t];
      BOOST_TEST(d >= distance_lower_bound(m.points[i], d));
    }
}

// The local bounds of flow_distance.h only tighten the theorem's ε/G, and a distance radius the
// triangles meet tightens them further; the bound stays above the sampled distance.
BOOST_AUTO_TEST_CASE(local_distance_bounds_tighten_the_hausdorff_bound) {
  const test::Soup m = test::icosphere(3);
  const FlowCertificate plain = certify(m, unit_sphere, sphere_box);
  BOOST_TEST_REQUIRE(plain.status == FlowCertificateStatus::certified, plain.reason);
  BOOST_TEST(plain.hausdorff_upper_bound <= plain.epsilon / plain.min_gradient * (1 + 1e-12));
  FlowCertificateOptions options;
  options.distance_radius = 2 * sampled_distance_to_unit_sphere(m);
  const FlowCertificate tight = certify_gradient_flow(m.points, m.triangles, Surface::parse(unit_sphere), sphere_box, options);
  BOOST_TEST_REQUIRE(tight.status == FlowCertificateStatus::certified, tight.reason);
  BOOST_TEST(tight.hausdorff_upper_bound <= plain.hausdorff_upper_bound);
  BOOST_TEST(tight.hausdorff_upper_bound <= options.distance_radius);
  BOOST_TEST(tight.hausdorff_upper_bound >= sampled_distance_to_unit_sphere(m));
}

// delmesh's default mesh of two_blobs: ∇E vanishes inside and between the blobs, close enough
// for E's tube to reach those points; the normalised function's tube (built from E's enclosures,
// tolerances::flow_normalized_box_rounds rounds of budget) certifies it.  Every triangle's bound
// is checked against a proved lower bound of the distance of its points to Σ: |∇E| ≤ L = 3.26
// everywhere (each Gaussian w exp(−4r²) has gradient 8wr exp(−4r²) ≤ 8w exp(−1/2)/(2√2) <
// 1.7156w, and the weights add up to 1.9), so d(x, Σ) ≥ |E(x)|/L.
BOOST_AUTO_TEST_CASE(delmesh_two_blobs_output_is_certified_by_the_normalised_function) {
  const CertifiedCatalogMesh m = mesh_and_certify("two_blobs", DelMeshOptions{});
  const FlowCertificate& c = m.certificate;
  BOOST_TEST_REQUIRE(c.status == FlowCertificateStatus::certified, c.reason);
  BOOST_TEST((c.function == FlowFunction::normalized));
  BOOST_TEST(c.reason_with_E.find("may vanish") != std::string::npos, c.reason_with_E);
  BOOST_TEST(c.mesh_components == 2u);
  BOOST_TEST(c.box_rounds >= 1u);
  BOOST_TEST(c.box_rounds <= tolerances::flow_normalized_box_rounds);
  const auto E = [](double x, double y, double z) {
    return 0.3 - std::exp(-4 * ((x + 0.75) * (x + 0.75) + y * y + z * z)) -
           0.9 * std::exp(-4 * ((x - 0.75) * (x - 0.75) + (y - 0.1) * (y - 0.1) + z * z));
  };
  const double L = 3.26;
  BOOST_TEST_REQUIRE(c.triangle_distance_bounds.size() == m.triangles.size());
  double farthest = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Point3 &a = m.points[m.triangles[t][0]], &b = m.points[m.triangles[t][1]], &d = m.points[m.triangles[t][2]];
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; i + j <= 8; ++j) {
        const double u = i / 8.0, v = j / 8.0, w = 1 - u - v;
        const double lower = std::abs(E(w * a.x() + u * b.x() + v * d.x(), w * a.y() + u * b.y() + v * d.y(),
                                         w * a.z() + u * b.z() + v * d.z())) / L;
        BOOST_TEST(c.triangle_distance_bounds[t] >= lower);
        farthest = std::max(farthest, lower);
      }
  }
  BOOST_TEST(c.hausdorff_upper_bound >= farthest);
  BOOST_TEST(c.hausdorff_upper_bound / m.box.diagonal() < 0.1);
}

// The chair and the tangle cube (delmesh's default meshes): a critical point of E lies in E's
// tube; the normalised function's tube proof needs more than one round of its budget, each
// leaving less of B unexplored, and certifies both.
BOOST_AUTO_TEST_CASE(delmesh_chair_and_tanglecube_outputs_are_certified_in_rounds, *boost::unit_test::label("slow")) {
  for (const std::string name : {"chair", "tanglecube"}) {
    const CertifiedCatalogMesh m = mesh_and_certify(name, DelMeshOptions{});
    const FlowCertificate& c = m.certificate;
    BOOST_TEST_REQUIRE(c.status == FlowCertificateStatus::certified, name << ": " << c.reason);
    BOOST_TEST((c.function == FlowFunction::normalized));
    BOOST_TEST(c.reason_with_E.find("may vanish") != std::string::npos, c.reason_with_E);
    BOOST_TEST(c.box_rounds >= 2u, name << ": " << c.box_rounds << " rounds");
    BOOST_TEST(c.hausdorff_upper_bound > 0);
  }
}

// delmesh's default mesh of near_sheets (two unit spheres 0.05 apart): its coarse triangles are
// chords up to 0.2 inside the spheres, so E's tube and F's tube ±ε′ reach the box, and F's tube
// also holds F's critical point in the gap.  Its vertices lie on Σ and its triangles inside, so
// the one-sided tube (wide inside, thin outside) certifies it.  The distance of a point to Σ is
// known exactly: min over the spheres of ||x − c| − 1|.
BOOST_AUTO_TEST_CASE(delmesh_near_sheets_output_is_certified_with_a_one_sided_tube) {
  const CertifiedCatalogMesh m = mesh_and_certify("near_sheets", DelMeshOptions{});
  const FlowCertificate& c = m.certificate;
  BOOST_TEST_REQUIRE(c.status == FlowCertificateStatus::certified, c.reason);
  BOOST_TEST((c.function == FlowFunction::normalized));
  BOOST_TEST(c.one_sided_tube);
  BOOST_TEST(c.reason_with_E.find("boundary of the box") != std::string::npos, c.reason_with_E);
  BOOST_TEST(c.tube_lower < 0);
  BOOST_TEST(c.tube_upper > 0);
  BOOST_TEST(c.tube_upper < 0.1 * -c.tube_lower);
  BOOST_TEST(c.mesh_components == 2u);
  const auto distance = [](double x, double y, double z) {
    const auto to = [&](double cx) { return std::abs(std::sqrt((x - cx) * (x - cx) + y * y + z * z) - 1); };
    return std::min(to(1.025), to(-1.025));
  };
  BOOST_TEST_REQUIRE(c.triangle_distance_bounds.size() == m.triangles.size());
  double farthest = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Point3 &a = m.points[m.triangles[t][0]], &b = m.points[m.triangles[t][1]], &d = m.points[m.triangles[t][2]];
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; i + j <= 8; ++j) {
        const double u = i / 8.0, v = j / 8.0, w = 1 - u - v;
        const double at = distance(w * a.x() + u * b.x() + v * d.x(), w * a.y() + u * b.y() + v * d.y(),
                                   w * a.z() + u * b.z() + v * d.z());
        BOOST_TEST(c.triangle_distance_bounds[t] >= at);
        farthest = std::max(farthest, at);
      }
  }
  BOOST_TEST(c.hausdorff_upper_bound >= farthest);
}

BOOST_AUTO_TEST_SUITE_END()
