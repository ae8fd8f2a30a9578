// Tests of the gradient-cone certificate (solvers/gradient_cone.h) on the unit sphere, where
// ⟨∇E(x), w⟩ = 2⟨x, w⟩: it vanishes on Σ exactly along the great circle ⟂ w.
#include "solvers/gradient_cone.h"

#include <cmath>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "symbolic/surface.h"

using namespace delmesh;

namespace {

CompiledSystem unit_sphere() {
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  return CompiledSystem({x * x + y * y + z * z - 1}, {x, y, z}, {});
}

Domain cube(double lo0, double hi0, double lo1, double hi1, double lo2, double hi2) {
  return Domain::from_box({{lo0, hi0}, {lo1, hi1}, {lo2, hi2}});
}

}  // namespace

BOOST_AUTO_TEST_SUITE(gradient_cone)

BOOST_AUTO_TEST_CASE(cap_away_from_the_silhouette_is_proved) {
  // Σ ∩ {z ≥ 0.5} is a cap where ⟨∇E, e_z⟩ = 2z ≥ 1.
  const auto E = unit_sphere();
  const auto r = prove_gradient_cone(E, AffineChart::identity(), cube(-1.5, 1.5, -1.5, 1.5, 0.5, 1.5), {0, 0, 1}, 200);
  BOOST_TEST(r.proved);
  BOOST_TEST(r.boxes >= 1u);
}

BOOST_AUTO_TEST_CASE(a_domain_meeting_the_silhouette_is_never_proved) {
  // The equator z = 0 is in J_{e_z} and in the domain: no budget may prove the certificate.
  const auto E = unit_sphere();
  for (std::size_t budget : {10u, 1000u, 100000u})
    BOOST_TEST(!prove_gradient_cone(E, AffineChart::identity(), cube(0.5, 1.5, -0.5, 0.5, -0.2, 0.2), {0, 0, 1}, budget)
                    .proved);
}

BOOST_AUTO_TEST_CASE(half_spaces_cut_the_domain) {
  // The box meets the equator, but the half-space z ≥ 0.3 (−z ≤ −0.3) keeps only a cap.
  const auto E = unit_sphere();
  Domain d = cube(-1.5, 1.5, -1.5, 1.5, -1.5, 1.5);
  d.half_spaces.push_back(HalfSpace{{0, 0, -1}, -0.3});
  BOOST_TEST(prove_gradient_cone(E, AffineChart::identity(), d, {0, 0, 1}, 2000).proved);
  d.half_spaces.back().offset = 0.1;  // z ≥ −0.1 reaches the equator
  BOOST_TEST(!prove_gradient_cone(E, AffineChart::identity(), d, {0, 0, 1}, 2000).proved);
}

BOOST_AUTO_TEST_CASE(a_domain_missing_the_surface_is_proved_for_any_direction) {
  const auto E = unit_sphere();
  const auto r = prove_gradient_cone(E, AffineChart::identity(), cube(-0.3, 0.3, -0.3, 0.3, -0.3, 0.3), {1, 0, 0}, 50);
  BOOST_TEST(r.proved);
}

BOOST_AUTO_TEST_CASE(the_surface_box_holds_the_section_and_is_empty_off_the_surface) {
  // The cap Σ ∩ {z ≥ 0.5} = {x² + y² ≤ 0.75, z = √(1 − x² − y²)}: its box is [−√0.75, √0.75]² ×
  // [0.5, 1], which the proof's box must hold, inside the domain's box.
  const auto E = unit_sphere();
  const auto r = prove_gradient_cone(E, AffineChart::identity(), cube(-1.5, 1.5, -1.5, 1.5, 0.5, 1.5), {0, 0, 1}, 2000);
  BOOST_REQUIRE(r.proved);
  const double rim = std::sqrt(0.75);
  for (int i = 0; i <= 64; ++i)
    for (int j = 0; j <= 64; ++j) {
      const double x = -rim + 2 * rim * i / 64, y = -rim + 2 * rim * j / 64;
      if (x * x + y * y > 0.75) continue;
      const double p[3] = {x, y, std::sqrt(1 - x * x - y * y)};
      for (int k = 0; k < 3; ++k) BOOST_TEST((r.surface_lo[k] <= p[k] && p[k] <= r.surface_hi[k]));
    }
  BOOST_TEST(r.surface_lo[2] >= 0.5);
  BOOST_TEST(r.surface_hi[2] <= 1.5);
  // A proof that Σ misses the domain leaves the box empty.
  const auto inside = prove_gradient_cone(E, AffineChart::identity(), cube(-0.3, 0.3, -0.3, 0.3, -0.3, 0.3), {1, 0, 0}, 50);
  BOOST_REQUIRE(inside.proved);
  for (int k = 0; k < 3; ++k) BOOST_TEST(inside.surface_lo[k] > inside.surface_hi[k]);
}

BOOST_AUTO_TEST_CASE(planar_chart_section_of_a_facet) {
  // The plane z = 0.2 in the frame (e_x, e_y): Σ ∩ Π is the circle of radius √0.96, whose tangent
  // t = ∇E × e_z is orthogonal to ∇E's in-plane part.  With w = e_x the functional is 2x: zero on
  // the circle at x = 0, so the square around (0, ±0.98) is not proved, the one at x ∈ [0.5, 1.2]
  // is.
  const auto E = unit_sphere();
  AffineChart chart;
  chart.origin = {0, 0, 0.2};
  chart.columns = {{1, 0, 0}, {0, 1, 0}};
  BOOST_TEST(prove_gradient_cone(E, chart, Domain::from_box({{0.5, 1.2}, {-0.5, 0.5}}), {1, 0, 0}, 500).proved);
  BOOST_TEST(!prove_gradient_cone(E, chart, Domain::from_box({{-0.2, 0.2}, {0.8, 1.2}}), {1, 0, 0}, 500).proved);
}

BOOST_AUTO_TEST_CASE(hessians_decide_boxes_the_natural_form_cannot) {
  // The torus E = (|x|² + R² − r²)² − 4R²(x² + y²), R = 1, r = 0.4, and w = (0.3, 0.2, 0.93): over
  // the slab z ∈ [0.2, 0.5] (the top of the tube, whose normals lean less than 60° from e_z) the
  // functional ⟨∇E, w⟩ keeps its sign on Σ.  Both forms prove it; the functional's mean-value
  // form (E compiled with Hessians) needs fewer boxes.  A slab through the equator z = 0, where
  // ⟨∇E, w⟩ vanishes on Σ (at four points of the two equator circles), is never proved.
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  const GiNaC::ex s = x * x + y * y + z * z + GiNaC::numeric(84, 100);
  const GiNaC::ex torus = s * s - 4 * (x * x + y * y);
  const CompiledSystem natural({torus}, {x, y, z}, {});
  const CompiledSystem centred({torus}, {x, y, z}, {}, true);
  const std::array<double, 3> w{0.3, 0.2, 0.93};
  const Domain top = cube(-1.5, 1.5, -1.5, 1.5, 0.2, 0.5);
  const auto without = prove_gradient_cone(natural, AffineChart::identity(), top, w, 100000);
  const auto with = prove_gradient_cone(centred, AffineChart::identity(), top, w, 100000);
  BOOST_TEST(without.proved);
  BOOST_TEST(with.proved);
  BOOST_TEST(with.boxes < without.boxes);
  const Domain across = cube(-1.5, 1.5, -1.5, 1.5, -0.1, 0.5);
  for (const CompiledSystem* E : {&natural, &centred})
    BOOST_TEST(!prove_gradient_cone(*E, AffineChart::identity(), across, w, 20000).proved);
}

BOOST_AUTO_TEST_CASE(the_slope_bounds_the_angle_to_w_from_below) {
  // On the cap Σ ∩ {|x|, |y| ≤ 0.3, z ≥ 0.5} of the unit sphere, ⟨∇E, e_z⟩ / |∇E| = z, whose
  // least value is √(1 − 2·0.3²) = √0.82 at the corners: every proved slope is a lower bound of
  // it, and refining the cover towards a target raises the slope past the target without
  // turning the proof into a failure (the refining boxes do not use the cover's budget).
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  const CompiledSystem E({x * x + y * y + z * z - 1}, {x, y, z}, {}, true);
  const Domain cap = cube(-0.3, 0.3, -0.3, 0.3, 0.5, 1.1);
  const double least = std::sqrt(0.82);
  const auto plain = prove_gradient_cone(E, AffineChart::identity(), cap, {0, 0, 1}, 200);
  BOOST_TEST(plain.proved);
  BOOST_TEST(plain.slope == 0.0);  // no slope asked for
  const auto coarse = prove_gradient_cone(E, AffineChart::identity(), cap, {0, 0, 1}, 200, {1e-300, 0});
  BOOST_TEST(coarse.proved);
  BOOST_TEST(coarse.slope > 0.0);
  BOOST_TEST(coarse.slope <= least);
  const auto refined = prove_gradient_cone(E, AffineChart::identity(), cap, {0, 0, 1}, coarse.boxes, {0.88, 100000});
  BOOST_TEST(refined.proved);
  BOOST_TEST(refined.slope >= 0.88);
  BOOST_TEST(refined.slope <= least);
  // A slope can never exceed the true one, however much is spent.
  const auto beyond = prove_gradient_cone(E, AffineChart::identity(), cap, {0, 0, 1}, coarse.boxes, {0.95, 20000});
  BOOST_TEST(beyond.proved);
  BOOST_TEST(beyond.slope <= least);
  // A domain that misses Σ has slope +∞: nothing is left to bound.
  const auto empty = prove_gradient_cone(E, AffineChart::identity(), cube(-0.3, 0.3, -0.3, 0.3, -0.3, 0.3), {1, 0, 0},
                                         50, {0.5, 100});
  BOOST_TEST(empty.proved);
  BOOST_TEST(std::isinf(empty.slope));
}

BOOST_AUTO_TEST_CASE(the_slope_bounds_a_direction_not_a_magnitude) {
  // On Σ = {(1 + x² + y²) z = 0} ∩ P, P = [−1, 1]² × [−0.05, 0.05], ∇E = (0, 0, 1 + x² + y²):
  // its direction is e_z everywhere and its length runs from 1 to 3.  The whole of P is one box
  // that (iii) drops (⟨∇E, e_z⟩ ∈ [1, 3] on it), where ∇E × e_z = (∂E/∂y, −∂E/∂x, 0) lies in
  // [−0.1, 0.1]²: the slope is at least 1/√1.02 > 0.99 without a single refining box, where
  // min ⟨∇E, e_z⟩ / max |∇E| would give 1/3 or less.  It never exceeds the true slope 1.
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  const CompiledSystem E({(1 + x * x + y * y) * z}, {x, y, z}, {}, true);
  const auto r = prove_gradient_cone(E, AffineChart::identity(), cube(-1, 1, -1, 1, -0.05, 0.05), {0, 0, 1}, 10, {0.9, 0});
  BOOST_TEST(r.proved);
  BOOST_TEST(r.boxes == 1u);
  BOOST_TEST(r.slope > 0.99);
  BOOST_TEST(r.slope <= 1.0);
  // Tilted away from ∇E by the angle θ with cos θ = 0.8, the slope is at most 0.8, and refining
  // brings it close.
  const auto tilted = prove_gradient_cone(E, AffineChart::identity(), cube(-1, 1, -1, 1, -0.05, 0.05), {0.6, 0, 0.8},
                                          10, {0.75, 20000});
  BOOST_TEST(tilted.proved);
  BOOST_TEST(tilted.slope >= 0.75);
  BOOST_TEST(tilted.slope <= 0.8);
}

BOOST_AUTO_TEST_CASE(a_proved_zero_of_the_functional_refutes_the_certificate) {
  // With Hessians, a box inside P around a point of the equator z = 0 (where ⟨∇E, e_z⟩ = 2z
  // vanishes on the sphere) gets a Krawczyk proof of that zero: the attempt stops, refuted, long
  // before its budget.  Without Hessians it cannot refute, and drills towards the equator until a
  // box no longer splits; on the cap it proves and is not refuted.
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  const CompiledSystem E({x * x + y * y + z * z - 1}, {x, y, z}, {}, true);
  const Domain across = cube(0.5, 1.5, -0.5, 0.5, -0.2, 0.2);
  const auto refuted = prove_gradient_cone(E, AffineChart::identity(), across, {0, 0, 1}, 100000);
  BOOST_TEST(!refuted.proved);
  BOOST_TEST(refuted.refuted());
  BOOST_TEST(refuted.boxes < 200u);
  // The refuting point, narrowed to the rounding: on the equator of the sphere, inside P.
  BOOST_TEST_REQUIRE(refuted.vanishing_point.has_value());
  const auto& v = *refuted.vanishing_point;
  BOOST_TEST(std::abs(v[2]) < 1e-14);
  BOOST_TEST(std::abs(v[0] * v[0] + v[1] * v[1] - 1) < 1e-14);
  BOOST_TEST((v[0] >= 0.5 && std::abs(v[1]) <= 0.5));
  const auto spent = prove_gradient_cone(unit_sphere(), AffineChart::identity(), across, {0, 0, 1}, 1000);
  BOOST_TEST(!spent.proved);
  BOOST_TEST(!spent.refuted());
  BOOST_TEST(!spent.vanishing_point.has_value());
  BOOST_TEST(spent.boxes > 4 * refuted.boxes);
  const Domain upper = cube(-1.5, 1.5, -1.5, 1.5, 0.5, 1.5);
  const auto cap = prove_gradient_cone(E, AffineChart::identity(), upper, {0, 0, 1}, 200);
  BOOST_TEST(cap.proved);
  BOOST_TEST(!cap.refuted());
  // In a facet's plane chart (dimension 2, no slice): the circle of Σ ∩ {z = 0.2} crosses x = 0,
  // where the functional 2x vanishes, inside the square around (0, 0.98).
  AffineChart chart;
  chart.origin = {0, 0, 0.2};
  chart.columns = {{1, 0, 0}, {0, 1, 0}};
  const auto planar = prove_gradient_cone(E, chart, Domain::from_box({{-0.2, 0.2}, {0.8, 1.2}}), {1, 0, 0}, 100000);
  BOOST_TEST(planar.refuted());
  BOOST_TEST(planar.boxes < 200u);
  BOOST_TEST_REQUIRE(planar.vanishing_point.has_value());
  BOOST_TEST(std::abs((*planar.vanishing_point)[0]) < 1e-14);
  BOOST_TEST(std::abs((*planar.vanishing_point)[1] - std::sqrt(0.96)) < 1e-14);
  BOOST_TEST((*planar.vanishing_point)[2] == 0.2);
  // A zero just outside the half-space that bounds P (z ≥ 0.01) refutes nothing: the cover of
  // the part above it is proved.
  Domain above = across;
  above.half_spaces.push_back(HalfSpace{{0, 0, -1}, -0.01});
  const auto cut = prove_gradient_cone(E, AffineChart::identity(), above, {0, 0, 1}, 100000);
  BOOST_TEST(cut.proved);
  BOOST_TEST(!cut.refuted());
}

BOOST_AUTO_TEST_CASE(misuse_throws) {
  const auto E = unit_sphere();
  AffineChart chart;
  chart.columns = {{1, 0, 0}};
  BOOST_CHECK_THROW(prove_gradient_cone(E, chart, cube(-1, 1, -1, 1, -1, 1), {0, 0, 1}, 10), PreconditionViolation);
}

BOOST_AUTO_TEST_SUITE_END()
