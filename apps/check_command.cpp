//! \file check_command.cpp
//! `delmesh check MESH [--lambda L] [--json]`: the independent checker (meshing/mesh_checker.h)
//! on a mesh file, optionally compared with the bounds of Theorem 6.1 for λ.

#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "apps/command_line.h"
#include "apps/commands.h"
#include "common/errors.h"
#include "meshing/mesh_checker.h"
#include "meshing/mesh_io.h"
#include "meshing/theorem_bounds.h"

namespace delmesh::app {

namespace {

struct CheckOptions {
  std::string mesh;
  double lambda = 0;
  bool json = false;
  CLI::Option* lambda_option = nullptr;
};

const char* yes_no(bool b) { return b ? "yes" : "no"; }
const char* pass_fail(bool b) { return b ? "pass" : "FAIL"; }
//! "1 boundary loop", "3 boundary loops", "2 non-manifold vertices".
std::string count_of(std::size_t n, const std::string& thing) {
  if (n == 1) return "1 " + thing;
  return std::to_string(n) + " " + (thing.back() == 'x' ? thing.substr(0, thing.size() - 2) + "ices" : thing + "s");
}

}  // namespace

void require_bounds_lambda(double lambda) {
  if (!(lambda > 0 && lambda < 1.0 / 6.0)) {
    throw InvalidInput("--lambda must lie in (0, 1/6) for the bounds of Theorem 6.1, got " + format_number(lambda));
  }
}

CheckVerdict check_verdict(const MeshReport& report, std::optional<double> lambda) {
  CheckVerdict v;
  v.report = report;
  v.lambda = lambda;
  if (lambda) {
    require_bounds_lambda(*lambda);
    if (*lambda > 0.06) v.warnings.push_back("Theorem 6.1 covers 0 < lambda <= 0.06 only; the bounds are computed anyway");
    v.bounds = theorem_bounds(*lambda);
    v.angle_ok = report.triangles > 0 && report.min_angle_deg >= v.bounds.min_angle_deg;
    v.ratio_ok = report.triangles > 0 && report.max_radius_edge_ratio <= v.bounds.max_radius_edge_ratio;
    v.roughness_ok = report.triangles > 0 && report.max_roughness_rad <= v.bounds.max_roughness_rad;
  }
  return v;
}

nlohmann::ordered_json CheckVerdict::to_json() const {
  nlohmann::ordered_json out = nlohmann::ordered_json::parse(delmesh::to_json(report).dump());
  if (lambda) {
    out["lambda"] = *lambda;
    out["bounds"] = {{"min_angle_deg", bounds.min_angle_deg},
                     {"max_radius_edge_ratio", bounds.max_radius_edge_ratio},
                     {"max_roughness_rad", bounds.max_roughness_rad}};
    out["pass"] = {{"min_angle_deg", angle_ok},
                   {"max_radius_edge_ratio", ratio_ok},
                   {"max_roughness_rad", roughness_ok},
                   {"all", all_pass()}};
  }
  return out;
}

namespace {

ExitCode run_check(const CheckOptions& o) {
  const bool with_bounds = o.lambda_option->count() > 0;
  if (with_bounds) require_bounds_lambda(o.lambda);
  // Read as a soup: open, non-manifold and non-orientable meshes are reported, not refused.
  const TriangleSoup soup = read_triangle_soup(o.mesh);
  const CheckVerdict verdict = check_verdict(check_mesh(soup.points, soup.triangles),
                                             with_bounds ? std::optional<double>(o.lambda) : std::nullopt);
  for (const std::string& warning : verdict.warnings) print_warning(warning);
  const MeshReport& report = verdict.report;
  const TheoremBounds& bounds = verdict.bounds;

  if (o.json) {
    print_json(std::cout, verdict.to_json());
  } else {
    std::cout << "mesh:                  " << o.mesh << "\n";
    std::cout << "vertices:              " << report.vertices << "\n";
    std::cout << "edges:                 " << report.edges << "\n";
    std::cout << "triangles:             " << report.triangles << "\n";
    std::cout << "components:            " << report.components << "\n";
    std::cout << "euler characteristic:  " << report.euler_characteristic << "\n";
    // The genus only of the components that are closed orientable 2-manifolds, "-" elsewhere.
    std::cout << "genus per component:  ";
    bool undefined = false;
    for (int g : report.genus_per_component) {
      std::cout << " " << (g >= 0 ? std::to_string(g) : "-");
      undefined = undefined || g < 0;
    }
    if (undefined) std::cout << "  (-: not a closed orientable 2-manifold, genus undefined)";
    std::cout << "\n";
    std::cout << "closed:                " << yes_no(report.closed);
    if (!report.closed)
      std::cout << " (" << count_of(report.boundary_edges, "boundary edge") << " in "
                << count_of(report.boundary_loops, "boundary loop") << ")";
    std::cout << "\n";
    std::cout << "manifold:              " << yes_no(report.manifold);
    if (report.nonmanifold_edges > 0 || report.nonmanifold_vertices > 0)
      std::cout << " (" << count_of(report.nonmanifold_edges, "non-manifold edge") << ", "
                << count_of(report.nonmanifold_vertices, "non-manifold vertex") << ")";
    else if (!report.manifold)
      std::cout << " (it has boundary)";
    std::cout << "\n";
    std::cout << "orientable:            " << yes_no(report.orientable);
    if (report.orientable && !report.oriented) std::cout << " (but the triangles are not consistently oriented)";
    std::cout << "\n";
    std::cout << "min angle (deg):       " << report.min_angle_deg << "\n";
    std::cout << "max radius-edge ratio: " << report.max_radius_edge_ratio << "\n";
    std::cout << "max roughness (rad):   " << report.max_roughness_rad << "\n";
    if (with_bounds) {
      std::cout << "Theorem 6.1 bounds for lambda = " << format_number(o.lambda) << ":\n";
      std::cout << "  min angle >= " << bounds.min_angle_deg << " deg: " << pass_fail(verdict.angle_ok) << "\n";
      std::cout << "  radius-edge ratio <= " << bounds.max_radius_edge_ratio << ": " << pass_fail(verdict.ratio_ok)
                << "\n";
      std::cout << "  roughness <= " << bounds.max_roughness_rad << " rad: " << pass_fail(verdict.roughness_ok)
                << "\n";
    }
    std::cout.flush();
  }
  return verdict.all_pass() ? ExitCode::complete : ExitCode::check_failed;
}

}  // namespace

Command add_check_command(CLI::App& parent) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* sub = parent.add_subcommand("check", "Check a mesh file independently (topology, quality, bounds)");
  sub->footer(
      "Check a triangle mesh file (OFF, PLY or OBJ) from the file alone: components, Euler characteristic, "
      "genus per component (where defined: closed orientable 2-manifold components), closed / manifold / "
      "orientable with the counts of boundary edges and loops and of non-manifold edges and vertices, minimum "
      "angle, maximum radius-edge ratio, maximum roughness. Open, non-manifold and non-orientable meshes are "
      "reported, not refused. With --lambda, compare with the bounds of Theorem 6.1." "\n\n"
      "Exit codes: 0 checked (and with --lambda every bound holds), 1 some bound fails, "
              "2 invalid input (missing or corrupt file, lambda out of range), 4 internal error.");
  sub->add_option("MESH", o->mesh, "The mesh file (.off, .ply or .obj)")->required();
  o->lambda_option = sub->add_option("--lambda", o->lambda,
                                     "lambda in (0, 1/6): compare with min angle >= asin(1/(2+2 lambda)), "
                                     "radius-edge ratio <= 1+lambda, roughness <= 2 beta(lambda)")->type_name("L")
      ->check(finite_number());
  sub->add_flag("--json", o->json,
                "Print the report as JSON (with --lambda also \"lambda\", \"bounds\" and \"pass\")");
  return {sub, [o]() { return run_check(*o); }};
}

}  // namespace delmesh::app
