//! \file solve_command.cpp
//! `delmesh solve`: one numerical primitive of §5.2 on a surface, solved by a certified solver,
//! printed in world coordinates.  The primitive's parameters are built from directions, a point
//! and a plane with solvers/query_geometry.h (the same helpers the mesher uses).

#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "apps/command_line.h"
#include "apps/commands.h"
#include "common/errors.h"
#include "common/tolerances.h"
#include "solvers/homotopy_solver.h"
#include "solvers/query_geometry.h"
#include "solvers/subdivision_solver.h"
#include "solvers/univariate_isolator.h"
#include "symbolic/compiled_system.h"
#include "symbolic/line_polynomial.h"
#include "symbolic/primitives.h"

namespace delmesh::app {

namespace {

struct SolveOptions {
  SurfaceOptions surface;
  SolveRequest request;  // all but the surface and the parameters, bound to the options directly
  std::map<std::string, std::string> parameters;          // "--direction" → its value
  std::map<std::string, CLI::Option*> parameter_options;  // "--direction" → option
  bool json = false;

  //! The options as values: the surface and the parameter options given.
  SolveRequest request_of() const {
    SolveRequest r = request;
    r.surface = surface.arguments();
    for (const auto& [name, option] : parameter_options) {
      if (option->count() > 0) r.parameters[name] = parameters.at(name);
    }
    return r;
  }
};

//! The parameter options each primitive takes, and which of them it requires.
struct PrimitiveParameters {
  std::set<std::string> allowed;
  std::set<std::string> required;
};

const std::map<std::string, PrimitiveParameters>& primitive_parameters() {
  static const std::map<std::string, PrimitiveParameters> table{
      {"surface_critical", {{"--direction"}, {}}},
      {"surface_line", {{"--point", "--direction"}, {"--point", "--direction"}}},
      {"surface_plane_contact", {{"--plane-origin", "--plane-normal"}, {"--plane-origin", "--plane-normal"}}},
      {"curve_critical",
       {{"--plane-origin", "--plane-normal", "--direction"}, {"--plane-origin", "--plane-normal", "--direction"}}},
      {"silhouette_plane",
       {{"--plane-origin", "--plane-normal", "--direction"}, {"--plane-origin", "--plane-normal", "--direction"}}},
      {"silhouette_critical", {{"--direction", "--direction2"}, {"--direction", "--direction2"}}},
  };
  return table;
}

double dot(const Vec3& p, const Vec3& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }
Vec3 cross(const Vec3& p, const Vec3& q) {
  return {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
}
void append(std::vector<double>& to, const Vec3& v) { to.insert(to.end(), v.begin(), v.end()); }

//! A primitive's parameter vector and solver domain.  `empty`: the line or plane misses the box,
//! so there is nothing to solve (no roots).
struct Query {
  std::vector<double> parameters;
  Domain domain;
  bool line = false;
  Vec3 line_point{}, line_direction{};
  bool empty = false;
  std::string description;  // the parameters as used, for the text output
};

std::string text_of(const Vec3& v) {
  return format_number(v[0]) + "," + format_number(v[1]) + "," + format_number(v[2]);
}

Query build_query(const SolveRequest& o, const Box3& box) {
  Query q;
  const std::string& name = o.primitive;
  auto vector_of = [&](const std::string& option) { return parse_vector3(o.parameters.at(option), option); };
  if (name == "surface_critical") {
    const Vec3 d = o.parameters.count("--direction") > 0 ? vector_of("--direction") : Vec3{0, 0, 1};
    const OrthonormalFrame f = orthonormal_frame(d);
    append(q.parameters, f.a);
    append(q.parameters, f.b);
    q.domain = box_domain(box);
    q.description = "direction " + text_of(f.d);
  } else if (name == "surface_line") {
    const Vec3 p = vector_of("--point");
    const Vec3 v = unit_vector(vector_of("--direction"));
    append(q.parameters, p);
    append(q.parameters, v);
    q.line = true;
    q.line_point = p;
    q.line_direction = v;
    const auto range = clip_line_to_box(p, v, box);
    if (!range) {
      q.empty = true;
    } else {
      q.domain = Domain::from_box({{(*range)[0], (*range)[1]}});
    }
    q.description = "line " + text_of(p) + " + t (" + text_of(v) + ")";
  } else if (name == "surface_plane_contact" || name == "curve_critical" ||
             name == "silhouette_plane") {
    const Vec3 origin = vector_of("--plane-origin");
    const Vec3 normal = unit_vector(vector_of("--plane-normal"));
    OrthonormalFrame frame = orthonormal_frame(normal);
    Vec3 d{};
    if (name == "curve_critical") {
      // The direction d must be parallel to the plane: its component in the plane becomes a.
      const Vec3 given = vector_of("--direction");
      const double along = dot(given, normal);
      const Vec3 in_plane{given[0] - along * normal[0], given[1] - along * normal[1], given[2] - along * normal[2]};
      if (std::sqrt(dot(in_plane, in_plane)) <= 1e-12 * std::sqrt(dot(given, given))) {
        throw InvalidInput("--direction must not be normal to the plane for curve_critical");
      }
      frame.a = unit_vector(in_plane);
      frame.b = cross(frame.d, frame.a);
    } else if (name == "silhouette_plane") {
      d = unit_vector(vector_of("--direction"));
    }
    append(q.parameters, origin);
    append(q.parameters, frame.a);
    append(q.parameters, frame.b);
    if (name == "silhouette_plane") append(q.parameters, d);
    const auto section = plane_box_section(origin, frame, box);
    if (!section) {
      q.empty = true;
    } else {
      q.domain = polygon_domain(section->polygon);
    }
    q.description = "plane origin " + text_of(origin) + " normal " + text_of(normal) + ", frame a " +
                    text_of(frame.a) + " b " + text_of(frame.b);
    if (name == "silhouette_plane") q.description += ", direction " + text_of(d);
  } else if (name == "silhouette_critical") {
    const Vec3 d = unit_vector(vector_of("--direction"));
    const Vec3 e = unit_vector(vector_of("--direction2"));
    const Vec3 c = cross(d, e);
    if (std::sqrt(dot(c, c)) <= 1e-12) throw InvalidInput("--direction and --direction2 must not be parallel");
    append(q.parameters, d);
    append(q.parameters, e);
    q.domain = box_domain(box);
    q.description = "direction " + text_of(d) + ", direction2 " + text_of(e);
  } else {
    throw InvalidInput("delmesh solve does not know the parameters of primitive " + name);
  }
  return q;
}

void check_parameter_options(const SolveRequest& o) {
  bool registered = false;
  std::string known;
  for (const PrimitiveInfo& info : primitive_registry()) {
    registered = registered || info.name == o.primitive;
    known += (known.empty() ? "" : ", ") + info.name;
  }
  if (!registered) throw InvalidInput("unknown primitive '" + o.primitive + "' (known: " + known + ")");
  const auto entry = primitive_parameters().find(o.primitive);
  if (entry == primitive_parameters().end()) {
    throw InvalidInput("delmesh solve does not know the parameters of primitive " + o.primitive);
  }
  for (const auto& [option, value] : o.parameters) {
    if (entry->second.allowed.count(option) == 0) throw InvalidInput(option + " is not a parameter of " + o.primitive);
  }
  for (const std::string& option : entry->second.required) {
    if (o.parameters.count(option) == 0) throw InvalidInput(o.primitive + " needs " + option);
  }
}

//! World bounding box of a solver box: the compiled world point (affine in the unknowns)
//! evaluated over intervals.
std::array<std::array<double, 2>, 3> world_box(const CompiledSystem& system, const std::vector<double>& parameters,
                                               const SolverBox& box) {
  RoundingGuard guard;
  std::vector<Interval> unknowns, params;
  for (const auto& b : box.bounds) unknowns.emplace_back(b[0], b[1]);
  for (double p : parameters) params.emplace_back(p);
  Interval xyz[3];
  system.world_point(unknowns.data(), params.data(), xyz);
  std::array<std::array<double, 2>, 3> out{};
  for (int i = 0; i < 3; ++i) out[i] = {xyz[i].inf(), xyz[i].sup()};
  return out;
}

template <class T>
std::string to_text(const T& value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

}  // namespace

const std::vector<std::string>& solve_parameter_options() {
  static const std::vector<std::string> names{"--direction", "--direction2", "--point", "--plane-origin",
                                              "--plane-normal"};
  return names;
}

SolveOutcome solve_primitive(const SolveRequest& o) {
  if (o.solver != "subdivision" && o.solver != "homotopy") {
    throw InvalidInput("--solver: expected subdivision or homotopy, got '" + o.solver + "'");
  }
  if (o.max_boxes < 1) throw InvalidInput("--max-boxes must be at least 1");
  const std::map<std::string, TaylorForms> taylor_choices{
      {"automatic", TaylorForms::automatic}, {"always", TaylorForms::always}, {"never", TaylorForms::never}};
  if (!taylor_choices.count(o.taylor_forms))
    throw InvalidInput("--taylor-forms: expected automatic, always or never, got '" + o.taylor_forms + "'");
  if (!std::isfinite(o.time_limit) || o.time_limit < 0 || o.time_limit > max_time_limit_seconds) {
    throw InvalidInput("--time-limit must be >= 0 and <= 1e9 seconds (0: none), got " + format_number(o.time_limit));
  }
  check_parameter_options(o);
  const SurfaceInput input = o.surface.resolve();
  const Query query = build_query(o, input.box);
  const PrimitiveSystem system = build_primitive(o.primitive, input.surface);
  const CompiledSystem compiled(system);

  SolveResult result;
  const auto start = std::chrono::steady_clock::now();
  if (query.empty) {
    result.status = SolveStatus::complete;
  } else if (o.solver == "homotopy") {
    if (!system.is_square()) {
      throw InvalidInput("--solver homotopy needs a square system; " + o.primitive +
                         " is over-determined (use --solver subdivision)");
    }
    HomotopyOptions options;
    options.time_limit_seconds = o.time_limit;
    result = solve_homotopy(compiled, equation_degrees(system), query.parameters, query.domain, options);
  } else if (query.line) {
    std::unique_ptr<LinePolynomial> polynomial;
    if (input.surface.is_polynomial()) polynomial = std::make_unique<LinePolynomial>(input.surface);
    UnivariateOptions options;
    options.box_budget = o.max_boxes;
    const auto& t = query.domain.box.bounds[0];
    result = isolate_line_roots(compiled, polynomial.get(), query.line_point, query.line_direction, t[0], t[1],
                                options);
  } else {
    SubdivisionOptions options;
    options.box_budget = o.max_boxes;
    options.time_limit_seconds = o.time_limit;
    options.exclusion_mode = !system.is_square();
    options.taylor_forms = taylor_choices.at(o.taylor_forms);
    result = solve_subdivision(compiled, query.parameters, query.domain, options);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<WorldBox> undecided;
  for (const UndecidedBox& u : result.undecided) undecided.push_back(world_box(compiled, query.parameters, u.box));
  const std::string solver = query.line && o.solver == "subdivision" ? "univariate isolator" : o.solver;
  return SolveOutcome{input, query.description, solver, std::move(result), std::move(undecided), seconds};
}

nlohmann::ordered_json SolveOutcome::to_json() const {
  nlohmann::ordered_json out;
  out["status"] = to_text(result.status);
  out["roots"] = nlohmann::ordered_json::array();
  for (const CertifiedRoot& r : result.roots) out["roots"].push_back({r.world[0], r.world[1], r.world[2]});
  out["undecided"] = nlohmann::ordered_json::array();
  for (const auto& b : undecided) {
    out["undecided"].push_back({{b[0][0], b[0][1]}, {b[1][0], b[1][1]}, {b[2][0], b[2][1]}});
  }
  out["boxes"] = result.counters.boxes;
  out["seconds"] = seconds;
  return out;
}

namespace {

ExitCode run_solve(const SolveOptions& options) {
  const SolveOutcome outcome = solve_primitive(options.request_of());
  const SolveRequest& o = options.request;
  const SurfaceInput& input = outcome.input;
  const SolveResult& result = outcome.result;
  const auto& undecided = outcome.undecided;

  if (options.json) {
    print_json(std::cout, outcome.to_json());
  } else {
    std::cout << "primitive: " << o.primitive << " (" << outcome.description << ")\n";
    std::cout << "surface:   " << input.name << ": " << input.surface.text() << " = 0 in " << format_box(input.box)
              << "\n";
    std::cout << "solver:    " << outcome.solver << "\n";
    std::cout << "status:    " << result.status << "\n";
    std::cout << "roots:     " << result.roots.size() << "\n";
    for (const CertifiedRoot& r : result.roots) {
      std::cout << "  " << format_number(r.world[0]) << " " << format_number(r.world[1]) << " "
                << format_number(r.world[2]) << "\n";
    }
    std::cout << "undecided: " << undecided.size() << "\n";
    for (std::size_t i = 0; i < undecided.size(); ++i) {
      const auto& b = undecided[i];
      std::cout << "  [" << format_number(b[0][0]) << ", " << format_number(b[0][1]) << "] x ["
                << format_number(b[1][0]) << ", " << format_number(b[1][1]) << "] x [" << format_number(b[2][0])
                << ", " << format_number(b[2][1]) << "]  (" << result.undecided[i].reason << ")\n";
    }
    std::cout << "boxes:     " << result.counters.boxes << "\n";
    std::cout << "seconds:   " << outcome.seconds << "\n";
    std::cout.flush();
  }
  return ExitCode::complete;
}

}  // namespace

Command add_solve_command(CLI::App& parent) {
  auto o = std::make_shared<SolveOptions>();
  CLI::App* sub = parent.add_subcommand("solve", "Solve one numerical primitive of Sec. 5.2 (certified)");
  sub->footer(
      "Solve one numerical primitive of Sec. 5.2 on a surface with a certified solver and print its roots in "
      "world coordinates, and the regions it could neither exclude nor certify (undecided)." "\n\n"
      
      "Parameters per primitive:\n"
      "  surface_critical       [--direction] (default 0,0,1), domain: the box\n"
      "  surface_line           --point --direction, domain: the line clipped to the box\n"
      "  surface_plane_contact  --plane-origin --plane-normal, domain: the polygon plane & box\n"
      "  curve_critical         --plane-origin --plane-normal --direction (in-plane)\n"
      "  silhouette_plane       --plane-origin --plane-normal --direction\n"
      "  silhouette_critical    --direction --direction2, domain: the box\n"
      "Exit codes: 0 solved (whatever the status), 2 invalid input, 4 internal error.");
  o->surface.add_to(*sub);
  std::string names;
  for (const PrimitiveInfo& info : primitive_registry()) names += (names.empty() ? "" : "|") + info.name;
  sub->add_option("--primitive", o->request.primitive, names)->required()->type_name("P");
  o->parameter_options["--direction"] = sub->add_option(
      "--direction", o->parameters["--direction"],
      "dx,dy,dz: height direction (surface_critical, default 0,0,1), line direction (surface_line), "
      "in-plane direction (curve_critical; its component in the plane is used), silhouette direction "
      "(silhouette_plane, silhouette_critical)")
      ->type_name("DX,DY,DZ");
  o->parameter_options["--direction2"] = sub->add_option(
      "--direction2", o->parameters["--direction2"],
      "dx,dy,dz: direction d' of the critical points of the silhouette (silhouette_critical)")
      ->type_name("DX,DY,DZ");
  o->parameter_options["--point"] =
      sub->add_option("--point", o->parameters["--point"],
                      "px,py,pz: a point of the line (surface_line); the line is clipped to the box")
          ->type_name("PX,PY,PZ");
  o->parameter_options["--plane-origin"] = sub->add_option(
      "--plane-origin", o->parameters["--plane-origin"],
      "ox,oy,oz: a point of the plane (surface_plane_contact, curve_critical, silhouette_plane); the domain is the "
      "polygon plane & box")
      ->type_name("OX,OY,OZ");
  o->parameter_options["--plane-normal"] =
      sub->add_option("--plane-normal", o->parameters["--plane-normal"], "nx,ny,nz: the plane's normal (non-zero)")
      ->type_name("NX,NY,NZ");
  sub->add_option("--solver", o->request.solver,
                  "subdivision (certified interval subdivision; the univariate isolator for surface_line) "
                  "or homotopy (total-degree homotopy, polynomial E and square systems only)")
      ->capture_default_str()
      ->type_name("SOLVER");
  sub->add_option("--taylor-forms", o->request.taylor_forms,
                  "automatic, always or never: run the subdivision solver on Taylor forms of a polynomial system "
                  "(automatic: for dense expanded polynomials, where they are faster)")
      ->capture_default_str()
      ->type_name("MODE");
  sub->add_option("--max-boxes", o->request.max_boxes, "box budget of the subdivision solver and the isolator (1 to 1e9)")
      ->check(whole_number(1, max_count))
      ->capture_default_str()
      ->type_name("N");
  sub->add_option("--time-limit", o->request.time_limit, "seconds, at most 1e9; 0 means no limit (subdivision and homotopy)")
      ->check(finite_number())
      ->capture_default_str()
      ->type_name("S");
  sub->add_flag("--json", o->json,
                "Print {\"status\", \"roots\": [[x,y,z],...], \"undecided\": [[[lo,hi],[lo,hi],[lo,hi]],...] "
                "(world bounding boxes), \"boxes\", \"seconds\"}");
  return {sub, [o]() { return run_solve(*o); }};
}

}  // namespace delmesh::app
