//! \file check_command.cpp
//! `delmesh check MESH [--lambda L] [(--surface NAME | --expr E --box B) --certify [--method M]
//! [--seed N]] [--time-limit S] [--json]`: the independent checker (meshing/core/mesh_checker.h) on a
//! mesh file, optionally compared with the bounds of Theorem 6.1 for λ, and with --certify the
//! topology certificates of the mesh for that surface: the restricted-Delaunay certificate
//! (meshing/verify/certificate.h), the gradient-flow certificate (meshing/verify/gradient_flow_certificate.h),
//! or both, and the verdict they give together.  The time limit counts from
//! the command's start: the certificate stops at it (status undecided); reading the mesh, checking
//! it and compiling the surface are held to it by the phase watchdog (apps/phase_watchdog.h).

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "apps/command_line.h"
#include "apps/commands.h"
#include "apps/interrupt.h"
#include "apps/phase_watchdog.h"
#include "common/errors.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/core/theorem_bounds.h"
#include "meshing/inputs/mesh_io.h"
#include "meshing/verify/certificate.h"
#include "meshing/verify/gradient_flow_certificate.h"

namespace delmesh::app {

namespace {

struct CheckOptions {
  std::string mesh;
  double lambda = 0;
  bool json = false;
  bool certify = false;
  std::string method = "auto";
  std::uint64_t seed = 1;
  double time_limit = 0;  //!< seconds; 0: none
  SurfaceOptions surface;
  CLI::Option* lambda_option = nullptr;
  CLI::Option* seed_option = nullptr;
  CLI::Option* method_option = nullptr;
};

const char* yes_no(bool b) { return b ? "yes" : "no"; }
const char* pass_fail(bool b) { return b ? "pass" : "FAIL"; }
//! "1 boundary loop", "3 boundary loops", "2 non-manifold vertices".
std::string count_of(std::size_t n, const std::string& thing) {
  if (n == 1) return "1 " + thing;
  return std::to_string(n) + " " + (thing.back() == 'x' ? thing.substr(0, thing.size() - 2) + "ices" : thing + "s");
}

//! "(x, y, z)" with 6 significant digits (the JSON has every digit).
std::string point_text(const std::array<double, 3>& x) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << x[0] << ", " << x[1] << ", " << x[2] << ")";
  return s.str();
}

//! The certificate's lines of the text report: status, the comparison with Tri S|Σ, and the
//! first witnesses (proved ones first) and unsettled findings.
void print_certificate(std::ostream& out, const Certificate& c) {
  std::ostringstream status;
  status << c.status;
  out << "certificate:           " << status.str() << (c.interrupted ? " (interrupted)" : "") << ", "
      << c.faces_checked() << " Voronoi faces checked (" << c.voronoi_edges << " edges, " << c.voronoi_facets
      << " facets, " << c.voronoi_cells << " cells) in " << c.seconds << " s (restricted Delaunay)\n";
  if (c.status == CertificateStatus::violated)
    out << "  (the mesh's vertices fail a sampling check of Sec. 5.3: this proves nothing about the mesh's "
           "topology)\n";
  out << "  Tri S|Sigma = mesh:  " << yes_no(c.restricted_matches_mesh);
  if (!c.restricted_matches_mesh)
    out << " (" << c.restricted_not_in_mesh << " restricted triangles not in the mesh, " << c.mesh_not_restricted
        << " mesh triangles not restricted, " << c.repeated_mesh_triangles << " repeated, " << c.coincident_vertices
        << " coincident vertices)";
  out << "\n";
  if (!c.witnesses.empty()) {
    std::size_t proved = 0;
    for (const auto& w : c.witnesses) proved += w.proved ? 1 : 0;
    out << "  witnesses:           " << c.witnesses.size() << " (" << proved << " proved)\n";
    std::size_t listed = 0;
    for (bool want : {true, false})
      for (const auto& w : c.witnesses)
        if (w.proved == want && listed < certificate_findings_listed) {
          ++listed;
          out << "    " << w.witness.kind << " at " << point_text(w.witness.point)
              << (w.proved ? "" : " (candidate: from an undecided region)") << "\n";
        }
  }
  if (!c.unsettled.empty()) {
    out << "  unsettled:           " << c.unsettled.size() << "\n";
    for (std::size_t i = 0; i < c.unsettled.size() && i < certificate_findings_listed; ++i)
      out << "    " << c.unsettled[i].what.check << ": " << c.unsettled[i].what.reason << " at "
          << point_text(c.unsettled[i].what.location) << "\n";
  }
}

//! The gradient-flow certificate's lines: status, reason and place, the tube and the bound.
void print_flow_certificate(std::ostream& out, const FlowCertificate& c) {
  std::ostringstream status;
  status << c.status;
  out << "gradient flow:         " << status.str() << " in " << c.seconds << " s ("
      << count_of(c.mesh_components, "mesh component") << ", " << count_of(c.critical_points, "critical point")
      << " counted, " << count_of(c.triangle_pieces, "triangle piece") << ", " << c.boxes << " boxes)\n";
  if (!c.reason.empty())
    out << "  " << (c.status == FlowCertificateStatus::refuted ? "refutation:          " : "not proved:          ")
        << c.reason << (c.location ? " at " + point_text(*c.location) : "") << "\n";
  if (c.epsilon > 0) out << "  |E| on the mesh:     <= " << c.epsilon << " (tube |E| <= " << c.tube << ")\n";
  if (c.min_gradient > 0) out << "  |grad E| on tube:    >= " << c.min_gradient << "\n";
  if (c.status == FlowCertificateStatus::certified)
    out << "  Hausdorff distance:  <= " << c.hausdorff_upper_bound << " (" << 100 * c.hausdorff_upper_bound / c.box_diagonal
        << " % of the box diagonal)\n";
}

}  // namespace

void require_bounds_lambda(double lambda) {
  if (!(lambda > 0 && lambda < beta_lambda_bound)) {
    throw InvalidInput("--lambda must lie in (0, 1/6) for the bounds of Theorem 6.1, got " + format_number(lambda));
  }
}

CheckVerdict check_verdict(const MeshReport& report, std::optional<double> lambda) {
  CheckVerdict v;
  v.report = report;
  v.lambda = lambda;
  if (lambda) {
    require_bounds_lambda(*lambda);
    if (*lambda > lambda0) v.warnings.push_back("Theorem 6.1 covers 0 < lambda <= 0.06 only; the bounds are computed anyway");
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

bool TopologyCertificates::interrupted() const {
  return (delaunay && delaunay->interrupted) || (flow && flow->interrupted);
}

bool TopologyCertificates::time_limited() const {
  return (delaunay && delaunay->time_limited) || (flow && flow->time_limited);
}

nlohmann::ordered_json TopologyCertificates::to_json() const {
  nlohmann::ordered_json out;
  if (delaunay) out["certificate"] = nlohmann::ordered_json::parse(delmesh::to_json(*delaunay).dump());
  if (flow) out["gradient_flow"] = nlohmann::ordered_json::parse(delmesh::to_json(*flow, true).dump());
  const bool bounded = flow && flow->status == FlowCertificateStatus::certified;
  out["topology"] = {{"verdict", verdict},
                     {"method", method.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(method)},
                     {"reason", reason},
                     {"hausdorff_upper_bound",
                      bounded ? nlohmann::ordered_json(flow->hausdorff_upper_bound) : nlohmann::ordered_json(nullptr)}};
  return out;
}

TopologyCertificates certify_topology(const std::vector<Point3>& points,
                                      const std::vector<std::array<std::size_t, 3>>& triangles,
                                      const SurfaceInput& input, CertifyMethod method, std::uint64_t seed,
                                      const std::atomic<bool>* interrupt,
                                      std::optional<std::chrono::steady_clock::time_point> deadline) {
  TopologyCertificates c;
  if (method != CertifyMethod::gradient_flow) {
    CertificateOptions options;
    options.seed = seed;
    options.interrupt = interrupt;
    options.deadline = deadline;
    c.delaunay = certify_mesh(points, triangles, input.surface, input.box, options);
  }
  const bool delaunay_ok =
      c.delaunay && c.delaunay->status == CertificateStatus::certified && c.delaunay->restricted_matches_mesh;
  const bool flow_wanted = method == CertifyMethod::gradient_flow || method == CertifyMethod::both ||
                           (method == CertifyMethod::automatic && !delaunay_ok);
  if (flow_wanted && !c.interrupted() && !c.time_limited()) {
    FlowCertificateOptions options;
    options.seed = seed;
    options.interrupt = interrupt;
    options.deadline = deadline;
    // certify_mesh validated the surface if it ran and was not stopped (it throws otherwise).
    options.surface_validated = c.delaunay.has_value();
    c.flow = certify_gradient_flow(points, triangles, input.surface, input.box, options);
  }
  const bool flow_ok = c.flow && c.flow->status == FlowCertificateStatus::certified;
  const bool flow_refuted = c.flow && c.flow->status == FlowCertificateStatus::refuted;
  const std::string delaunay_failed = "the restricted-Delaunay certificate did not certify the mesh as Tri S|Sigma";
  const auto decide = [&](const char* verdict, const char* by, const std::string& reason) {
    c.verdict = verdict;
    c.method = by;
    c.reason = reason;
  };
  if (method == CertifyMethod::both) {
    if (delaunay_ok && flow_ok)
      decide("certified", "both", "both proofs hold");
    else if (flow_refuted)
      decide("refuted", "gradient-flow", c.flow->reason);
    else
      decide("undecided", "", delaunay_ok && c.flow ? "the gradient-flow certificate: " + c.flow->reason : delaunay_failed);
  } else if (delaunay_ok) {
    decide("certified", "restricted-delaunay", "the mesh is Tri S|Sigma of its vertices, certified");
  } else if (flow_ok) {
    decide("certified", "gradient-flow", "the mesh is isotopic to the surface along its gradient flow");
  } else if (flow_refuted) {
    decide("refuted", "gradient-flow", c.flow->reason);
  } else {
    decide("undecided", "", c.flow ? c.flow->reason : delaunay_failed);
  }
  return c;
}

namespace {

// The option combinations `check` refuses (InvalidInput), and the certificate method asked for.
CertifyMethod validated_method(const CheckOptions& o, bool with_bounds) {
  if (with_bounds) require_bounds_lambda(o.lambda);
  if (o.certify && !o.surface.given())
    throw InvalidInput("--certify needs the surface: --surface NAME, or --expr E with --box B");
  if (!o.certify && o.surface.given())
    throw InvalidInput("--surface and --expr are used only with --certify (the certificate of the mesh for that surface)");
  if (!o.certify && o.seed_option->count() > 0) throw InvalidInput("--seed is used only with --certify");
  if (!o.certify && o.method_option->count() > 0) throw InvalidInput("--method is used only with --certify");
  const CertifyMethod method = parse_enum<CertifyMethod>(o.method, "--method");
  if (!std::isfinite(o.time_limit) || o.time_limit < 0 || o.time_limit > max_time_limit_seconds)
    throw InvalidInput("--time-limit must be >= 0 and <= 1e9 seconds (0: none), got " + format_number(o.time_limit));
  return method;
}

// The mesh checker's lines of the text report: counts, topology and quality.
void print_mesh_report(std::ostream& out, const std::string& mesh, const MeshReport& report) {
  out << "mesh:                  " << mesh << "\n";
  out << "vertices:              " << report.vertices << "\n";
  out << "edges:                 " << report.edges << "\n";
  out << "triangles:             " << report.triangles << "\n";
  out << "components:            " << report.components << "\n";
  out << "euler characteristic:  " << report.euler_characteristic << "\n";
  // The genus only of the components that are closed orientable 2-manifolds, "-" elsewhere.
  out << "genus per component:  ";
  bool undefined = false;
  for (int g : report.genus_per_component) {
    out << " " << (g >= 0 ? std::to_string(g) : "-");
    undefined = undefined || g < 0;
  }
  if (undefined) out << "  (-: not a closed orientable 2-manifold, genus undefined)";
  out << "\n";
  out << "closed:                " << yes_no(report.closed);
  if (!report.closed)
    out << " (" << count_of(report.boundary_edges, "boundary edge") << " in "
        << count_of(report.boundary_loops, "boundary loop") << ")";
  out << "\n";
  out << "manifold:              " << yes_no(report.manifold);
  if (report.nonmanifold_edges > 0 || report.nonmanifold_vertices > 0)
    out << " (" << count_of(report.nonmanifold_edges, "non-manifold edge") << ", "
        << count_of(report.nonmanifold_vertices, "non-manifold vertex") << ")";
  else if (!report.manifold)
    out << " (it has boundary)";
  out << "\n";
  out << "orientable:            " << yes_no(report.orientable);
  if (report.orientable && !report.oriented) out << " (but the triangles are not consistently oriented)";
  out << "\n";
  out << "min angle (deg):       " << report.min_angle_deg << "\n";
  out << "max radius-edge ratio: " << report.max_radius_edge_ratio << "\n";
  out << "max roughness (rad):   " << report.max_roughness_rad << "\n";
}

// The text report: the mesh checker's lines, the comparison with Theorem 6.1's bounds for λ when
// asked, and the certificates with their verdict when they ran.
void print_text_report(std::ostream& out, const CheckOptions& o, bool with_bounds, const CheckVerdict& verdict,
                       const std::optional<TopologyCertificates>& certificates) {
  print_mesh_report(out, o.mesh, verdict.report);
  if (with_bounds) {
    const TheoremBounds& bounds = verdict.bounds;
    out << "Theorem 6.1 bounds for lambda = " << format_number(o.lambda) << ":\n";
    out << "  min angle >= " << bounds.min_angle_deg << " deg: " << pass_fail(verdict.angle_ok) << "\n";
    out << "  radius-edge ratio <= " << bounds.max_radius_edge_ratio << ": " << pass_fail(verdict.ratio_ok) << "\n";
    out << "  roughness <= " << bounds.max_roughness_rad << " rad: " << pass_fail(verdict.roughness_ok) << "\n";
  }
  if (certificates) {
    if (certificates->delaunay) print_certificate(out, *certificates->delaunay);
    if (certificates->flow) print_flow_certificate(out, *certificates->flow);
    out << "topology:              " << certificates->verdict
        << (certificates->method.empty() ? "" : " (" + certificates->method + ")") << ": " << certificates->reason
        << "\n";
  }
  out.flush();
}

// The exit code, with the warning of a certificate stopped by a signal or the time limit.
ExitCode check_exit_code(const CheckVerdict& verdict, const std::optional<TopologyCertificates>& certificates) {
  if (certificates && certificates->interrupted()) {
    print_warning("interrupted by a signal: the certificate is incomplete (status undecided)");
    return ExitCode::limit_reached;
  }
  if (certificates && certificates->time_limited()) {
    print_warning("stopped by --time-limit: the certificate is incomplete (status undecided)");
    return ExitCode::limit_reached;
  }
  const bool certified = !certificates || certificates->verdict == "certified";
  return verdict.all_pass() && certified ? ExitCode::complete : ExitCode::check_failed;
}

ExitCode run_check(const CheckOptions& o) {
  const bool with_bounds = o.lambda_option->count() > 0;
  const CertifyMethod method = validated_method(o, with_bounds);
  const auto start = RunLimits::Clock::now();
  const RunLimits limits = RunLimits::after(o.time_limit, &interrupt_flag(), start);
  const RunLimits::Scope limits_scope(limits);
  // Reading and checking the mesh and compiling the surface cannot stop themselves: the watchdog
  // ends them at the deadline or a signal.  The certificate stops itself at either (and is then
  // reported, undecided); its own watchdog ends it only if one step still runs
  // PhaseWatchdog::solve_grace after the deadline.
  PhaseWatchdog watchdog(limits);
  std::optional<PhaseWatchdog::Phase> phase;  // (destroyed before the watchdog it arms)
  phase.emplace(watchdog, "reading and checking the mesh");
  // Read as a soup: open, non-manifold and non-orientable meshes are reported, not refused; faces
  // of more than three vertices are triangulated as `mesh --input-mesh` does.
  const TriangleSoup soup = triangulate_polygons(read_polygon_soup(o.mesh), o.mesh);
  const CheckVerdict verdict = check_verdict(check_mesh(soup.points, soup.triangles),
                                             with_bounds ? std::optional<double>(o.lambda) : std::nullopt);
  std::optional<TopologyCertificates> certificates;
  if (o.certify) {
    phase.emplace(watchdog, "compiling the surface");
    const SurfaceInput input = o.surface.resolve();
    phase.reset();
    PhaseWatchdog certificate_watchdog(RunLimits::after(
        o.time_limit > 0 ? o.time_limit + PhaseWatchdog::solve_grace.count() : 0, nullptr, start));
    const PhaseWatchdog::Phase certifying(certificate_watchdog, "certifying the mesh");
    certificates = certify_topology(soup.points, soup.triangles, input, method, o.seed, &interrupt_flag(),
                                    limits.deadline());
  }
  phase.reset();
  for (const std::string& warning : verdict.warnings) print_warning(warning);
  if (o.json) {
    nlohmann::ordered_json out = verdict.to_json();
    if (certificates) out.update(certificates->to_json());
    print_json(std::cout, out);
  } else {
    print_text_report(std::cout, o, with_bounds, verdict, certificates);
  }
  return check_exit_code(verdict, certificates);
}

}  // namespace

Command add_check_command(CLI::App& parent) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* sub =
      parent.add_subcommand("check", "Check a mesh file independently (topology, quality, bounds, certificate)");
  sub->footer(
      "Check a mesh file (OFF, PLY, OBJ or STL; polygons are triangulated as by mesh --input-mesh) from the file "
      "alone: components, Euler characteristic, "
      "genus per component (where defined: closed orientable 2-manifold components), closed / manifold / "
      "orientable with the counts of boundary edges and loops and of non-manifold edges and vertices, minimum "
      "angle, maximum radius-edge ratio, maximum roughness. Open, non-manifold and non-orientable meshes are "
      "reported, not refused. With --lambda, compare with the bounds of Theorem 6.1. With --certify and the "
      "surface, certify the topology: build the Delaunay triangulation of the mesh's vertices, run the five "
      "checks of Sec. 5.3 on every Voronoi face, and compare the restricted Delaunay triangulation Tri S|Sigma "
      "with the mesh; certified and matching proves the mesh homeomorphic to the surface (Theorem 2.1). That "
      "needs the mesh to be Tri S|Sigma of its vertices; any closed mesh, from any program, is certified by the "
      "gradient flow instead: in a tube |E| <= eps' around the mesh the gradient of E is proved non-zero, every "
      "triangle transverse to it, and a segment through each critical point of a height function on the surface "
      "crosses the mesh once; then the mesh is isotopic to the surface and within the certified Hausdorff bound "
      "eps/min|grad E| of it. --method auto runs restricted-Delaunay, then gradient-flow if the first did not "
      "certify; both runs the two independent proofs. The verdict (\"topology:\") is certified, refuted (only "
      "with a proof that the mesh's topology differs, e.g. it is not a closed 2-manifold) or undecided with the "
      "first condition not proved and where." "\n\n"
      "Exit codes: 0 checked (and with --lambda every bound holds, with --certify the verdict is certified), 1 "
      "some bound fails or the verdict is not certified, "
              "2 invalid input (missing or corrupt file, lambda out of range, a bad surface), 3 stopped by "
              "--time-limit or a signal such as SIGINT or SIGTERM (during the certificate it stops and the report "
              "says undecided; before it nothing is printed; while the report is printed it is finished "
              "first), 4 internal error, 6 the report could not be written to standard output.");
  sub->add_option("MESH", o->mesh, "The mesh file (.off, .ply or .obj; polygons are triangulated)")->required();
  o->lambda_option = sub->add_option("--lambda", o->lambda,
                                     "lambda in (0, 1/6): compare with min angle >= asin(1/(2+2 lambda)), "
                                     "radius-edge ratio <= 1+lambda, roughness <= 2 beta(lambda)")->type_name("L")
      ->check(finite_number());
  o->surface.add_to(*sub);
  sub->add_flag("--certify", o->certify,
                "Certify the topology of the mesh for the surface given by --surface or --expr with --box");
  o->method_option = sub->add_option("--method", o->method,
                                     "auto, restricted-delaunay, gradient-flow or both: which certificates "
                                     "--certify runs")
                         ->type_name("M")
                         ->capture_default_str();
  o->seed_option = sub->add_option("--seed", o->seed,
                                   "Seed of the certificates' generic directions (FacetCycle, Silhouette, the "
                                   "gradient flow's height function), 0 <= N < 2^64")
                       ->type_name("N")
                       ->check(whole_number(0, std::numeric_limits<std::uint64_t>::max()))
                       ->capture_default_str();
  sub->add_option("--time-limit", o->time_limit,
                  "Stop (exit code 3) after this many seconds (at most 1e9) from the start; with --certify "
                  "the report then says undecided. 0 means none")
      ->type_name("S")
      ->check(finite_number());
  sub->add_flag("--json", o->json,
                "Print the report as JSON (with --lambda also \"lambda\", \"bounds\" and \"pass\"; with "
                "--certify also \"topology\", and \"certificate\" and \"gradient_flow\" for the methods that ran)");
  return {sub, [o]() { return stopped_as_limit([&] { return run_check(*o); }); }};
}

}  // namespace delmesh::app
