#pragma once
//! \file theorem_bounds.h
//! The functions α, β of §2.3, the three inequalities of §4 that fix λ₀ = 0.06, and the bounds of
//! Theorem 6.1 for a given λ.

#include <ostream>

namespace delmesh {

//! λ₀ = 0.06: the guarantees of Theorem 6.1 hold for 0 < λ ≤ λ₀ (the inequalities of §4 hold there).
inline constexpr double lambda0 = 0.06;
//! α(λ) is defined for 0 < λ < 1/3; the mesher accepts these λ (without a guarantee above λ₀).
inline constexpr double alpha_lambda_bound = 1.0 / 3.0;
//! β(λ) is defined for 0 < λ < 1/6; Smooth and the bounds of Theorem 6.1 need it.
inline constexpr double beta_lambda_bound = 1.0 / 6.0;

//! α(λ) = λ / (1 − 3λ) (§2.3, Lemma 2.1).  Precondition: 0 < λ < 1/3, else PreconditionViolation.
double alpha(double lambda);
//! β(λ) = α(2λ) + arcsin λ + arcsin(2 sin(2 arcsin λ) / √3) (§2.3, Lemma 2.2).
//! Precondition: 0 < λ < 1/6 (so that α(2λ) is defined), else PreconditionViolation.
double beta(double lambda);

struct TheoremBounds {
  double min_angle_deg;        //!< arcsin(1 / (2 + 2λ)) in degrees: implied by radius-edge ratio ≤ 1+λ
  double max_radius_edge_ratio;//!< 1 + λ, Theorem 6.1(ii) via Quality
  double max_roughness_rad;    //!< 2 β(λ), Theorem 6.1(ii) via Smooth
};
std::ostream& operator<<(std::ostream& out, const TheoremBounds& bounds);

//! Bounds of Theorem 6.1 for λ (valid for 0 < λ ≤ 0.06; computed for any 0 < λ < 1/6).
//! Precondition: 0 < λ < 1/6, else PreconditionViolation.
TheoremBounds theorem_bounds(double lambda);

//! The three inequalities of §4 that the proofs of §§4–6 assume for λ ≤ λ₀ = 0.06:
//!   (1) λ / (1 − λ) < cos(α(λ) + 3β(λ))   (Lemmas 4.6, 4.9)
//!   (2) α(λ) + β(λ) < π/3                  (Lemmas 4.3–4.5)
//!   (3) arccos λ > α(λ) + β(λ)
struct TheoremConditions {
  bool distance_cosine = false;   //!< inequality (1)
  bool angle_below_60deg = false; //!< inequality (2)
  bool arccos_bound = false;      //!< inequality (3)
  bool all() const { return distance_cosine && angle_below_60deg && arccos_bound; }
};
//! Evaluates the three inequalities in double precision.  Precondition: 0 < λ < 1/6.
//! They hold on (0, λ*) with λ* ≈ 0.06956 (inequality (1) is the first to fail), so the paper's
//! λ₀ = 0.06 leaves a margin.
TheoremConditions theorem_conditions(double lambda);
//! theorem_conditions(lambda).all().
bool theorem_conditions_hold(double lambda);

}  // namespace delmesh
