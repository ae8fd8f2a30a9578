#include "meshing/core/theorem_bounds.h"

#include <cmath>
#include <string>

#include <boost/math/constants/constants.hpp>

#include "common/errors.h"

namespace delmesh {
namespace {

constexpr double pi = boost::math::constants::pi<double>();

void require_open_interval(double lambda, double upper, const char* what, const char* upper_text) {
  if (!(lambda > 0.0 && lambda < upper)) {
    throw PreconditionViolation(std::string(what) + ": requires 0 < lambda < " + upper_text +
                                ", got " + std::to_string(lambda));
  }
}

}  // namespace

double alpha(double lambda) {
  require_open_interval(lambda, alpha_lambda_bound, "alpha", "1/3");
  return lambda / (1.0 - 3.0 * lambda);
}

double beta(double lambda) {
  require_open_interval(lambda, beta_lambda_bound, "beta", "1/6");
  const double two_over_root3 = 2.0 / std::sqrt(3.0);
  return alpha(2.0 * lambda) + std::asin(lambda) +
         std::asin(two_over_root3 * std::sin(2.0 * std::asin(lambda)));
}

std::ostream& operator<<(std::ostream& out, const TheoremBounds& bounds) {
  return out << "{min_angle_deg " << bounds.min_angle_deg << ", max_radius_edge_ratio "
             << bounds.max_radius_edge_ratio << ", max_roughness_rad " << bounds.max_roughness_rad
             << "}";
}

TheoremBounds theorem_bounds(double lambda) {
  require_open_interval(lambda, beta_lambda_bound, "theorem_bounds", "1/6");
  TheoremBounds bounds{};
  bounds.min_angle_deg = std::asin(1.0 / (2.0 + 2.0 * lambda)) * 180.0 / pi;
  bounds.max_radius_edge_ratio = 1.0 + lambda;
  bounds.max_roughness_rad = 2.0 * beta(lambda);
  return bounds;
}

TheoremConditions theorem_conditions(double lambda) {
  require_open_interval(lambda, beta_lambda_bound, "theorem_conditions", "1/6");
  const double a = alpha(lambda);
  const double b = beta(lambda);
  TheoremConditions conditions;
  conditions.distance_cosine = lambda / (1.0 - lambda) < std::cos(a + 3.0 * b);
  conditions.angle_below_60deg = a + b < pi / 3.0;
  conditions.arccos_bound = std::acos(lambda) > a + b;
  return conditions;
}

bool theorem_conditions_hold(double lambda) { return theorem_conditions(lambda).all(); }

}  // namespace delmesh
