// Tests of the limits of meshing/driver/refinement.h outside Refinement::run(): the records computed
// when Del S changes everywhere (queue_everything_within) and the seed insertion stop once the
// deadline has passed or the interrupt flag is set.
#include <boost/test/unit_test.hpp>

#include <atomic>
#include <chrono>

#include "meshing/driver/refinement.h"
#include "meshing/driver/sample_topology.h"
#include "meshing/inputs/implicit_oracle.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

// An oracle that counts the calls it passes on to `inner`.
class CountingOracle final : public SurfaceOracle {
 public:
  explicit CountingOracle(SurfaceOracle& inner) : inner_(inner) {}
  std::size_t calls() const { return calls_; }

  void set_run_controls(std::uint64_t seed, std::optional<std::chrono::steady_clock::time_point> deadline) override {
    inner_.set_run_controls(seed, deadline);
  }
  const Box3& box() const override { return inner_.box(); }
  const Box3& clip_box() const override { return inner_.clip_box(); }
  SolveResult surface_line(const Vec3& p, const Vec3& v, double t0, double t1) override {
    ++calls_;
    return inner_.surface_line(p, v, t0, t1);
  }
  SolveResult surface_critical(const Vec3& d, const Domain& domain, std::size_t box_budget) override {
    ++calls_;
    return inner_.surface_critical(d, domain, box_budget);
  }
  SolveResult surface_plane_contact(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) override {
    ++calls_;
    return inner_.surface_plane_contact(o, a, b, domain);
  }
  SolveResult curve_critical(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) override {
    ++calls_;
    return inner_.curve_critical(o, a, b, domain);
  }
  SolveResult silhouette_plane(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d,
                               const Domain& domain) override {
    ++calls_;
    return inner_.silhouette_plane(o, a, b, d, domain);
  }
  SolveResult silhouette_critical(const Vec3& d, const Vec3& d2, const Domain& domain) override {
    ++calls_;
    return inner_.silhouette_critical(d, d2, domain);
  }
  SolveResult solve(const std::string& primitive, const std::vector<double>& parameters, const Domain& domain,
                    std::size_t box_budget) override {
    ++calls_;
    return inner_.solve(primitive, parameters, domain, box_budget);
  }
  ConeAnswer prove_gradient_cone(const AffineChart& chart, const Domain& domain, const Vec3& w) override {
    ++calls_;
    return inner_.prove_gradient_cone(chart, domain, w);
  }
  ConeAnswer gradient_cone_slope(const AffineChart& chart, const Domain& domain, const Vec3& w,
                                 double target) override {
    ++calls_;
    return inner_.gradient_cone_slope(chart, domain, w, target);
  }
  bool bounds_cone_slopes() const override { return inner_.bounds_cone_slopes(); }
  int gradient_sign(const Vec3& a, const Vec3& b, const Vec3& w) const override {
    ++calls_;
    return inner_.gradient_sign(a, b, w);
  }
  int value_sign(const Vec3& lo, const Vec3& hi) const override {
    ++calls_;
    return inner_.value_sign(lo, hi);
  }
  Vec3 gradient(const Vec3& x) const override { return inner_.gradient(x); }
  Vec3 normal(const Vec3& x) const override { return inner_.normal(x); }
  std::optional<Vec3> project(const Vec3& x) const override { return inner_.project(x); }
  nlohmann::json statistics_json() const override { return inner_.statistics_json(); }

 private:
  SurfaceOracle& inner_;
  mutable std::size_t calls_ = 0;
};

// Inserts four points of the unit sphere, in general position: each insertion changes Del S
// everywhere (its dimension grows), so each queues every face and computes every record.
// Returns the oracle calls the insertions made.
std::size_t calls_of_four_insertions(const RefinementLimits& limits) {
  const auto& entry = catalog_entry("sphere");
  ImplicitOracle inner(entry.surface(), entry.box, SolverBackend::subdivision);
  CountingOracle oracle(inner);
  Refinement refinement(oracle, 1, limits);
  const double a = 1 / std::sqrt(3.0);
  for (const Vec3& p : {Vec3{a, a, a}, Vec3{a, -a, -a}, Vec3{-a, a, -a}, Vec3{-a, -a, a}})
    BOOST_TEST(refinement.insert(Witness{p, CheckKind::seed, -1, false}).has_value());
  return oracle.calls();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(refinement_limits)

BOOST_AUTO_TEST_CASE(a_passed_deadline_stops_the_records_of_a_global_change) {
  const std::size_t free_calls = calls_of_four_insertions({});
  BOOST_TEST(free_calls > 0u);
  RefinementLimits passed;
  passed.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  BOOST_TEST(calls_of_four_insertions(passed) == 0u);
}

BOOST_AUTO_TEST_CASE(the_interrupt_flag_stops_the_records_and_the_run) {
  std::atomic<bool> flag{true};
  RefinementLimits interrupted;
  interrupted.interrupt = &flag;
  BOOST_TEST(calls_of_four_insertions(interrupted) == 0u);
}

BOOST_AUTO_TEST_CASE(a_passed_deadline_stops_seed_insertion_and_topology) {
  const auto& entry = catalog_entry("torus");
  ImplicitOracle oracle(entry.surface(), entry.box, SolverBackend::subdivision);
  std::atomic<bool> flag{true};
  RefinementLimits limits;
  limits.interrupt = &flag;
  Refinement refinement(oracle, 1, limits);
  BOOST_TEST(refinement.limit_passed());
  const SampleTopologyResult result = sample_topology(refinement);
  // The seed solve ran (it has its own deadline only), no seed was inserted, and the run says why.
  BOOST_TEST(result.seeds.seeds == 0u);
  BOOST_TEST(refinement.delaunay().size() == 0u);
  BOOST_TEST((result.status == MeshStatus::interrupted));
}

BOOST_AUTO_TEST_SUITE_END()
