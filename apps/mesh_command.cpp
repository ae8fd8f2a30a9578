//! \file mesh_command.cpp
//! `delmesh mesh`: DelMesh (meshing/driver/del_mesh.h) on a catalog surface or an expression; writes the
//! mesh (OFF/PLY/OBJ/STL/VTP by extension) and the statistics JSON.  Exit code 3 when a limit stopped the
//! run, 5 when it ended uncertified: the mesh and statistics are still written.  The two outputs are
//! written as a group (apps/output_files.h): both replace the old files once both are complete, or
//! neither does (exit code 2 or 6), and existing files are left untouched.

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "apps/command_line.h"
#include "apps/commands.h"
#include "apps/interrupt.h"
#include "apps/output_files.h"
#include "apps/phase_watchdog.h"
#include "apps/progress_line.h"
#include "apps/surface_normals.h"
#include "common/enum_names.h"
#include "common/errors.h"
#include "common/peak_memory.h"
#include "common/run_limits.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/make_oracle.h"
#include "meshing/inputs/mesh_io.h"
#include "meshing/inputs/self_intersection_repair.h"
#include "meshing/inputs/sharp_features.h"
#include "meshing/verify/certificate.h"

namespace delmesh::app {

namespace {

//! The command line of `delmesh mesh`: the run's options are bound to the fields of `run`.
struct MeshOptions {
  SurfaceOptions surface;
  std::string input_mesh;
  DelMeshOptions run;
  std::string out, stats;
  bool quiet = false;
  bool certify = false;
  bool repair = false;
  CLI::Option* input_mesh_option = nullptr;
  CLI::Option* min_spacing_option = nullptr;
  CLI::Option* feature_angle_option = nullptr;
  CLI::Option* no_features_option = nullptr;
  CLI::Option* out_option = nullptr;
  CLI::Option* stats_option = nullptr;
};

template <class T>
std::string to_text(const T& value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

//! The flag of an option with a range, and its value in `options` as the program prints it.
std::pair<std::string, std::string> flag_and_value(MeshOption option, const DelMeshOptions& options) {
  switch (option) {
    case MeshOption::lambda: return {"--lambda", format_number(options.lambda)};
    case MeshOption::size_bound:
      return {"--size-bound", options.size_bound ? format_number(*options.size_bound) : "none"};
    case MeshOption::max_distance:
      return {"--max-distance", options.max_distance ? format_number(*options.max_distance) : "none"};
    case MeshOption::max_points: return {"--max-points", std::to_string(options.max_points)};
    case MeshOption::time_limit: return {"--time-limit", format_number(options.time_limit_seconds)};
    case MeshOption::threads: return {"--threads", std::to_string(options.threads)};
    case MeshOption::min_spacing: return {"--min-spacing", format_number(options.min_spacing)};
    case MeshOption::feature_angle:
      return {"--feature-angle", options.feature_angle_deg ? format_number(*options.feature_angle_deg) : "none"};
  }
  return {"--unknown-option", ""};
}

//! The run's options as values.
MeshRequest request_of(const MeshOptions& o) {
  MeshRequest r;
  r.surface = o.surface.arguments();
  if (o.input_mesh_option->count() > 0) r.input_mesh = o.input_mesh;
  r.options = o.run;
  r.min_spacing_given = o.min_spacing_option->count() > 0;
  return r;
}

//! The warning for a λ that Theorem 6.1 does not cover (λ > 0.06), if it is one.
void warn_lambda(double lambda, std::vector<std::string>& warnings) {
  if (lambda > lambda0)
    warnings.push_back("lambda = " + format_number(lambda) +
                       " > 0.06: Theorem 6.1 does not cover it (no guarantee of topology or quality)");
}

//! Throws InvalidInput "FLAG must RANGE, got VALUE" for the first option out of its range
//! (DelMeshOptions::validate(), the one statement of the ranges).
void require_valid_options(const DelMeshOptions& options) {
  if (const std::optional<OptionViolation> violation = options.validate()) {
    const auto [flag, value] = flag_and_value(violation->option, options);
    throw InvalidInput(flag + " must " + violation->requirement + ", got " + value);
  }
}

}  // namespace

MeshPlan plan_mesh(const MeshRequest& r) {
  require_valid_options(r.options);
  if (r.input_mesh) {
    (void)plan_mesh_input(r);  // a missing, corrupt or invalid mesh, or a bad option, is reported as such first
    throw InvalidInput("--input-mesh: a triangle mesh is remeshed through plan_mesh_input() and remesh()");
  }
  if (!r.surface.surface && !r.surface.expr) {
    throw InvalidInput("give one of --surface NAME, --expr E --box B, --input-mesh FILE");
  }

  if (r.options.max_distance && r.options.phase != MeshPhase::all)
    throw InvalidInput("--max-distance needs --phase all (the distance is refined with Quality and Smooth)");

  MeshPlan plan{r.surface.resolve(), r.options, {}};
  if (!r.min_spacing_given) plan.options.min_spacing = 0;
  warn_lambda(r.options.lambda, plan.warnings);
  return plan;
}

MeshInputPlan plan_mesh_input(const MeshRequest& r) {
  if (!r.input_mesh) throw PreconditionViolation("plan_mesh_input: the request has no --input-mesh");
  require_valid_options(r.options);  // a bad option is refused before the input is read
  // The default outputs <stem>_remeshed.off and .json never replace the input.
  return plan_mesh_input(r, read_input_mesh(*r.input_mesh),
                         std::filesystem::path(*r.input_mesh).stem().string() + "_remeshed");
}

MeshInputPlan plan_mesh_input(const MeshRequest& r, InputMesh mesh, const std::string& name) {
  require_valid_options(r.options);
  if (r.surface.surface || r.surface.expr || r.surface.box)
    throw InvalidInput("--input-mesh excludes --surface, --expr and --box");
  if (r.options.max_distance)
    throw InvalidInput("--max-distance needs --surface or --expr: an input mesh has no E whose gradient bounds "
                       "the distance");
  MeshInputPlan plan{name, r.input_mesh.value_or(name), std::move(mesh), r.options, {}};
  if (!r.min_spacing_given)
    plan.options.min_spacing = tolerances::min_spacing_median_edge_fraction * plan.mesh.median_edge_length;
  warn_lambda(r.options.lambda, plan.warnings);
  if (const auto& folded = plan.mesh.folded_vertices; !folded.empty()) {
    const Point3& x = plan.mesh.mesh.point(folded.front());
    std::ostringstream warning;
    warning << folded.size() << " vertex(es) of the input are folded (the first: " << std::size_t(folded.front())
            << " at (" << x.x() << ", " << x.y() << ", " << x.z()
            << ")): faces around them face every direction both ways, so Silhouette can never be clean there "
               "and the run cannot end complete (meshing/inputs/folded_vertices.h)";
    plan.warnings.push_back(warning.str());
  }
  return plan;
}

DelMeshResult remesh(const MeshInputPlan& plan, const DelMeshOptions& options) {
  PreparedInput input = make_oracle(TriangleMeshInput{plan.path, &plan.mesh});
  return del_mesh(input, options);
}

nlohmann::json run_statistics(const DelMeshResult& result, std::uint64_t seed, const std::optional<std::string>& mesh_file) {
  nlohmann::json statistics = result.statistics;
  if (!statistics.is_object()) statistics = nlohmann::json::object();
  if (!statistics.contains("status")) statistics["status"] = to_text(result.status);
  if (!statistics.contains("seed")) statistics["seed"] = seed;
  if (mesh_file && !statistics.contains("mesh_file")) statistics["mesh_file"] = *mesh_file;
  statistics["peak_memory_bytes"] = peak_resident_bytes();
  return statistics;
}

nlohmann::json mesh_statistics(const DelMeshResult& result, const SurfaceInput& input, std::uint64_t seed,
                               const std::optional<std::string>& mesh_file) {
  nlohmann::json statistics = run_statistics(result, seed, mesh_file);
  statistics["surface"] = {{"name", input.name},
                           {"equation", input.surface.text()},
                           {"box", {input.box.lo[0], input.box.hi[0], input.box.lo[1], input.box.hi[1],
                                    input.box.lo[2], input.box.hi[2]}}};
  return statistics;
}

namespace {

//! The run's input: one of the two plans, an implicit surface or a triangle mesh to remesh.
struct MeshRun {
  std::optional<MeshPlan> plan;
  std::optional<MeshInputPlan> mesh_plan;
  std::optional<RepairReport> repair;  //!< --repair: what it did to the input mesh

  const std::string& name() const { return plan ? plan->input.name : mesh_plan->name; }
  DelMeshOptions& options() { return plan ? plan->options : mesh_plan->options; }
  const std::vector<std::string>& warnings() const { return plan ? plan->warnings : mesh_plan->warnings; }
  //! What make_oracle() builds the run's oracle from.
  MesherInput input() const {
    if (plan) return ImplicitInput{plan->input.name, plan->input.surface, plan->input.box, plan->options.solver};
    return TriangleMeshInput{mesh_plan->path, &mesh_plan->mesh};
  }
};

MeshRun plan_run(const MeshOptions& o) {
  const MeshRequest request = request_of(o);
  MeshRun run;
  if (o.repair && !request.input_mesh) throw InvalidInput("--repair needs --input-mesh");
  if (!request.input_mesh && (o.feature_angle_option->count() > 0 || o.no_features_option->count() > 0))
    throw InvalidInput(std::string(o.feature_angle_option->count() > 0 ? "--feature-angle" : "--no-features") +
                       " needs --input-mesh (an implicit surface is smooth: it has no sharp edges)");
  if (request.input_mesh && o.repair) {
    RepairedInput repaired = read_and_repair_input_mesh(*request.input_mesh);
    run.repair = repaired.report;
    run.mesh_plan = plan_mesh_input(request, std::move(repaired.input),
                                    std::filesystem::path(*request.input_mesh).stem().string() + "_remeshed");
    if (o.certify)
      throw InvalidInput("--certify needs --surface or --expr (the certificate is proved on an implicit surface)");
  } else if (request.input_mesh) {
    run.mesh_plan = plan_mesh_input(request);
    if (o.certify)
      throw InvalidInput("--certify needs --surface or --expr (the certificate is proved on an implicit surface)");
  } else {
    run.plan = plan_mesh(request);
  }
  return run;
}

//! The mesh and statistics files (defaults from the input's name), added to `outputs` in this
//! order (so checked writable and distinct: apps/output_files.h).
std::pair<std::string, std::string> output_files(const MeshOptions& o, const std::string& name, OutputSet& outputs) {
  const std::string out = o.out_option->count() > 0 ? o.out : name + ".off";
  const std::string stats = o.stats_option->count() > 0 ? o.stats : name + ".json";
  const std::string extension = extension_of(out);
  if (extension != ".off" && extension != ".ply" && extension != ".obj" && extension != ".stl" && extension != ".vtp") {
    throw InvalidInput("--out: the extension must be .off, .ply, .obj, .stl or .vtp, got '" + out + "'");
  }
  if (out == "-") throw InvalidInput("--out: a mesh file name is required (\"-\" is only for --stats)");
  outputs.add("--out", out);
  outputs.add("--stats", stats);
  return {out, stats};
}

//! Progress on stderr (apps/progress_line.h: one line rewritten in place on a terminal, plain
//! lines every few seconds elsewhere), after a header that goes out with the first report, i.e.
//! once del_mesh has accepted the surface: a surface rejected as invalid input gives the single
//! `error:` line only.  The caller finishes the line before it writes anything else.
std::shared_ptr<ProgressLine> report_progress(const MeshOptions& o, MeshRun& run) {
  DelMeshOptions& options = run.options();
  const std::string what =
      run.plan ? run.plan->input.name + " (" + run.plan->input.surface.text() + " = 0) in " +
                     format_box(run.plan->input.box)
               : run.mesh_plan->path + " (" + std::to_string(run.mesh_plan->mesh.report.triangles) + " triangles) in " +
                     format_box(run.mesh_plan->mesh.box) + ", min spacing " + format_number(options.min_spacing);
  auto line = std::make_shared<ProgressLine>(
      std::cerr, "delmesh: meshing " + what + ", lambda " + format_number(o.run.lambda) + ", phase " + to_text(o.run.phase),
      ::isatty(STDERR_FILENO) == 1);
  options.progress = [line](const ProgressReport& report) { line->report(report); };
  return line;
}

//! The certificate of the finished mesh (meshing/verify/certificate.h), from the mesh alone, into the
//! statistics; a run stopped by a limit or a signal, or without triangles, has none (null).
//! \return how the certificate was stopped: interrupted by a signal, time_limit by the
//! command's deadline; nothing if it ran to its end.
std::optional<MeshStatus> certify_result(const MeshOptions& o, const MeshPlan& plan, const DelMeshResult& result,
                                         const RunLimits& limits, nlohmann::json& statistics) {
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  mesh_to_soup(result.mesh, points, triangles);
  const bool ended = result.status == MeshStatus::complete || result.status == MeshStatus::uncertified;
  if (!ended || triangles.empty()) {
    statistics["certificate"] = nullptr;
    print_warning(std::string("--certify: no certificate for a run that ") +
                  (ended ? "has no triangles" : "stopped before its end"));
    return std::nullopt;
  }
  if (!o.quiet) std::cerr << "delmesh: certifying the mesh from scratch" << std::endl;
  CertificateOptions certificate_options;
  certificate_options.seed = o.run.seed;
  certificate_options.interrupt = &interrupt_flag();
  certificate_options.deadline = limits.deadline();
  const Certificate certificate = certify_mesh(points, triangles, plan.input.surface, plan.input.box, certificate_options);
  statistics["certificate"] = to_json(certificate);
  if (!certificate.interrupted && !certificate.time_limited &&
      (certificate.status != CertificateStatus::certified || !certificate.restricted_matches_mesh))
    print_warning("--certify: the certificate of the mesh is " + to_text(certificate.status) +
                  (certificate.restricted_matches_mesh ? "" : ", and Tri S|Sigma differs from the mesh") +
                  " (statistics: \"certificate\")");
  if (certificate.interrupted) return MeshStatus::interrupted;
  if (certificate.time_limited) return MeshStatus::time_limit;
  return std::nullopt;
}

//! "N findings were not settled (R1 n1, R2 n2; statistics: "unsettled")" from the statistics'
//! "unsettled" object, the reasons in the order the statistics list them.
std::string unsettled_summary(const nlohmann::json& unsettled) {
  const auto count = unsettled["count"].get<std::size_t>();
  std::string text = std::to_string(count) + (count == 1 ? " finding was" : " findings were") + " not settled (";
  for (const auto& [reason, n] : unsettled["by_reason"].items())
    text += reason + " " + std::to_string(n.get<std::size_t>()) + "; ";
  return text + "statistics: \"unsettled\")";
}

//! The exit code of a finished run, with its warning.
ExitCode exit_code(MeshStatus status, const nlohmann::json& statistics, double min_spacing) {
  switch (status) {
    case MeshStatus::complete: return ExitCode::complete;
    case MeshStatus::uncertified:
      if (statistics["min_spacing"]["reached"].get<bool>())
        print_warning("the termination floor --min-spacing " + format_number(min_spacing) + " was reached " +
                      std::to_string(statistics["min_spacing"]["witnesses_below"].get<std::size_t>()) +
                      " times (statistics: \"min_spacing\")");
      if (!statistics["solver_certified"].get<bool>())
        print_warning("the oracle gave answers that are not certified, so the run cannot be complete "
                      "(statistics: \"solver_certified\")");
      print_warning("uncertified: the run ended, but " + unsettled_summary(statistics["unsettled"]) +
                    "; the mesh carries no guarantee");
      return ExitCode::uncertified;
    case MeshStatus::interrupted:
      print_warning("interrupted by a signal: the mesh is partial");
      return ExitCode::limit_reached;
    case MeshStatus::point_limit:
    case MeshStatus::time_limit: break;
  }
  print_warning("stopped by " + std::string(status == MeshStatus::time_limit ? "--time-limit" : "--max-points") +
                " (status " + to_text(status) + "): the mesh is partial");
  return ExitCode::limit_reached;
}

//! The time limit of del_mesh for the rest of the command's limits: the seconds left before the
//! deadline (at least the least positive double, since 0 would mean none), or 0 without one.
double seconds_left(const RunLimits& limits) {
  const std::optional<double> left = limits.seconds_left();
  return left ? std::max(*left, std::numeric_limits<double>::denorm_min()) : 0;
}

//! del_mesh on the run's input: the oracle (with the validation of an implicit surface) built
//! under the watchdog, then the run in the time left.  The statistics' "seconds" count from the
//! oracle's construction.  If `normals` is given and the input is an implicit surface, it gets the
//! unit normals of the mesh by the oracle's ∇E (surface_normals.h), before the oracle is gone.
DelMeshResult mesh_run(const MeshRun& run, DelMeshOptions options, PhaseWatchdog& watchdog, const RunLimits& limits,
                       PointNormals* normals) {
  const auto start = std::chrono::steady_clock::now();
  std::optional<PreparedInput> input;
  {
    const PhaseWatchdog::Phase phase(watchdog, run.plan ? "validating the surface and building its oracle"
                                                        : "building the oracle of the input mesh");
    input.emplace(make_oracle(run.input()));
  }
  options.time_limit_seconds = seconds_left(limits);
  DelMeshResult result = del_mesh(*input, options);
  if (normals && input->implicit) *normals = surface_normals(*input->implicit, result.mesh);
  result.statistics["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

//! One line on stderr for the statistics' "distance" certificate (del_mesh.h), if it was attempted.
void print_distance(const nlohmann::json& statistics) {
  const auto d = statistics.find("distance");
  if (d == statistics.end() || (*d)["status"] == "not attempted") return;
  if ((*d)["status"] == "certified")
    std::cerr << "delmesh: distance to the surface <= " << format_number((*d)["hausdorff_upper_bound"].get<double>())
              << " (two-sided Hausdorff, certified by the gradient flow)" << std::endl;
  else
    std::cerr << "delmesh: distance to the surface not certified: " << (*d)["reason"].get<std::string>() << std::endl;
}

//! Writes the run's mesh in `format`.  A .vtp of an implicit surface carries `normals` (the unit
//! normals ∇E/|∇E| at its vertices, surface_normals.h) and, when the gradient-flow certificate of
//! the run certified the mesh, the point data certified_distance (vertex_distance_bounds); one of
//! an input mesh has neither, and no other format has point data.
void write_run_mesh(const MeshRun& run, const DelMeshResult& result, std::ostream& out, MeshFormat format,
                    const PointNormals& normals) {
  const bool vtp = format == MeshFormat::vtp && run.plan;
  write_mesh(result.mesh, out, format, vtp ? normals : PointNormals{},
             vtp ? vertex_distance_bounds(result.mesh, result.triangle_distance_bounds) : PointDistances{});
}

//! The steps: plan the run and check its outputs (every option valid from then on, so a warning
//! cannot precede an `error:` about them), mesh, certify if asked, write, and map the status.
ExitCode run_mesh(const MeshOptions& o) {
  // Installed before the input is read: a signal that arrives while the surface is compiled or an
  // input mesh read then stops the run at its first check instead of ending the process.
  install_interrupt_handlers();
  // One deadline for the whole command, from its start; the phases without steps of their own
  // to test it between (parsing and compiling E, reading and validating the input, building the
  // oracle) are held to it by the watchdog.
  const RunLimits limits =
      RunLimits::after(std::min(o.run.time_limit_seconds, max_time_limit_seconds), &interrupt_flag());
  const RunLimits::Scope limits_scope(limits);
  PhaseWatchdog watchdog(limits);
  std::optional<PhaseWatchdog::Phase> preparing;
  preparing.emplace(watchdog, o.input_mesh_option->count() > 0 ? "reading and validating the input mesh"
                                                               : "parsing and compiling the expression");
  MeshRun run = plan_run(o);
  preparing.reset();
  OutputSet outputs;
  const std::pair<std::string, std::string> files = output_files(o, run.name(), outputs);
  const std::string& out = files.first;
  const std::string& stats = files.second;
  if (run.repair && !o.quiet) std::cerr << "delmesh: --repair: " << run.repair->summary(run.mesh_plan->path) << std::endl;
  for (const std::string& warning : run.warnings()) print_warning(warning);
  const std::shared_ptr<ProgressLine> progress = o.quiet ? nullptr : report_progress(o, run);

  DelMeshOptions& options = run.options();
  options.interrupt = &interrupt_flag();
  const MeshFormat format = mesh_format(out);
  PointNormals normals;  // for a .vtp of an implicit surface
  DelMeshResult result = mesh_run(run, options, watchdog, limits, format == MeshFormat::vtp ? &normals : nullptr);
  if (progress) progress->finish();

  nlohmann::json statistics =
      run.plan ? mesh_statistics(result, run.plan->input, o.run.seed, out) : run_statistics(result, o.run.seed, out);
  if (run.repair && statistics.contains("input_mesh")) {
    const RepairReport& r = *run.repair;
    statistics["input_mesh"]["repair"] = {{"method", r.method},
                                          {"intersecting_pairs", r.intersecting_pairs},
                                          {"faces_before", r.faces_before},
                                          {"faces_after", r.faces_after},
                                          {"vertices_before", r.vertices_before},
                                          {"vertices_after", r.vertices_after},
                                          {"seconds", r.seconds}};
  }
  const std::optional<MeshStatus> certificate_stopped =
      o.certify ? certify_result(o, *run.plan, result, limits, statistics) : std::nullopt;
  if (certificate_stopped) {
    // The run stopped at the signal or the deadline like any limit; how the mesh itself ended
    // stays on record.
    statistics["run_status"] = statistics["status"];
    statistics["status"] = to_text(*certificate_stopped);
  }

  // Both files or neither: a file that cannot be written leaves the other one as it was.
  outputs.write({[&](std::ostream& s) { write_run_mesh(run, result, s, format, normals); },
                 [&](std::ostream& s) { s << statistics.dump(2) << "\n"; }});

  if (!o.quiet) {
    std::cerr << "delmesh: " << result.status << ": wrote " << out << " (" << result.mesh.number_of_vertices()
              << " vertices, " << result.mesh.number_of_faces() << " triangles)"
              << (stats == "-" ? "" : " and " + stats) << std::endl;
    print_distance(statistics);
  }
  if (certificate_stopped) {
    print_warning(std::string(*certificate_stopped == MeshStatus::interrupted ? "interrupted by a signal"
                                                                              : "stopped by --time-limit") +
                  " during the certificate: the mesh is written, its certificate is incomplete");
    return ExitCode::limit_reached;
  }
  return exit_code(result.status, statistics, options.min_spacing);
}

}  // namespace

//! The options of `delmesh mesh`, one add_option each with its help text (hence the length).
Command add_mesh_command(CLI::App& parent) {
  auto o = std::make_shared<MeshOptions>();
  CLI::App* sub = parent.add_subcommand("mesh", "Mesh a surface with DelMesh; write the mesh and its statistics");
  sub->footer(
      "Mesh the surface E = 0 with DelMesh (Sec. 6.2). For 0 < lambda <= 0.06 the output is homeomorphic to "
      "the surface, every triangle has radius-edge ratio <= 1+lambda and every edge roughness <= 2 beta(lambda) "
      "(Theorem 6.1). Writes the mesh and a statistics JSON." "\n\n"
      "Exit codes: 0 complete; 2 invalid input (one `error:` line; existing output files are left "
              "untouched); 3 stopped by --max-points, --time-limit, or a first SIGINT, SIGTERM, SIGHUP, SIGQUIT, "
              "SIGXCPU, SIGUSR1, SIGUSR2 or SIGALRM (status interrupted; a second one removes the temporary files "
              "and exits with 3 at once): the partial mesh and the statistics are written; 4 internal error; "
              "5 uncertified: the run ended but some check, solver region or output defect was not settled (listed "
              "under \"unsettled\" in the statistics; mesh and statistics written, without the guarantee); 6 an "
              "output could not be written (disk full, permission, closed pipe): existing files are left untouched. "
              "Both outputs are written to temporary files (devices, FIFOs and - in place; symbolic links are "
              "followed) and renamed over their targets together, once both are complete.");
  o->surface.add_to(*sub);
  o->input_mesh_option = sub->add_option(
      "--input-mesh", o->input_mesh,
      "A closed triangle mesh (OFF/PLY/OBJ/STL; polygons are triangulated) to remesh with DelMesh (Sec. 7): it must be "
      "manifold, consistently oriented and free of self-intersections (else exit code 2). The box is its "
      "bounding box enlarged by 0.1 of its diagonal; output vertices lie on the input surface. Default outputs: "
      "<stem>_remeshed.off and .json")->type_name("FILE");
  sub->add_flag(
      "--repair", o->repair,
      "With --input-mesh: a closed mesh that intersects itself is repaired first (CGAL's autorefinement, which "
      "keeps the surface bounding the union of what the mesh encloses, else its local self-intersection removal) "
      "and then validated; one line on stderr says what changed, the statistics hold it under "
      "input_mesh.repair. Refused (exit code 2) if the result still intersects itself or is not a closed "
      "manifold; other defects are refused as without --repair");
  o->min_spacing_option = sub->add_option(
      "--min-spacing", o->run.min_spacing,
      "Termination floor H >= 0: a witness closer than H to the sample is recorded, not inserted, and the run "
      "ends uncertified (exit code 5). Default: none for --surface/--expr, 0.1 times the median edge length "
      "for --input-mesh (a triangle mesh is not smooth, so refinement need not stop at creases without it)")
      ->type_name("H")
      ->check(finite_number());
  o->feature_angle_option =
      sub->add_option_function<double>(
             "--feature-angle", [o](double degrees) { o->run.feature_angle_deg = degrees; },
             "With --input-mesh: an input edge is sharp when the normals of its two faces differ by more than DEG "
             "degrees, 0 < DEG < 180. Smooth does not refine an edge whose Voronoi facet meets a sharp edge (the "
             "normal jumps there, so the roughness bound cannot hold); such findings do not block complete when the "
             "closed-ball property is proved (docs/certificates.md)")
          ->type_name("DEG")
          ->check(finite_number())
          ->default_str(to_text(default_feature_angle_deg));
  o->no_features_option =
      sub->add_flag_callback(
             "--no-features", [o] { o->run.feature_angle_deg = std::nullopt; },
             "With --input-mesh: detect no sharp edges; Smooth then refines every edge whose roughness exceeds its "
             "bound, creases included")
          ->excludes(o->feature_angle_option);
  sub->add_option("--lambda", o->run.lambda,
                  "lambda in (0, 1/3); Theorem 6.1 covers (0, 0.06], larger values run with a warning")->type_name("L")
      ->check(finite_number())
      ->capture_default_str();
  sub->add_option_function<std::string>(
         "--phase", [o](const std::string& text) { o->run.phase = parse_enum<MeshPhase>(text, "--phase"); },
         "topology (SampleTopology only, Sec. 5) or all (DelMesh, Sec. 6.2)")
      ->type_name("PHASE")
      ->default_str(to_text(o->run.phase));
  sub->add_option_function<std::string>(
         "--solver", [o](const std::string& text) { o->run.solver = parse_enum<SolverBackend>(text, "--solver"); },
         "subdivision or homotopy (polynomial E only)")
      ->type_name("SOLVER")
      ->default_str(to_text(o->run.solver));
  sub->add_option(
      "--size-bound", o->run.size_bound,
      "H > 0 (length units of E): also refine triangles whose surface Delaunay ball radius exceeds H")->type_name("H")
      ->check(finite_number());
  sub->add_option(
      "--max-distance", o->run.max_distance,
      "delta > 0 (length units of E; --surface/--expr only): also refine until every triangle is proved within "
      "delta of the surface along the gradient flow; the run is complete only if the gradient-flow certificate "
      "then proves the two-sided Hausdorff distance <= delta (statistics \"distance\")")->type_name("DELTA")
      ->check(finite_number());
  o->out_option = sub->add_option("--out", o->out,
                                  "Mesh file, format by extension .off|.ply|.obj|.stl (binary)|.vtp (VTK XML PolyData, with "
                                  "the unit normals grad E/|grad E| at the vertices for --surface/--expr, and "
                                  "certified_distance, a proved bound on each vertex's distance to the surface, when "
                                  "the statistics' \"distance\" is certified) (default: "
                                  "<name>.off, <name> = the catalog name or 'surface' for --expr)")->type_name("FILE");
  o->stats_option =
      sub->add_option("--stats", o->stats, "Statistics JSON file, or - for stdout (default: <name>.json)")->type_name("FILE|-");
  sub->add_option("--max-points", o->run.max_points,
                  "Stop (exit code 3) once the sample holds N points, 1 <= N <= 1e9. The seeds (critical points of a "
                  "height function, at least two per component) are always inserted first, so the sample may exceed "
                  "a small N and its partial mesh may have few or no triangles")
      ->type_name("N")
      ->check(whole_number(1, max_count))
      ->capture_default_str();
  sub->add_option("--time-limit", o->run.time_limit_seconds, "Stop (exit code 3) after this many seconds (at most 1e9); 0 means none")->type_name("S")
      ->check(finite_number())
      ->capture_default_str();
  sub->add_option("--seed", o->run.seed, "Seed of the generic directions, 0 <= N < 2^64; same input and seed give the same mesh")->type_name("N")
      ->check(whole_number(0, std::numeric_limits<std::uint64_t>::max()))
      ->capture_default_str();
  sub->add_option("--threads", o->run.threads,
                  "Threads for the work of an insertion: the new Voronoi cell's certificate beside the records of "
                  "the changed Voronoi edges (two threads), and those records and the new facets on all threads "
                  "when there are enough of them to pay for the hand-off (smaller batches run on one thread); 0 means "
                  "every hardware thread. The mesh is the same for every value; at most 1024, and more than the "
                  "hardware threads run as many as there are")
      ->type_name("N")
      ->check(whole_number(0, max_threads))
      ->capture_default_str();
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  sub->add_flag("--certify", o->certify,
                "Certify the finished mesh from scratch, as `delmesh check --certify` does, and put the "
                "certificate in the statistics (\"certificate\"); a warning if it is not certified and matching");
  return {sub, [o]() { return stopped_as_limit([&] { return run_mesh(*o); }); }};
}

}  // namespace delmesh::app
