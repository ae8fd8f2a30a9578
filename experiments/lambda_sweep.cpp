//! \file lambda_sweep.cpp
//! Theorem 6.1 by experiment: for catalog surfaces (or a surface given by --expr, --box, --name)
//! and a decreasing sequence of λ, run DelMesh
//! (no size bound), judge the output with the independent checker (meshing/core/mesh_checker.h) and
//! compare with the theorem's bounds for λ:
//!   (i)   topology: closed orientable 2-manifold with the catalog's genus per component;
//!   (ii)  radius-edge ratio ≤ 1+λ (so min angle ≥ arcsin(1/(2+2λ))), roughness ≤ 2β(λ);
//!   (iii) size: |S| ≤ 2(2+5λ)²/(πλ²) · ∫_Σ dA/lfs² (the end of the proof of Theorem 6.1), and
//!         |S| λ² / ∫_Σ dA/lfs² roughly constant in λ (an ε-sample has Θ(∫_Σ dA/(ε lfs)²) points).
//! The integral I = ∫_Σ dA/lfs² is computed for the surfaces whose lfs is known in closed form
//! (catalog.local_feature_size) by the midpoint rule over a ray-cast chart: Σ is written as
//! ρ(s, t) along rays from a centre (star charts) or from a core circle (tube charts), ρ found by
//! bisection on the compiled E, and dA = |J| / |n·e| ds dt with J the Jacobian of the coordinates
//! and e the ray direction.  The closed forms for the sphere (4π) and the torus (4π²R/r) are
//! printed next to the computed values.
//!
//! Real ε-samples (experiments/sampling/eps_sample.h) for every surface: a dense reference sample
//! R of Σ (experiments/sampling/dense_sample.h, cell edges ≤ --relative-spacing · lfs, seeded by
//! --sample-seed), with lfs analytic where the catalog knows it and otherwise estimated from the
//! Voronoi poles of a dense sample (experiments/sampling/lfs_estimate.h); the greedy
//! farthest-point ε-sample of R for each ε of --epsilons; and per run size_ratio =
//! |S| λ² / (|ε-sample| ε²), which Theorem 6.1(iii) predicts to stay bounded as λ → 0.  Where lfs
//! is analytic the pole estimate is made as well and its relative error against the exact lfs is
//! reported.  The ε-samples depend on the surface only, so they are computed once per surface, or
//! read back with --eps-reference from an earlier run's eps_reference.csv (the Snakemake workflow,
//! experiments/Snakefile, does that).
//!
//! Output in <out-dir>: lambda_sweep.csv (one row per surface and λ), eps_sample.csv (one row per
//! surface, λ and ε), eps_reference.csv (one row per surface and ε: the ε-samples and the lfs
//! estimate's error), lfs_estimate.csv (a subsample of R: lfs estimate and exact lfs), each with
//! its metadata NAME.csv.json (experiments/csv_writer.h); meshes under meshes/.  --eps-only
//! computes the reference files without meshing.

#include <CLI/CLI.hpp>

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "common/errors.h"
#include "common/huge_page_heap.h"
#include "experiments/experiment_support.h"
#include "experiments/sampling/dense_sample.h"
#include "experiments/sampling/eps_sample.h"
#include "experiments/sampling/lfs_estimate.h"
#include "meshing/core/theorem_bounds.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/mesh_io.h"
#include "symbolic/catalog.h"

namespace {

using namespace delmesh;
using namespace delmesh::experiments;
namespace fs = std::filesystem;
constexpr double pi = boost::math::constants::pi<double>();
using Vec = std::array<double, 3>;

//! A chart of Σ by rays: star charts from centres (one per component), or a tube chart about the
//! circle of radius R in the plane z = 0 centred on the z-axis.
struct Chart {
  enum class Kind { star, tube } kind;
  std::vector<Vec> centres;  //!< star: one centre per component
  double core_radius = 0;    //!< tube
};

//! The charts of the surfaces with analytic lfs (geometry read off the catalog descriptions).
const std::map<std::string, Chart>& charts() {
  static const std::map<std::string, Chart> table{
      {"sphere", {Chart::Kind::star, {{0, 0, 0}}, 0}},
      {"ellipsoid", {Chart::Kind::star, {{0, 0, 0}}, 0}},
      {"near_sheets", {Chart::Kind::star, {{1.025, 0, 0}, {-1.025, 0, 0}}, 0}},
      {"torus", {Chart::Kind::tube, {}, 1.0}},
      {"thin_handle", {Chart::Kind::tube, {}, 1.0}},
  };
  return table;
}

//! The root ρ > 0 of E(origin + ρ e) on a ray where E < 0 at ρ = 0: the point ρ_k of the grid
//! ρ_0 = 0, ρ_k = ρ_{k−1} + step (up to max_rho + step) where E turns from < 0 to ≥ 0, then
//! bisection of [ρ_{k−1}, ρ_k] to the last bit.  Scanning from ρ_0 gives the first such k; a hint
//! (operator()) gives the one nearest the hint, the same k when E changes sign once on the ray.
class RayRoot {
 public:
  RayRoot(const CompiledE& E, double step, double max_rho) : E_(E) {
    grid_.push_back(0);
    for (double rho = step; rho <= max_rho + step; rho += step) grid_.push_back(rho);
  }

  //! The root along origin + ρ e.  `hint`: the grid index k of the previous ray of the same chart,
  //! or 0 to scan from ρ = 0.  On the charts here each ray meets its component of Σ once, so the
  //! sign of E changes once along the grid and walking from the neighbouring ray's k finds the same
  //! k as the scan from 0, in a few evaluations instead of hundreds.  `hint` is updated.
  double operator()(const Vec& origin, const Vec& e, std::size_t& hint) const {
    auto at = [&](double rho) { return E_(origin[0] + rho * e[0], origin[1] + rho * e[1], origin[2] + rho * e[2]); };
    if (!(at(0) < 0)) throw std::runtime_error("chart origin is not inside the surface");
    const std::size_t last = grid_.size() - 1;
    std::size_t k = std::min(std::max<std::size_t>(hint, 1), last);
    if (at(grid_[k]) >= 0) {
      while (k > 1 && at(grid_[k - 1]) >= 0) --k;  // E(ρ_0) < 0 was checked
    } else {
      do {
        if (++k > last) throw std::runtime_error("ray leaves the chart range without meeting the surface");
      } while (at(grid_[k]) < 0);
    }
    hint = k;
    // Bisection: once the midpoint rounds to an end, no later step changes the bracket.
    double lo = grid_[k - 1], hi = grid_[k];
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (mid == lo || mid == hi) break;
      (at(mid) < 0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }

 private:
  const CompiledE& E_;
  std::vector<double> grid_;  //!< ρ_0, ρ_1, … as the scan accumulates them
};

//! ∫_Σ dA / lfs², midpoint rule with n × 2n cells per chart.
double lfs_integral(const LfsFunction& local_feature_size, const Box3& box, const CompiledE& E, const Chart& chart,
                    int n) {
  const RayRoot first_root(E, 1e-3 * box.diagonal(), box.diagonal());
  std::size_t hint = 0;  // the grid index of the previous ray's root
  double total = 0;
  // One cell: the ray origin + ρ e meets Σ at p; jacobian(ρ) is |J| of the chart coordinates.
  auto add = [&](const Vec& origin, const Vec& e, const auto& jacobian, double cell_area) {
    const double rho = first_root(origin, e, hint);
    const Vec p{origin[0] + rho * e[0], origin[1] + rho * e[1], origin[2] + rho * e[2]};
    Vec g{};
    E.value_and_gradient(p, g);
    const double cosine = std::fabs(g[0] * e[0] + g[1] * e[1] + g[2] * e[2]) / std::hypot(g[0], g[1], g[2]);
    const double lfs = local_feature_size(p);
    total += std::fabs(jacobian(rho)) / cosine / (lfs * lfs) * cell_area;
  };
  if (chart.kind == Chart::Kind::star) {
    // x = c + ρ (sinθ cosφ, sinθ sinφ, cosθ), J = ρ² sinθ.
    const double dt = pi / n, dp = 2 * pi / (2 * n);
    for (const Vec& c : chart.centres) {
      hint = 0;  // another component
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
          const double theta = (i + 0.5) * dt, phi = (j + 0.5) * dp;
          const Vec e{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
          add(c, e, [theta](double rho) { return rho * rho * std::sin(theta); }, dt * dp);
        }
    }
  } else {
    // x = (R + ρ cos v)(cos u, sin u, 0) + ρ sin v (0, 0, 1), J = ρ (R + ρ cos v).
    const double R = chart.core_radius, du = 2 * pi / (2 * n), dv = 2 * pi / n;
    for (int i = 0; i < 2 * n; ++i)
      for (int j = 0; j < n; ++j) {
        const double u = (i + 0.5) * du, v = (j + 0.5) * dv;
        const Vec origin{R * std::cos(u), R * std::sin(u), 0};
        const Vec e{std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v)};
        add(origin, e, [R, v](double rho) { return rho * (R + rho * std::cos(v)); }, du * dv);
      }
  }
  return total;
}

//! One surface of the sweep: a catalog entry, or the surface of --expr/--box/--name.
struct SweepSurface {
  std::string name;
  Surface surface;
  Box3 box;
  std::optional<std::vector<int>> genus_per_component; //!< empty for --expr without --genus
  LfsFunction analytic_lfs;                              //!< empty where no closed form is known
};

//! The ε-samples of one surface and, where lfs is analytic, the pole estimate's error.
struct EpsReference {
  std::string lfs_source; //!< "analytic" or PoleLfsEstimate::name()
  std::size_t reference_points = 0;
  std::vector<double> epsilons;
  std::vector<std::size_t> sizes;
  std::vector<double> covering;
  std::optional<LfsErrorSummary> error; //!< of the pole estimate against the analytic lfs
  double seconds = 0;
};

struct EpsParameters {
  std::vector<double> epsilons;
  DenseSampleOptions sample;
  std::size_t lfs_points = 3000; //!< rows of lfs_estimate.csv per surface (a regular subsample of R)
};

//! Writes every stride-th reference point (at most `count`) with its lfs estimate and exact lfs.
void write_lfs_points(CsvWriter& csv, const std::string& name, const std::vector<std::array<double, 3>>& points,
                      const std::vector<double>& estimate, const std::vector<double>& exact, std::size_t count) {
  const std::size_t stride = std::max<std::size_t>(1, (points.size() + count - 1) / std::max<std::size_t>(count, 1));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < points.size(); i += stride)
    csv.row({name, field(points[i][0]), field(points[i][1]), field(points[i][2]), field(estimate[i]),
             field(exact.empty() ? nan : exact[i])});
}

//! The reference sample, its lfs and the ε-samples (see the file comment).  Rows for
//! lfs_estimate.csv go to lfs_csv.
EpsReference eps_reference(const SweepSurface& s, const EpsParameters& parameters, CsvWriter& lfs_csv) {
  const Stopwatch clock;
  EpsReference result;
  result.epsilons = parameters.epsilons;
  LfsEstimateOptions estimate_options;
  estimate_options.sample = parameters.sample;
  const LfsEstimateResult estimate = estimate_lfs(s.surface, s.box, estimate_options);
  std::vector<std::array<double, 3>> points;
  std::vector<double> lfs;
  if (s.analytic_lfs) {
    // The estimate against the exact lfs on the estimator's own sample; the ε-samples from a
    // reference refined for the exact lfs.
    std::vector<double> exact;
    for (const auto& p : estimate.sample.points) exact.push_back(s.analytic_lfs(p));
    result.error = lfs_relative_error(estimate.values, exact);
    write_lfs_points(lfs_csv, s.name, estimate.sample.points, estimate.values, exact, parameters.lfs_points);
    DenseSample reference = dense_sample(s.surface, s.box, parameters.sample, s.analytic_lfs);
    if (reference.status != DenseSampleStatus::complete)
      throw std::runtime_error(s.name + ": the reference sample reached its point limit");
    points = std::move(reference.points);
    for (const auto& p : points) lfs.push_back(s.analytic_lfs(p));
    result.lfs_source = "analytic";
  } else {
    if (estimate.sample.status != DenseSampleStatus::complete)
      throw std::runtime_error(s.name + ": the reference sample reached its point limit");
    write_lfs_points(lfs_csv, s.name, estimate.sample.points, estimate.values, {}, parameters.lfs_points);
    points = estimate.sample.points;
    lfs = estimate.values;
    result.lfs_source = PoleLfsEstimate::name();
  }
  result.reference_points = points.size();
  const EpsSampleResult samples = eps_sample(points, lfs, parameters.epsilons);
  result.epsilons = samples.epsilons;
  result.sizes = samples.sizes;
  result.covering = samples.covering;
  result.seconds = clock.seconds();
  return result;
}

std::vector<std::string> eps_reference_columns() {
  return {"surface", "lfs_source", "epsilon", "eps_sample_vertices", "covering_ratio", "reference_points",
          "lfs_relative_error_max", "lfs_relative_error_median", "lfs_relative_error_mean", "seconds"};
}

void write_eps_reference(CsvWriter& csv, const std::string& name, const EpsReference& r) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < r.epsilons.size(); ++k)
    csv.row({name, r.lfs_source, field(r.epsilons[k]), field(r.sizes[k]), field(r.covering[k]),
             field(r.reference_points), field(r.error ? r.error->max : nan), field(r.error ? r.error->median : nan),
             field(r.error ? r.error->mean : nan), field(r.seconds)});
}

//! The rows of an eps_reference.csv for surface `name` (written by an earlier run with the same
//! sampling parameters: its metadata file eps_reference.csv.json must carry them, each `expected`
//! key with the same value); throws InvalidInput if either file cannot be read, a parameter
//! differs, or the file has no row for the surface.
EpsReference read_eps_reference(const std::string& path, const std::string& name,
                                const std::vector<std::pair<std::string, std::string>>& expected) {
  nlohmann::json meta;
  try {
    meta = read_metadata(path);
  } catch (const std::exception& e) {
    throw InvalidInput("--eps-reference: " + std::string(e.what()));
  }
  for (const auto& [key, value] : expected) {
    const nlohmann::json& parameters = meta["parameters"];
    if (!parameters.is_object() || !parameters.contains(key) || parameters[key] != value)
      throw InvalidInput("--eps-reference file '" + path + "' was made with other sampling parameters (want " +
                         key + "=" + value + ")");
  }
  std::ifstream in(path);
  if (!in) throw InvalidInput("cannot read --eps-reference file '" + path + "'");
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  auto column = [&header, &path](const std::string& key) {
    const auto at = std::find(header.begin(), header.end(), key);
    if (at == header.end()) throw InvalidInput("--eps-reference file '" + path + "' has no column " + key);
    return static_cast<std::size_t>(at - header.begin());
  };
  const std::size_t c_surface = column("surface"), c_source = column("lfs_source"), c_eps = column("epsilon"),
                    c_size = column("eps_sample_vertices"), c_cover = column("covering_ratio"),
                    c_points = column("reference_points"), c_max = column("lfs_relative_error_max"),
                    c_median = column("lfs_relative_error_median"), c_mean = column("lfs_relative_error_mean");
  EpsReference r;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line);
    if (f.size() != header.size() || f[c_surface] != name) continue;
    r.lfs_source = f[c_source];
    r.epsilons.push_back(std::stod(f[c_eps]));
    r.sizes.push_back(std::stoull(f[c_size]));
    r.covering.push_back(std::stod(f[c_cover]));
    r.reference_points = std::stoull(f[c_points]);
    if (f[c_max] != "nan") r.error = LfsErrorSummary{std::stod(f[c_max]), std::stod(f[c_median]), std::stod(f[c_mean]), 0};
  }
  if (r.epsilons.empty()) throw InvalidInput("--eps-reference file '" + path + "' has no row for " + name);
  return r;
}

//! A surface name usable in file names.
void check_name(const std::string& name) {
  if (name.empty() || !std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
      }))
    throw InvalidInput("--name must be letters, digits, '_' or '-' (got '" + name + "')");
}

std::string lambda_tag(double lambda) {
  std::ostringstream out;
  out << lambda;
  return out.str();
}

// The name and value of each parameter in a CSV file's metadata.
using CsvParameters = std::vector<std::pair<std::string, std::string>>;

// The sweep's command line.
struct SweepOptions {
  std::string surfaces = "sphere,ellipsoid,torus,genus2,metaball,two_blobs,thin_handle,near_sheets";
  std::vector<double> lambdas{0.06, 0.05, 0.04, 0.03, 0.02};
  std::string out_dir = "out";
  int resolution = 200;
  bool no_meshes = false, no_eps = false, eps_only = false;
  std::string expr, box_text, expr_name, eps_reference_path;
  std::vector<int> expr_genus;
  EpsParameters eps;
  DelMeshOptions base;
  CLI::Option* surfaces_option = nullptr;
  CLI::Option* expr_option = nullptr;

  SweepOptions() { eps.epsilons = {0.1, 0.15, 0.19}; }
};

// The options of the sweep's command line, into `o`.
void add_sweep_options(CLI::App& app, SweepOptions& o) {
  o.surfaces_option = app.add_option("--surfaces", o.surfaces, "catalog names, comma separated")->capture_default_str();
  o.expr_option = app.add_option("--expr", o.expr, "a surface E(x,y,z) = 0 to sweep as well (with --box, --name)");
  auto* box_option = app.add_option("--box", o.box_text, "x0,x1,y0,y1,z0,z1: the box of --expr");
  auto* name_option = app.add_option("--name", o.expr_name, "the name of --expr in the CSV and file names");
  app.add_option("--genus", o.expr_genus, "genus of each component of --expr (ascending), for topology_correct");
  o.expr_option->needs(box_option)->needs(name_option);
  box_option->needs(o.expr_option);
  name_option->needs(o.expr_option);
  app.add_option("--lambdas", o.lambdas, "values of lambda")->capture_default_str();
  app.add_option("--seed", o.base.seed, "delmesh seed")->capture_default_str();
  app.add_option("--threads", o.base.threads, "delmesh threads (0: every hardware thread)")->capture_default_str();
  app.add_option("--time-limit", o.base.time_limit_seconds, "delmesh time limit per run (s), 0 none")
      ->capture_default_str();
  app.add_option("--max-points", o.base.max_points, "delmesh point limit per run")->capture_default_str();
  app.add_option("--resolution", o.resolution, "integration cells per chart: n x 2n")->capture_default_str();
  app.add_option("--epsilons", o.eps.epsilons, "epsilon of the epsilon-samples")->capture_default_str();
  app.add_option("--sample-seed", o.eps.sample.seed, "seed of the dense reference sample")->capture_default_str();
  app.add_option("--relative-spacing", o.eps.sample.relative_spacing,
                 "reference sample: cell edge <= this times lfs")->capture_default_str();
  app.add_option("--eps-reference", o.eps_reference_path,
                 "read the epsilon-samples from this eps_reference.csv instead of computing them");
  app.add_flag("--eps-only", o.eps_only, "compute the epsilon-samples (eps_reference.csv, lfs_estimate.csv) only");
  app.add_flag("--no-eps-samples", o.no_eps, "no epsilon-samples (lambda_sweep.csv only)");
  app.add_option("--out-dir", o.out_dir, "output directory")->capture_default_str();
  app.add_flag("--no-meshes", o.no_meshes, "do not write the meshes");
}

// The surfaces: the catalog names (all of --surfaces, or none if only --expr is given) and --expr.
std::vector<SweepSurface> sweep_surfaces(const SweepOptions& o) {
  std::vector<SweepSurface> sweep;
  if (!(o.expr_option->count() && !o.surfaces_option->count()))
    for (const std::string& name : split(o.surfaces)) {
      const CatalogEntry& entry = catalog_entry(name);
      sweep.push_back({name, entry.surface(), entry.box, entry.genus_per_component, entry.local_feature_size});
    }
  if (o.expr_option->count()) {
    check_name(o.expr_name);
    std::optional<std::vector<int>> genus;
    if (!o.expr_genus.empty()) {
      genus = o.expr_genus;
      std::sort(genus->begin(), genus->end());
    }
    sweep.push_back({o.expr_name, Surface::parse(o.expr), Box3::parse(o.box_text), genus, {}});
  }
  return sweep;
}

// The option values the sweep refuses (InvalidInput).
void check_sweep_options(const SweepOptions& o) {
  for (double e : o.eps.epsilons)
    if (!(e > 0 && e < 1)) throw InvalidInput("--epsilons must lie in (0, 1)");
  if (!(o.eps.sample.relative_spacing > 0 && o.eps.sample.relative_spacing < 1))
    throw InvalidInput("--relative-spacing must lie in (0, 1)");
  if (o.no_eps && (o.eps_only || !o.eps_reference_path.empty()))
    throw InvalidInput("--no-eps-samples excludes --eps-only and --eps-reference");
}

// The parameters of the ε-samples, as the CSV files' metadata records them.
CsvParameters sampling_parameters(const EpsParameters& eps) {
  std::string epsilons;
  for (std::size_t k = 0; k < eps.epsilons.size(); ++k) epsilons += (k ? ";" : "") + field(eps.epsilons[k]);
  return {{"sample_seed", field(static_cast<long long>(eps.sample.seed))},
          {"relative_spacing", field(eps.sample.relative_spacing)},
          {"max_spacing", field(eps.sample.max_spacing)},
          {"epsilons", epsilons}};
}

// The line printed for a surface's ε-samples.
void print_eps_reference(const std::string& name, const EpsReference& r) {
  std::cout << name << ": reference sample " << r.reference_points << " points, lfs " << r.lfs_source;
  if (r.error) std::cout << " (pole estimate: relative error max " << r.error->max << " median " << r.error->median << ")";
  std::cout << "; eps-samples";
  for (std::size_t k = 0; k < r.epsilons.size(); ++k) std::cout << " " << r.epsilons[k] << ": " << r.sizes[k];
  std::cout << std::endl;
}

// The ε-samples, once per surface: computed (and written to eps_reference.csv and
// lfs_estimate.csv), or read back with --eps-reference.
std::map<std::string, EpsReference> eps_references(const SweepOptions& o, const std::vector<SweepSurface>& sweep,
                                                   const CsvParameters& sampling, const std::string& surface_names) {
  std::map<std::string, EpsReference> references;
  std::optional<CsvWriter> reference_csv, lfs_csv;
  if (o.eps_reference_path.empty()) {
    auto parameters = sampling;
    parameters.insert(parameters.begin(), {"surfaces", surface_names});
    reference_csv.emplace(fs::path(o.out_dir) / "eps_reference.csv", "lambda_sweep", parameters,
                          eps_reference_columns());
    lfs_csv.emplace(fs::path(o.out_dir) / "lfs_estimate.csv", "lambda_sweep", parameters,
                    std::vector<std::string>{"surface", "x", "y", "z", "lfs_estimate", "lfs_analytic"});
  }
  for (const SweepSurface& s : sweep) {
    EpsReference r;
    if (o.eps_reference_path.empty()) {
      r = eps_reference(s, o.eps, *lfs_csv);
      write_eps_reference(*reference_csv, s.name, r);
    } else {
      r = read_eps_reference(o.eps_reference_path, s.name, sampling);
    }
    print_eps_reference(s.name, r);
    references[s.name] = r;
  }
  if (reference_csv) {
    reference_csv->close();
    lfs_csv->close();
    std::cout << "wrote " << reference_csv->path().string() << ", " << lfs_csv->path().string() << std::endl;
  }
  return references;
}

// The columns of lambda_sweep.csv.
std::vector<std::string> sweep_columns() {
  std::vector<std::string> columns{"surface", "lambda", "status", "seconds", "expected_genus", "topology_correct"};
  append(columns, report_columns());
  append(columns, {"bound_min_angle_deg", "bound_max_radius_edge_ratio", "bound_max_roughness_rad",
                   "angle_ok", "ratio_ok", "roughness_ok", "lfs_integral", "vertices_lambda2",
                   "vertices_lambda2_over_lfs_integral", "theorem_size_bound", "size_ok",
                   "insertions_quality", "insertions_smooth", "insertions_topology", "seed", "lfs_source"});
  return columns;
}

// The columns of eps_sample.csv.
std::vector<std::string> eps_sample_columns() {
  return {"surface", "lambda", "seed", "status", "topology_correct", "vertices",
          "lfs_source", "epsilon", "eps_sample_vertices", "size_ratio",
          "reference_points", "covering_ratio", "lfs_relative_error_max",
          "lfs_relative_error_median", "lfs_integral", "vertices_lambda2_over_lfs_integral"};
}

// I = ∫_Σ dA/lfs² for a surface whose lfs is known in closed form and that has a chart (printed
// with the closed forms where they are known); nothing otherwise.
std::optional<double> surface_lfs_integral(const SweepSurface& s, int resolution) {
  const CompiledE E(s.surface);
  const auto chart = charts().find(s.name);
  if (!s.analytic_lfs || chart == charts().end()) return std::nullopt;
  const double integral = lfs_integral(s.analytic_lfs, s.box, E, chart->second, resolution);
  std::cout << s.name << ": integral of 1/lfs^2 over the surface = " << integral;
  if (s.name == "sphere") std::cout << " (closed form 4 pi = " << 4 * pi << ")";
  if (s.name == "torus") std::cout << " (closed form 4 pi^2 R / r = " << 4 * pi * pi / 0.4 << ")";
  if (s.name == "thin_handle") std::cout << " (closed form 4 pi^2 R / r = " << 4 * pi * pi / 0.08 << ")";
  std::cout << std::endl;
  return integral;
}

// One DelMesh run of the sweep and the checker's report on its mesh.
struct SweepRun {
  std::string status;
  double seconds = 0;
  MeshReport report;
  nlohmann::json statistics;
};

// DelMesh on surface s for λ (the mesh written under meshes/ unless --no-meshes); an error is
// the run's status, with the CSV's separators replaced.
SweepRun run_delmesh(const SweepSurface& s, double lambda, const SweepOptions& o) {
  DelMeshOptions options = o.base;
  options.lambda = lambda;
  options.distance_certificate = false;  // the sweep measures the mesher's sample and shape
  const Stopwatch clock;
  SweepRun run;
  try {
    DelMeshResult result = del_mesh(s.surface, s.box, options);
    std::ostringstream text;
    text << result.status;
    run.status = text.str();
    run.statistics = result.statistics;
    run.report = check_mesh(result.mesh);
    if (!o.no_meshes) {
      fs::create_directories(fs::path(o.out_dir) / "meshes");
      write_mesh(result.mesh,
                 (fs::path(o.out_dir) / "meshes" / ("sweep_" + s.name + "_l" + lambda_tag(lambda) + ".off")).string());
    }
  } catch (const std::exception& e) {
    run.status = std::string("error: ") + e.what();
    for (char& c : run.status)
      if (c == ',' || c == '\n') c = ';';
  }
  run.seconds = clock.seconds();
  return run;
}

// What a run's row compares with Theorem 6.1, shared by both CSV files.
struct RunJudgement {
  bool checked = false, correct = false;
  std::string correct_field;
  double v_l2 = 0;  // |S| λ²
};

// The run's row of lambda_sweep.csv and its line on standard output: the checker's report
// against the bounds for λ, and the size against the integral where it is known.
RunJudgement record_run(CsvWriter& csv, const SweepSurface& s, double lambda, const SweepRun& run,
                        const std::optional<double>& integral, const std::string& lfs_source, std::uint64_t seed) {
  const MeshReport& report = run.report;
  const TheoremBounds bounds = theorem_bounds(lambda);
  RunJudgement j;
  j.checked = s.genus_per_component.has_value();
  j.correct = j.checked && report.has_topology(*s.genus_per_component);
  const bool angle_ok = report.triangles > 0 && report.min_angle_deg >= bounds.min_angle_deg;
  const bool ratio_ok = report.triangles > 0 && report.max_radius_edge_ratio <= bounds.max_radius_edge_ratio;
  const bool roughness_ok = report.triangles > 0 && report.max_roughness_rad <= bounds.max_roughness_rad;
  j.v_l2 = static_cast<double>(report.vertices) * lambda * lambda;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double size_bound = integral ? 2 * (2 + 5 * lambda) * (2 + 5 * lambda) / (pi * lambda * lambda) * *integral : nan;
  const auto& insertions = run.statistics.contains("insertions") ? run.statistics["insertions"] : nlohmann::json::object();
  auto count = [&insertions](const char* key) { return insertions.value(key, 0LL); };
  j.correct_field = j.checked ? field(j.correct) : std::string("nan");
  std::vector<std::string> row{s.name, field(lambda), run.status, field(run.seconds),
                               s.genus_per_component ? field(*s.genus_per_component) : std::string("nan"),
                               j.correct_field};
  append(row, report_fields(report));
  append(row, {field(bounds.min_angle_deg), field(bounds.max_radius_edge_ratio),
               field(bounds.max_roughness_rad), field(angle_ok), field(ratio_ok), field(roughness_ok),
               field(integral ? *integral : nan), field(j.v_l2), field(integral ? j.v_l2 / *integral : nan),
               field(size_bound),
               integral ? field(static_cast<double>(report.vertices) <= size_bound) : std::string("nan"),
               field(count("quality")), field(count("smooth")),
               field(count("vor_edge") + count("facet_contact") + count("topo_disk") +
                     count("facet_cycle") + count("silhouette")),
               field(static_cast<long long>(seed)), lfs_source});
  csv.row(row);
  std::cout << s.name << " lambda=" << lambda << " " << run.status << " " << run.seconds << " s: " << report
            << " | bounds " << bounds
            << (!j.checked ? " topology not checked" : j.correct ? " topology ok" : " TOPOLOGY WRONG")
            << (angle_ok && ratio_ok && roughness_ok ? " bounds ok" : " BOUND VIOLATED") << std::endl;
  return j;
}

// Theorem 6.1(iii) against the ε-samples: the run's rows of eps_sample.csv, size_ratio =
// |S| λ² / (|ε-sample| ε²) for each ε.
void record_eps_rows(CsvWriter& eps_csv, const SweepSurface& s, double lambda, const SweepRun& run,
                     const RunJudgement& j, const EpsReference& r, const std::optional<double>& integral,
                     std::uint64_t seed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::cout << "  size_ratio";
  for (std::size_t k = 0; k < r.epsilons.size(); ++k) {
    const double eps_k = r.epsilons[k];
    const double ratio =
        run.report.vertices > 0 ? j.v_l2 / (static_cast<double>(r.sizes[k]) * eps_k * eps_k) : nan;
    eps_csv.row({s.name, field(lambda), field(static_cast<long long>(seed)), run.status, j.correct_field,
                 field(run.report.vertices), r.lfs_source, field(eps_k), field(r.sizes[k]), field(ratio),
                 field(r.reference_points), field(r.covering[k]), field(r.error ? r.error->max : nan),
                 field(r.error ? r.error->median : nan), field(integral ? *integral : nan),
                 field(integral ? j.v_l2 / *integral : nan)});
    std::cout << " eps=" << eps_k << ": " << ratio;
  }
  std::cout << std::endl;
}

// The sweep: the ε-samples, then DelMesh for every surface and λ, each run's rows written as it
// ends.
void run_sweep(const SweepOptions& o) {
  const std::vector<SweepSurface> sweep = sweep_surfaces(o);
  check_sweep_options(o);
  const CsvParameters sampling = sampling_parameters(o.eps);
  std::string surface_names;
  for (const SweepSurface& s : sweep) surface_names += (surface_names.empty() ? "" : ";") + s.name;
  std::map<std::string, EpsReference> references;
  if (!o.no_eps) references = eps_references(o, sweep, sampling, surface_names);
  if (o.eps_only) return;

  const CsvParameters run_parameters{{"surfaces", surface_names},
                                     {"seed", field(static_cast<long long>(o.base.seed))},
                                     {"time_limit", field(o.base.time_limit_seconds)},
                                     {"max_points", field(o.base.max_points)},
                                     {"resolution", field(o.resolution)}};
  CsvWriter csv(fs::path(o.out_dir) / "lambda_sweep.csv", "lambda_sweep", run_parameters, sweep_columns());
  std::optional<CsvWriter> eps_csv;
  if (!o.no_eps) {
    auto parameters = run_parameters;
    append(parameters, sampling);
    eps_csv.emplace(fs::path(o.out_dir) / "eps_sample.csv", "lambda_sweep", parameters, eps_sample_columns());
  }
  for (const SweepSurface& s : sweep) {
    const std::optional<double> integral = surface_lfs_integral(s, o.resolution);
    const std::string lfs_source = s.analytic_lfs ? "analytic" : PoleLfsEstimate::name();
    for (double lambda : o.lambdas) {
      const SweepRun run = run_delmesh(s, lambda, o);
      const RunJudgement j = record_run(csv, s, lambda, run, integral, lfs_source, o.base.seed);
      if (eps_csv) record_eps_rows(*eps_csv, s, lambda, run, j, references.at(s.name), integral, o.base.seed);
    }
  }
  csv.close();
  std::cout << "wrote " << csv.path().string();
  if (eps_csv) {
    eps_csv->close();
    std::cout << ", " << eps_csv->path().string();
  }
  std::cout << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
  delmesh::back_heap_with_huge_pages();
  CLI::App app{"Theorem 6.1 by experiment: DelMesh over a lambda sweep, checked by the independent "
               "checker against the bounds, with real epsilon-samples for the size; writes "
               "<out-dir>/lambda_sweep.csv, eps_sample.csv, eps_reference.csv, lfs_estimate.csv"};
  SweepOptions o;
  add_sweep_options(app, o);
  if (const auto code = parse_command_line(app, argc, argv)) return *code;
  return run_guarded([&] { run_sweep(o); });
}
