#pragma once
//! \file theorem_bounds.h
//! The functions α, β of §2.3 and the bounds of Theorem 6.1 for a given λ.

namespace delmesh {

//! α(λ) = λ / (1 − 3λ).  Precondition: 0 < λ < 1/3.
double alpha(double lambda);
//! β(λ) = α(2λ) + arcsin λ + arcsin(2 sin(2 arcsin λ) / √3).  Precondition: 0 < λ < 1/6.
double beta(double lambda);

struct TheoremBounds {
  double min_angle_deg;        //!< arcsin(1 / (2 + 2λ)), Theorem 6.1(ii) via Quality
  double max_radius_edge_ratio;//!< 1 + λ
  double max_roughness_rad;    //!< 2 β(λ)
};
//! Bounds of Theorem 6.1 for λ (valid for 0 < λ ≤ 0.06; computed for any 0 < λ < 1/6).
TheoremBounds theorem_bounds(double lambda);

}  // namespace delmesh
