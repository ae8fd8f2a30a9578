#include "meshing/inputs/implicit_oracle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/inputs/flow_distance.h"
#include "solvers/homotopy_solver.h"
#include "solvers/primitive_query.h"
#include "solvers/primitive_registry.h"
#include "solvers/query_geometry.h"
#include "solvers/subdivision_solver.h"
#include "solvers/surface_box.h"
#include "solvers/univariate_isolator.h"
#include "symbolic/compiled_system.h"
#include "symbolic/line_polynomial.h"

namespace delmesh {

using namespace detail;

namespace {

//! The registry index of a primitive the oracle has a method for.
std::size_t registry_index(const std::string& name) {
  const auto& registry = primitive_registry();
  for (std::size_t i = 0; i < registry.size(); ++i)
    if (registry[i].name == name) return i;
  throw PreconditionViolation("the primitive registry has no " + name + ", which the mesher uses");
}

}  // namespace

struct ImplicitOracle::Impl {
  Surface surface;
  std::vector<CompiledPrimitive> primitives;  // in registry order
  std::vector<std::vector<int>> degrees;      // for homotopy (square polynomial systems), else empty
  std::unique_ptr<LinePolynomial> line_polynomial;
  std::unique_ptr<CompiledSystem> gradient;  // E with its Jacobian ∇E and its Hessian
  std::mutex statistics_mutex;                 // statistics updates from concurrent calls
  std::once_flag distance_once;                // builds `distance` at the first flow_distance()
  std::unique_ptr<FlowDistance> distance;
  // The registry indices of the primitives with a method of their own.
  std::size_t surface_critical = registry_index("surface_critical"), surface_line = registry_index("surface_line"),
              surface_plane_contact = registry_index("surface_plane_contact"),
              curve_critical = registry_index("curve_critical"), silhouette_plane = registry_index("silhouette_plane"),
              silhouette_critical = registry_index("silhouette_critical");

  // The degrees cost a symbolic expansion of every system (minutes for a degree-12 E), so they
  // are computed only for the homotopy backend, the one that reads them.
  Impl(const Surface& s, bool with_degrees) : surface(s) {
    for (const PrimitiveInfo& row : primitive_registry()) {
      // The mesher's solves use TaylorForms::automatic: a form they would not use is not built.
      primitives.emplace_back(row.build(s), PolynomialFormBuild::if_it_pays);
      const PrimitiveSystem& sys = primitives.back().system;
      std::vector<int> deg;
      if (with_degrees && s.is_polynomial() && sys.is_square()) {
        try {
          deg = equation_degrees(sys);
        } catch (const InvalidInput&) {
          deg.clear();
        }
      }
      degrees.push_back(deg);
    }
    if (s.is_polynomial()) line_polynomial = std::make_unique<LinePolynomial>(s);
    const std::vector<GiNaC::symbol> xyz{coordinate_x(), coordinate_y(), coordinate_z()};
    gradient = std::make_unique<CompiledSystem>(std::vector<GiNaC::ex>{s.E()}, xyz, std::vector<GiNaC::symbol>{},
                                                true, PolynomialFormBuild::never);
  }
};

ImplicitOracle::ImplicitOracle(const Surface& surface, const Box3& box, SolverBackend backend)
    : impl_(std::make_unique<Impl>(surface, backend == SolverBackend::homotopy)),
      box_(box),
      backend_(backend),
      stats_(impl_->primitives.size()) {
  const SurfaceBox surface_box = surface_bounding_box(*impl_->gradient, box_);
  clip_box_ = surface_box.empty ? box_ : clip_box_around(surface_box.box, box_);
}
ImplicitOracle::~ImplicitOracle() = default;
ImplicitOracle::ImplicitOracle(ImplicitOracle&&) noexcept = default;
ImplicitOracle& ImplicitOracle::operator=(ImplicitOracle&&) noexcept = default;

const Surface& ImplicitOracle::surface() const { return impl_->surface; }

const FlowDistance* ImplicitOracle::flow_distance() const {
  std::call_once(impl_->distance_once, [this] { impl_->distance = std::make_unique<FlowDistance>(impl_->surface); });
  return impl_->distance.get();
}

void ImplicitOracle::set_run_controls(std::uint64_t seed, std::optional<std::chrono::steady_clock::time_point> deadline) {
  seed_ = seed;
  deadline_ = deadline;
}

double ImplicitOracle::seconds_left() const {
  if (!deadline_) return 0;
  const double left = std::chrono::duration<double>(*deadline_ - std::chrono::steady_clock::now()).count();
  return std::max(left, std::numeric_limits<double>::min());
}

void ImplicitOracle::count_fallback(std::size_t primitive) {
  if (backend_ != SolverBackend::homotopy) return;
  const std::lock_guard<std::mutex> lock(impl_->statistics_mutex);
  ++stats_[primitive].homotopy_fallbacks;
}

SolveResult ImplicitOracle::finish(std::size_t primitive, const std::vector<double>& parameters, SolveResult result,
                                  std::chrono::steady_clock::time_point start, std::optional<double> seconds) {
  // Only roots inside the domain count; the solver classifies them.
  result.roots.erase(std::remove_if(result.roots.begin(), result.roots.end(),
                                    [](const CertifiedRoot& r) { return !r.inside_domain; }),
                     result.roots.end());
  drop_spurious_roots(impl_->primitives[primitive], parameters, result);
  const std::lock_guard<std::mutex> lock(impl_->statistics_mutex);
  auto& s = stats_[primitive];
  ++s.calls;
  s.certified_roots += result.roots.size();
  s.undecided += result.undecided.size();
  s.boxes += result.counters.boxes;
  if (result.status == SolveStatus::time_limit) ++s.time_limited;
  s.seconds += seconds ? *seconds : std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

SolveResult ImplicitOracle::solve_square(std::size_t primitive, const std::vector<double>& parameters,
                                        const Domain& domain, std::size_t box_budget) {
  const std::size_t index = primitive;
  const auto& sys = impl_->primitives[index].compiled;
  if (backend_ == SolverBackend::homotopy && !impl_->degrees[index].empty()) {
    HomotopyOptions options;
    options.seed = seed_;
    options.deadline = deadline_;
    options.subdivision_budget_for_unproved = box_budget;
    HomotopySolveResult result = solve_homotopy(sys, impl_->degrees[index], parameters, domain, options);
    const std::lock_guard<std::mutex> lock(impl_->statistics_mutex);
    auto& s = stats_[index];
    s.homotopy_paths += result.counters.paths;
    s.homotopy_near_real += result.statistics.near_real;
    s.homotopy_diverging_near_domain += result.statistics.diverging_near_domain;
    ++(result.completeness_certified() ? s.homotopy_certified : s.homotopy_uncertified);
    s.homotopy_pieces_by_subdivision += result.statistics.pieces_by_subdivision;
    return std::move(result);  // the SolveResult part
  }
  count_fallback(primitive);
  SubdivisionOptions options;
  options.box_budget = box_budget;
  options.time_limit_seconds = seconds_left();
  SolveResult result = solve_subdivision(sys, parameters, domain, options);
  refine_singular_regions(sys, parameters, domain, result, options);
  return result;
}

SolveResult ImplicitOracle::solve_over_determined(std::size_t primitive, const std::vector<double>& parameters,
                                                 const Domain& domain, std::size_t box_budget) {
  SubdivisionOptions options;
  options.box_budget = box_budget;
  options.exclusion_mode = true;
  options.time_limit_seconds = seconds_left();
  count_fallback(primitive);
  return solve_subdivision(impl_->primitives[primitive].compiled, parameters, domain, options);
}

SolveResult ImplicitOracle::solve(const std::string& primitive, const std::vector<double>& parameters,
                                 const Domain& domain, std::size_t box_budget) {
  const auto start = std::chrono::steady_clock::now();
  const auto& registry = primitive_registry();
  const std::size_t index =
      static_cast<std::size_t>(&find_primitive(primitive) - registry.data());  // throws for unknown names
  const PrimitiveSystem& system = impl_->primitives[index].system;
  if (system.n_unknowns() == 1) throw PreconditionViolation("ImplicitOracle::solve: use surface_line() for " + primitive);
  if (parameters.size() != system.n_parameters()) {
    throw PreconditionViolation("ImplicitOracle::solve: " + std::to_string(parameters.size()) + " parameters given, " +
                                primitive + " has " + std::to_string(system.n_parameters()));
  }
  SolveResult result = system.is_square() ? solve_square(index, parameters, domain, box_budget)
                                          : solve_over_determined(index, parameters, domain, box_budget);
  return finish(index, parameters, std::move(result), start);
}

SolveResult ImplicitOracle::surface_line(const Vec3& p, const Vec3& v, double t0, double t1) {
  const auto start = std::chrono::steady_clock::now();
  UnivariateOptions options;
  options.box_budget = tolerances::mesher_box_budget_1d;
  options.time_limit_seconds = seconds_left();
  options.start = start;  // the isolator times the call from here: no second pair of readings
  const std::size_t index = impl_->surface_line;
  const CompiledPrimitive& primitive = impl_->primitives[index];
  auto r = isolate_line_roots(primitive.compiled, impl_->line_polynomial.get(), p, v, t0, t1, options);
  // The parameters are read only by side conditions (drop_spurious_roots()): none, none built.
  std::vector<double> parameters;
  if (primitive.side_conditions) parameters = {p[0], p[1], p[2], v[0], v[1], v[2]};
  const double seconds = r.counters.seconds;
  return finish(index, parameters, std::move(r), start, seconds);
}

SolveResult ImplicitOracle::surface_critical(const Vec3& d, const Domain& domain, std::size_t box_budget) {
  const auto start = std::chrono::steady_clock::now();
  const auto frame = orthonormal_frame(d);
  std::vector<double> params{frame.a[0], frame.a[1], frame.a[2], frame.b[0], frame.b[1], frame.b[2]};
  const std::size_t index = impl_->surface_critical;
  return finish(index, params, solve_square(index, params, domain, box_budget), start);
}

SolveResult ImplicitOracle::surface_plane_contact(const Vec3& o, const Vec3& a, const Vec3& b,
                                                 const Domain& domain) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> params{o[0], o[1], o[2], a[0], a[1], a[2], b[0], b[1], b[2]};
  const std::size_t index = impl_->surface_plane_contact;
  return finish(index, params, solve_over_determined(index, params, domain, tolerances::mesher_box_budget_2d), start);
}

SolveResult ImplicitOracle::curve_critical(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> params{o[0], o[1], o[2], a[0], a[1], a[2], b[0], b[1], b[2]};
  const std::size_t index = impl_->curve_critical;
  return finish(index, params, solve_square(index, params, domain, tolerances::mesher_box_budget_2d), start);
}

SolveResult ImplicitOracle::silhouette_plane(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d,
                                            const Domain& domain) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> params{o[0], o[1], o[2], a[0], a[1], a[2], b[0], b[1], b[2], d[0], d[1], d[2]};
  const std::size_t index = impl_->silhouette_plane;
  return finish(index, params, solve_square(index, params, domain, tolerances::mesher_box_budget_2d), start);
}

SolveResult ImplicitOracle::silhouette_critical(const Vec3& d, const Vec3& d2, const Domain& domain) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> params{d[0], d[1], d[2], d2[0], d2[1], d2[2]};
  const std::size_t index = impl_->silhouette_critical;
  return finish(index, params, solve_square(index, params, domain, tolerances::mesher_box_budget_3d), start);
}

SurfaceOracle::ConeAnswer ImplicitOracle::prove_gradient_cone(const AffineChart& chart, const Domain& domain,
                                                              const Vec3& w) {
  const std::size_t budget = domain.dimension() == 3 ? tolerances::gradient_cone_cell_box_budget
                                                     : tolerances::gradient_cone_box_budget;
  return answer(gradient_cone(chart, domain, w, budget, {}));
}

SurfaceOracle::ConeAnswer ImplicitOracle::gradient_cone_slope(const AffineChart& chart, const Domain& domain,
                                                              const Vec3& w, double target) {
  return answer(gradient_cone(chart, domain, w, tolerances::cell_slope_cover_budget,
                              {target, tolerances::cell_slope_box_budget}));
}

SurfaceOracle::ConeAnswer ImplicitOracle::answer(const GradientConeResult& r) {
  ConeAnswer a{r.proved, r.vanishing_point, r.slope, std::nullopt};
  if (r.proved) {
    a.surface_box = std::array<Vec3, 2>{r.surface_lo, r.surface_hi};
    a.orientation = r.orientation;
  }
  return a;
}

GradientConeResult ImplicitOracle::gradient_cone(const AffineChart& chart, const Domain& domain, const Vec3& w,
                                                 std::size_t budget, const SlopeRefinement& refinement) {
  const auto start = std::chrono::steady_clock::now();
  const auto r = delmesh::prove_gradient_cone(*impl_->gradient, chart, domain, w, budget, refinement);
  const std::lock_guard<std::mutex> lock(impl_->statistics_mutex);
  ++cone_stats_.attempts;
  cone_stats_.proved += r.proved ? 1 : 0;
  cone_stats_.refuted += r.refuted() ? 1 : 0;
  cone_stats_.boxes += r.boxes;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  cone_stats_.seconds += seconds;
  if (!r.proved) {
    cone_stats_.failed_boxes += r.boxes;
    cone_stats_.failed_seconds += seconds;
  }
  return r;
}

int ImplicitOracle::gradient_sign(const Vec3& a, const Vec3& b, const Vec3& w) const {
  return gradient_functional_sign(*impl_->gradient, a, b, w);
}

int ImplicitOracle::value_sign(const Vec3& lo, const Vec3& hi) const {
  return delmesh::value_sign(*impl_->gradient, lo, hi);
}

double ImplicitOracle::E(const Vec3& x) const {
  double value = 0;
  impl_->gradient->values<double>(x.data(), nullptr, &value);
  return value;
}

Vec3 ImplicitOracle::gradient(const Vec3& x) const {
  double value = 0;
  Vec3 g{};
  impl_->gradient->values_and_jacobian<double>(x.data(), nullptr, &value, g.data());
  return g;
}

Vec3 ImplicitOracle::normal(const Vec3& x) const { return normalized(gradient(x)); }

std::optional<Vec3> ImplicitOracle::project(const Vec3& start) const {
  Vec3 x = start;
  const double tol = tolerances::projection_relative_tolerance * diagonal();
  for (int it = 0; it < tolerances::projection_iterations; ++it) {
    double value = 0;
    Vec3 g{};
    impl_->gradient->values_and_jacobian<double>(x.data(), nullptr, &value, g.data());
    const double gg = dot(g, g);
    if (!(gg > 0) || !std::isfinite(value)) return std::nullopt;
    const double step = value / gg;
    x = x - step * g;
    if (!box_.contains(x)) return std::nullopt;
    if (std::abs(step) * std::sqrt(gg) <= tol) return x;
  }
  return std::nullopt;
}

const PrimitiveStatistics& ImplicitOracle::statistics(const std::string& primitive) const {
  return stats_[static_cast<std::size_t>(&find_primitive(primitive) - primitive_registry().data())];
}

nlohmann::json ImplicitOracle::statistics_json() const {
  const auto counts = [](const PrimitiveStatistics& s) {
    return nlohmann::json{{"calls", s.calls},
                          {"certified_roots", s.certified_roots},
                          {"undecided", s.undecided},
                          {"boxes", s.boxes},
                          {"seconds", s.seconds},
                          {"homotopy_fallbacks", s.homotopy_fallbacks},
                          {"time_limited", s.time_limited},
                          {"homotopy_paths", s.homotopy_paths},
                          {"homotopy_near_real", s.homotopy_near_real},
                          {"homotopy_diverging_near_domain", s.homotopy_diverging_near_domain},
                          {"homotopy_certified", s.homotopy_certified},
                          {"homotopy_uncertified", s.homotopy_uncertified},
                          {"homotopy_pieces_by_subdivision", s.homotopy_pieces_by_subdivision}};
  };
  nlohmann::json per = nlohmann::json::object();
  PrimitiveStatistics total;
  const auto& registry = primitive_registry();
  for (std::size_t i = 0; i < stats_.size(); ++i) {
    const auto& s = stats_[i];
    per[registry[i].name] = counts(s);
    total.calls += s.calls;
    total.certified_roots += s.certified_roots;
    total.undecided += s.undecided;
    total.boxes += s.boxes;
    total.seconds += s.seconds;
    total.homotopy_fallbacks += s.homotopy_fallbacks;
    total.time_limited += s.time_limited;
    total.homotopy_paths += s.homotopy_paths;
    total.homotopy_near_real += s.homotopy_near_real;
    total.homotopy_diverging_near_domain += s.homotopy_diverging_near_domain;
    total.homotopy_certified += s.homotopy_certified;
    total.homotopy_uncertified += s.homotopy_uncertified;
    total.homotopy_pieces_by_subdivision += s.homotopy_pieces_by_subdivision;
  }
  nlohmann::json j = counts(total);
  j.erase("calls");
  j["systems"] = total.calls;
  j["per_primitive"] = per;
  j["cone_certificates"] = {{"attempts", cone_stats_.attempts},
                            {"proved", cone_stats_.proved},
                            {"refuted", cone_stats_.refuted},
                            {"boxes", cone_stats_.boxes},
                            {"seconds", cone_stats_.seconds},
                            {"boxes_failed", cone_stats_.failed_boxes},
                            {"seconds_failed", cone_stats_.failed_seconds}};
  j["backend"] = backend_ == SolverBackend::homotopy ? "homotopy" : "subdivision";
  return j;
}

}  // namespace delmesh
