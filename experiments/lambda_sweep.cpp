//! \file lambda_sweep.cpp
//! Theorem 6.1 by experiment: for catalog surfaces and a decreasing sequence of λ, run DelMesh
//! (no size bound), judge the output with the independent checker (meshing/mesh_checker.h) and
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
//! printed next to the computed values.  Output: <out-dir>/lambda_sweep.csv, meshes under
//! <out-dir>/meshes/.

#include <CLI/CLI.hpp>

#include <boost/math/constants/constants.hpp>

#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "common/errors.h"
#include "experiments/experiment_support.h"
#include "meshing/del_mesh.h"
#include "meshing/mesh_io.h"
#include "meshing/theorem_bounds.h"
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

//! The first ρ > 0 with E(origin + ρ e) = 0: scan in steps of `step` up to max_rho, then bisect.
double first_root(const CompiledE& E, const Vec& origin, const Vec& e, double step, double max_rho) {
  auto at = [&](double rho) { return E(origin[0] + rho * e[0], origin[1] + rho * e[1], origin[2] + rho * e[2]); };
  double lo = 0, f_lo = at(0);
  if (!(f_lo < 0)) throw std::runtime_error("chart origin is not inside the surface");
  for (double hi = step; hi <= max_rho + step; hi += step) {
    const double f_hi = at(hi);
    if (f_hi >= 0) {
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (at(mid) < 0 ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    }
    lo = hi;
  }
  throw std::runtime_error("ray leaves the chart range without meeting the surface");
}

//! ∫_Σ dA / lfs², midpoint rule with n × 2n cells per chart.
double lfs_integral(const CatalogEntry& entry, const CompiledE& E, const Chart& chart, int n) {
  const double step = 1e-3 * entry.box.diagonal(), max_rho = entry.box.diagonal();
  double total = 0;
  // One cell: the ray origin + ρ e meets Σ at p; jacobian(ρ) is |J| of the chart coordinates.
  auto add = [&](const Vec& origin, const Vec& e, const auto& jacobian, double cell_area) {
    const double rho = first_root(E, origin, e, step, max_rho);
    const Vec p{origin[0] + rho * e[0], origin[1] + rho * e[1], origin[2] + rho * e[2]};
    Vec g{};
    E.value_and_gradient(p, g);
    const double cosine = std::fabs(g[0] * e[0] + g[1] * e[1] + g[2] * e[2]) / std::hypot(g[0], g[1], g[2]);
    const double lfs = entry.local_feature_size(p);
    total += std::fabs(jacobian(rho)) / cosine / (lfs * lfs) * cell_area;
  };
  if (chart.kind == Chart::Kind::star) {
    // x = c + ρ (sinθ cosφ, sinθ sinφ, cosθ), J = ρ² sinθ.
    const double dt = pi / n, dp = 2 * pi / (2 * n);
    for (const Vec& c : chart.centres)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
          const double theta = (i + 0.5) * dt, phi = (j + 0.5) * dp;
          const Vec e{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
          add(c, e, [theta](double rho) { return rho * rho * std::sin(theta); }, dt * dp);
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

std::string lambda_tag(double lambda) {
  std::ostringstream out;
  out << lambda;
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Theorem 6.1 by experiment: DelMesh over a lambda sweep, checked by the independent "
               "checker against the bounds; writes <out-dir>/lambda_sweep.csv"};
  std::string surfaces = "sphere,ellipsoid,torus,genus2,metaball,two_blobs,thin_handle,near_sheets";
  std::vector<double> lambdas{0.06, 0.05, 0.04, 0.03, 0.02};
  std::string out_dir = "out";
  int resolution = 200;
  bool no_meshes = false;
  DelMeshOptions base;
  app.add_option("--surfaces", surfaces, "catalog names, comma separated")->capture_default_str();
  app.add_option("--lambdas", lambdas, "values of lambda")->capture_default_str();
  app.add_option("--seed", base.seed, "delmesh seed")->capture_default_str();
  app.add_option("--threads", base.threads, "delmesh threads (0: every hardware thread)")->capture_default_str();
  app.add_option("--time-limit", base.time_limit_seconds, "delmesh time limit per run (s), 0 none")
      ->capture_default_str();
  app.add_option("--max-points", base.max_points, "delmesh point limit per run")->capture_default_str();
  app.add_option("--resolution", resolution, "integration cells per chart: n x 2n")->capture_default_str();
  app.add_option("--out-dir", out_dir, "output directory")->capture_default_str();
  app.add_flag("--no-meshes", no_meshes, "do not write the meshes");
  CLI11_PARSE(app, argc, argv);

  return run_guarded([&] {
    std::vector<std::string> columns{"surface", "lambda", "status", "seconds", "expected_genus",
                                     "topology_correct"};
    append(columns, report_columns());
    append(columns, {"bound_min_angle_deg", "bound_max_radius_edge_ratio", "bound_max_roughness_rad",
                     "angle_ok", "ratio_ok", "roughness_ok", "lfs_integral", "vertices_lambda2",
                     "vertices_lambda2_over_lfs_integral", "theorem_size_bound", "size_ok",
                     "insertions_quality", "insertions_smooth", "insertions_topology"});
    CsvWriter csv(fs::path(out_dir) / "lambda_sweep.csv", "lambda_sweep",
                  {{"surfaces", surfaces},
                   {"seed", field(static_cast<long long>(base.seed))},
                   {"time_limit", field(base.time_limit_seconds)},
                   {"max_points", field(base.max_points)},
                   {"resolution", field(resolution)}},
                  columns);
    for (const std::string& name : split(surfaces)) {
      const CatalogEntry& entry = catalog_entry(name);
      const Surface surface = entry.surface();
      const CompiledE E(surface);
      std::optional<double> integral;
      const auto chart = charts().find(name);
      if (entry.local_feature_size && chart != charts().end()) {
        integral = lfs_integral(entry, E, chart->second, resolution);
        std::cout << name << ": integral of 1/lfs^2 over the surface = " << *integral;
        if (name == "sphere") std::cout << " (closed form 4 pi = " << 4 * pi << ")";
        if (name == "torus") std::cout << " (closed form 4 pi^2 R / r = " << 4 * pi * pi / 0.4 << ")";
        if (name == "thin_handle") std::cout << " (closed form 4 pi^2 R / r = " << 4 * pi * pi / 0.08 << ")";
        std::cout << std::endl;
      }
      for (double lambda : lambdas) {
        DelMeshOptions options = base;
        options.lambda = lambda;
        const Stopwatch clock;
        std::string status;
        MeshReport report;
        nlohmann::json statistics;
        try {
          DelMeshResult result = del_mesh(surface, entry.box, options);
          std::ostringstream text;
          text << result.status;
          status = text.str();
          statistics = result.statistics;
          report = check_mesh(result.mesh);
          if (!no_meshes) {
            fs::create_directories(fs::path(out_dir) / "meshes");
            write_mesh(result.mesh,
                       (fs::path(out_dir) / "meshes" / ("sweep_" + name + "_l" + lambda_tag(lambda) + ".off")).string());
          }
        } catch (const std::exception& e) {
          status = std::string("error: ") + e.what();
          for (char& c : status)
            if (c == ',' || c == '\n') c = ';';
        }
        const double seconds = clock.seconds();
        const TheoremBounds bounds = theorem_bounds(lambda);
        const bool correct = report.has_topology(entry.genus_per_component);
        const bool angle_ok = report.triangles > 0 && report.min_angle_deg >= bounds.min_angle_deg;
        const bool ratio_ok = report.triangles > 0 && report.max_radius_edge_ratio <= bounds.max_radius_edge_ratio;
        const bool roughness_ok = report.triangles > 0 && report.max_roughness_rad <= bounds.max_roughness_rad;
        const double v_l2 = static_cast<double>(report.vertices) * lambda * lambda;
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const double size_bound = integral ? 2 * (2 + 5 * lambda) * (2 + 5 * lambda) / (pi * lambda * lambda) * *integral : nan;
        const auto& insertions = statistics.contains("insertions") ? statistics["insertions"] : nlohmann::json::object();
        auto count = [&insertions](const char* key) { return insertions.value(key, 0LL); };
        std::vector<std::string> row{name, field(lambda), status, field(seconds), field(entry.genus_per_component),
                                     field(correct)};
        append(row, report_fields(report));
        append(row, {field(bounds.min_angle_deg), field(bounds.max_radius_edge_ratio),
                     field(bounds.max_roughness_rad), field(angle_ok), field(ratio_ok), field(roughness_ok),
                     field(integral ? *integral : nan), field(v_l2), field(integral ? v_l2 / *integral : nan),
                     field(size_bound),
                     integral ? field(static_cast<double>(report.vertices) <= size_bound) : std::string("nan"),
                     field(count("quality")), field(count("smooth")),
                     field(count("vor_edge") + count("facet_contact") + count("topo_disk") +
                           count("facet_cycle") + count("silhouette"))});
        csv.row(row);
        std::cout << name << " lambda=" << lambda << " " << status << " " << seconds << " s: " << report
                  << " | bounds " << bounds << (correct ? " topology ok" : " TOPOLOGY WRONG")
                  << (angle_ok && ratio_ok && roughness_ok ? " bounds ok" : " BOUND VIOLATED") << std::endl;
      }
    }
    csv.close();
    std::cout << "wrote " << csv.path().string() << std::endl;
  });
}
