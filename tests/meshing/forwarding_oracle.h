#pragma once
// A SurfaceOracle that answers every question by asking another one: tests derive from it and
// override the one answer they alter (a solve cut short, a tangency reported), to drive the checks
// and the driver down paths the real solvers take only on hard inputs.
#include <optional>
#include <string>
#include <vector>

#include "meshing/core/surface_oracle.h"

namespace delmesh::test {

class ForwardingOracle : public SurfaceOracle {
 public:
  explicit ForwardingOracle(SurfaceOracle& inner) : inner_(inner) {}
  void set_run_controls(std::uint64_t seed, std::optional<std::chrono::steady_clock::time_point> deadline) override {
    inner_.set_run_controls(seed, deadline);
  }
  const Box3& box() const override { return inner_.box(); }
  const Box3& clip_box() const override { return inner_.clip_box(); }
  SolveResult surface_line(const Vec3& p, const Vec3& v, double t0, double t1) override {
    return inner_.surface_line(p, v, t0, t1);
  }
  SolveResult surface_critical(const Vec3& d, const Domain& domain, std::size_t box_budget) override {
    return inner_.surface_critical(d, domain, box_budget);
  }
  SolveResult surface_plane_contact(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) override {
    return inner_.surface_plane_contact(o, a, b, domain);
  }
  SolveResult curve_critical(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) override {
    return inner_.curve_critical(o, a, b, domain);
  }
  SolveResult silhouette_plane(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d,
                               const Domain& domain) override {
    return inner_.silhouette_plane(o, a, b, d, domain);
  }
  SolveResult silhouette_critical(const Vec3& d, const Vec3& d2, const Domain& domain) override {
    return inner_.silhouette_critical(d, d2, domain);
  }
  SolveResult solve(const std::string& primitive, const std::vector<double>& parameters, const Domain& domain,
                    std::size_t box_budget) override {
    return inner_.solve(primitive, parameters, domain, box_budget);
  }
  ConeAnswer prove_gradient_cone(const AffineChart& chart, const Domain& domain, const Vec3& w) override {
    return inner_.prove_gradient_cone(chart, domain, w);
  }
  ConeAnswer gradient_cone_slope(const AffineChart& chart, const Domain& domain, const Vec3& w,
                                 double target) override {
    return inner_.gradient_cone_slope(chart, domain, w, target);
  }
  bool bounds_cone_slopes() const override { return inner_.bounds_cone_slopes(); }
  int gradient_sign(const Vec3& a, const Vec3& b, const Vec3& w) const override {
    return inner_.gradient_sign(a, b, w);
  }
  using SurfaceOracle::value_sign;
  int value_sign(const Vec3& lo, const Vec3& hi) const override { return inner_.value_sign(lo, hi); }
  Vec3 gradient(const Vec3& x) const override { return inner_.gradient(x); }
  Vec3 normal(const Vec3& x) const override { return inner_.normal(x); }
  std::optional<Vec3> project(const Vec3& x) const override { return inner_.project(x); }
  bool gave_uncertified_answers() const override { return inner_.gave_uncertified_answers(); }
  nlohmann::json statistics_json() const override { return inner_.statistics_json(); }

 private:
  SurfaceOracle& inner_;
};

}  // namespace delmesh::test
