#include "meshing/inputs/detail/flow_enclosure.h"

#include <cmath>
#include <random>
#include <string>

#include <boost/test/unit_test.hpp>

#include <ginac/ginac.h>

#include "symbolic/surface.h"

using namespace delmesh;
using namespace delmesh::detail;

namespace {

//! E of `equation` and F = E / sqrt(|∇E|² + η²), F with its own symbolic gradient (Surface's,
//! independent of the composed enclosure's formulas).
struct Normalized {
  Surface E;
  CompiledSystem system_of_E;
  CompiledSystem system_of_F;
  double eta;
};

Normalized normalized(const std::string& equation, double eta) {
  const Surface E = Surface::parse(equation);
  GiNaC::ex squared = GiNaC::numeric(0);
  for (const GiNaC::ex& g : E.gradient()) squared += GiNaC::pow(g, 2);
  // As the certificate builds it (Surface takes η's double as the rational it is).
  const Surface F(E.E() * GiNaC::pow(squared + GiNaC::numeric(eta) * GiNaC::numeric(eta), GiNaC::numeric(-1, 2)));
  BOOST_TEST_REQUIRE(F.normalization_exponent() == 0);
  return {E, compile_value_and_gradient(E.E(), E.gradient()), compile_value_and_gradient(F.E(), F.gradient()), eta};
}

//! Whether v lies in a up to a relative slack for the rounding of the double evaluation.
bool inside(double v, const Interval& a) {
  const double slack = 1e-9 * (1 + std::abs(v));
  return a.inf() - slack <= v && v <= a.sup() + slack;
}

//! On random boxes (widths 1e-3 to 1) around random points of `box`, the composed enclosures hold
//! F, ⟨∇F, w⟩ and F(c) at random points x of the box, and the gradient bound is below |∇F(x)|.
void check_enclosures(const std::string& equation, double eta, const Box3& box) {
  const Normalized n = normalized(equation, eta);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  int usable = 0;
  for (int trial = 0; trial < 300; ++trial) {
    P3 centre;
    for (int k = 0; k < 3; ++k) centre[k] = box.lo[k] + unit(random) * (box.hi[k] - box.lo[k]);
    const double width = std::pow(10.0, -3 * unit(random));
    IBox x;
    for (int k = 0; k < 3; ++k) x[k] = Interval(centre[k] - width * unit(random), centre[k] + width * unit(random));
    P3 w;
    for (double& a : w) a = 2 * unit(random) - 1;
    Interval value, at_centre, directional;
    double bound = 0;
    bool ok = false;
    {
      RoundingGuard guard;
      const NormalizedEnclosure en(n.system_of_E, x, n.eta);
      ok = en.usable;
      value = en.value();
      at_centre = en.value_at_centre();
      directional = en.directional(interval_point(w));
      P3 c = en.e.c;
      double v[4];
      n.system_of_F.values<double>(c.data(), nullptr, v);
      BOOST_TEST(inside(v[0], at_centre), "F(c) = " << v[0] << " outside [" << at_centre.inf() << ", " << at_centre.sup() << "]");
      bound = gradient_lower_bound(en, en.centre_gradient(n.system_of_E));
    }
    if (!ok) continue;
    ++usable;
    for (int sample = 0; sample < 20; ++sample) {
      P3 p;
      for (int k = 0; k < 3; ++k) p[k] = x[k].inf() + unit(random) * (x[k].sup() - x[k].inf());
      double v[4];
      n.system_of_F.values<double>(p.data(), nullptr, v);
      const double along = v[1] * w[0] + v[2] * w[1] + v[3] * w[2];
      const double length = std::sqrt(v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
      BOOST_TEST(inside(v[0], value), "F = " << v[0] << " outside [" << value.inf() << ", " << value.sup() << "]");
      BOOST_TEST(inside(along, directional),
                 "<grad F, w> = " << along << " outside [" << directional.inf() << ", " << directional.sup() << "]");
      BOOST_TEST(bound <= length * (1 + 1e-9), "bound " << bound << " above |grad F| = " << length);
    }
  }
  BOOST_TEST(usable > 200);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(flow_enclosure)

// The composed enclosures of the normalised function against its own symbolic derivatives, on a
// polynomial (the chair quartic, whose E has critical points near its surface) and on a sum of
// Gaussians (two_blobs).
BOOST_AUTO_TEST_CASE(the_composed_enclosures_of_the_normalised_function_hold_its_values) {
  check_enclosures("(x^2+y^2+z^2-0.95)^2-0.8*((z-1)^2-2*x^2)*((z+1)^2-2*y^2)", 0.04, Box3::cube(1.6));
  check_enclosures("0.3-exp(-4*((x+0.75)^2+y^2+z^2))-0.9*exp(-4*((x-0.75)^2+(y-0.1)^2+z^2))", 0.12,
                   Box3{{-1.75, -1.1, -1}, {1.75, 1.2, 1}});
}

// A lower bound is proved on a small box away from the critical points of F, and it is close to
// |∇F| there (the composed forms are not loose on small boxes).
BOOST_AUTO_TEST_CASE(the_composed_gradient_bound_is_tight_on_a_small_box) {
  const Normalized n = normalized("x^2+y^2+z^2-1", 0.2);
  RoundingGuard guard;
  const IBox x{Interval(0.99, 1.01), Interval(-0.01, 0.01), Interval(-0.01, 0.01)};
  const NormalizedEnclosure en(n.system_of_E, x, n.eta);
  BOOST_TEST_REQUIRE(en.usable);
  // At (1, 0, 0): ∇E = (2, 0, 0), E = 0, so ∇F = (2/sqrt(4 + η²), 0, 0).
  const double expected = 2 / std::sqrt(4 + 0.04);
  const double bound = gradient_lower_bound(en, en.centre_gradient(n.system_of_E));
  BOOST_TEST(bound > 0.9 * expected);
  BOOST_TEST(bound <= expected * (1 + 1e-9));  // the least |∇F| on the box is at most its value at the centre
}

BOOST_AUTO_TEST_SUITE_END()
