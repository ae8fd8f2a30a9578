//! \file solve_command.cpp
//! `delmesh solve`: one numerical primitive of the registry (solvers/primitive_registry.h) on a
//! surface, solved by a certified solver, printed in world coordinates.  The registry row checks
//! the options, turns them and the box into the parameters and the domain, and supplies the help
//! text; solve_query (solvers/primitive_query.h) picks the solver.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "apps/command_line.h"
#include "apps/commands.h"
#include "apps/interrupt.h"
#include "apps/phase_watchdog.h"
#include "common/enum_names.h"
#include "common/errors.h"
#include "common/run_limits.h"
#include "common/tolerances.h"
#include "solvers/primitive_query.h"
#include "solvers/primitive_registry.h"
#include "symbolic/compiled_system.h"
#include "symbolic/line_polynomial.h"

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

//! The primitive's row, and the parameter options given as numbers (their text parsed).
std::pair<const PrimitiveInfo*, QueryOptions> query_options(const SolveRequest& o) {
  const PrimitiveInfo& row = find_primitive(o.primitive);
  QueryOptions given;
  for (QueryOption option : all_query_options) {
    const auto it = o.parameters.find(option_flag(option));
    if (it != o.parameters.end()) given.values[option] = parse_vector3(it->second, it->first);
  }
  for (const auto& entry : o.parameters) {
    const bool known = std::any_of(all_query_options.begin(), all_query_options.end(),
                                   [&](QueryOption option) { return option_flag(option) == entry.first; });
    if (!known) throw InvalidInput("delmesh solve has no parameter option " + entry.first);
  }
  row.check_query_options(given);
  return {&row, given};
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
  static const std::vector<std::string> names = [] {
    std::vector<std::string> flags;
    for (QueryOption option : all_query_options) flags.push_back(option_flag(option));
    return flags;
  }();
  return names;
}

SolveOutcome solve_primitive(const SolveRequest& o) {
  const SolverBackend solver = parse_enum<SolverBackend>(o.solver, "--solver");
  if (o.max_boxes < 1) throw InvalidInput("--max-boxes must be at least 1");
  const TaylorForms taylor_forms = parse_enum<TaylorForms>(o.taylor_forms, "--taylor-forms");
  if (!std::isfinite(o.time_limit) || o.time_limit < 0 || o.time_limit > max_time_limit_seconds) {
    throw InvalidInput("--time-limit must be >= 0 and <= 1e9 seconds (0: none), got " + format_number(o.time_limit));
  }
  const auto [row, given] = query_options(o);
  const SurfaceInput input = o.surface.resolve();
  const PrimitiveQuery query = row->make_query(given, input.box);
  const CompiledPrimitive primitive(row->build(input.surface));
  if (solver == SolverBackend::homotopy && !primitive.system.is_square()) {
    throw InvalidInput("--solver homotopy needs a square system; " + o.primitive +
                       " is over-determined (use --solver subdivision)");
  }
  std::unique_ptr<LinePolynomial> polynomial;
  if (query.line && query.domain && input.surface.is_polynomial()) {
    polynomial = std::make_unique<LinePolynomial>(input.surface);
  }
  QuerySolveOptions options;
  options.solver = solver;
  options.box_budget = o.max_boxes;
  options.time_limit_seconds = o.time_limit;
  // Under a command's limits (RunLimits::current()) the time limit counts from the command's start.
  if (const std::optional<double> left = RunLimits::current().seconds_left())
    options.time_limit_seconds = std::max(*left, std::numeric_limits<double>::denorm_min());
  options.taylor_forms = taylor_forms;

  const auto start = std::chrono::steady_clock::now();
  SolveResult result = solve_query(primitive, query, options, polynomial.get());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<WorldBox> undecided;
  for (const UndecidedBox& u : result.undecided) {
    undecided.push_back(world_box(primitive.compiled, query.parameters, u.box));
  }
  const std::string solver_name = query.line && solver == SolverBackend::subdivision ? "univariate isolator" : o.solver;
  return SolveOutcome{input, query.description, solver_name, std::move(result), std::move(undecided), seconds};
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

//! solve_primitive() under the command's limits: the solver stops at the deadline with its
//! partial result; parsing and compiling E, which cannot stop themselves, are ended by the
//! watchdog, as is a solve still running PhaseWatchdog::solve_grace after the deadline.
SolveOutcome limited_solve(const SolveRequest& request) {
  const double seconds = std::min(request.time_limit, max_time_limit_seconds);
  const auto start = RunLimits::Clock::now();
  const RunLimits limits = RunLimits::after(seconds, &interrupt_flag(), start);
  const RunLimits::Scope scope(limits);
  PhaseWatchdog watchdog(
      seconds > 0 ? RunLimits::after(seconds + PhaseWatchdog::solve_grace.count(), &interrupt_flag(), start) : limits);
  const PhaseWatchdog::Phase phase(watchdog, "parsing, compiling and solving");
  return solve_primitive(request);
}

ExitCode run_solve(const SolveOptions& options) {
  const SolveOutcome outcome = limited_solve(options.request_of());
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
  sub->footer("Solve one numerical primitive on a surface with a certified solver and print its roots in world "
              "coordinates, and the regions it could neither exclude nor certify (undecided).\n\n"
              "Primitives (the registry, solvers/primitive_registry.h), their options and domains:\n" +
              primitive_table_text(primitive_registry()) +
              "Exit codes: 0 solved (whatever the status), 2 invalid input, 3 interrupted by a signal "
              "(SIGINT, SIGTERM, ...), 4 internal error, 6 the answer could not be "
              "written to standard output.");
  o->surface.add_to(*sub);
  std::string names;
  for (const PrimitiveInfo& info : primitive_registry()) names += (names.empty() ? "" : "|") + info.name;
  sub->add_option("--primitive", o->request.primitive, names)->required()->type_name("P");
  for (QueryOption option : all_query_options) {
    // The help of an option: its kind, and what it means to each primitive that reads it.
    std::string help = is_position(option) ? "x,y,z: a point" : "dx,dy,dz: a non-zero direction";
    std::string uses;
    for (const PrimitiveInfo& info : primitive_registry()) {
      for (const OptionUse& use : info.options) {
        if (use.option == option) uses += (uses.empty() ? "" : "; ") + info.name + ": " + use.meaning;
      }
    }
    help += " (" + (uses.empty() ? std::string("read by no primitive") : uses) + ")";
    const std::string flag = option_flag(option);
    o->parameter_options[flag] =
        sub->add_option(flag, o->parameters[flag], help)->type_name(is_position(option) ? "X,Y,Z" : "DX,DY,DZ");
  }
  sub->add_option("--solver", o->request.solver,
                  "subdivision (certified interval subdivision; the univariate isolator for a line) "
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
  return {sub, [o]() { return stopped_as_limit([&] { return run_solve(*o); }); }};
}

}  // namespace delmesh::app
