#include "solvers/primitive_query.h"

#include <cstdio>
#include <cstdlib>

#include "common/errors.h"
#include "solvers/homotopy_solver.h"
#include "solvers/univariate_isolator.h"
#include "symbolic/scalar_traits.h"

namespace delmesh {

std::string option_flag(QueryOption option) {
  const char* flag = enum_name(option);
  return flag ? flag : "--unknown-option";
}

bool is_position(QueryOption option) { return option == QueryOption::point || option == QueryOption::plane_origin; }

const Vec3& QueryOptions::at(QueryOption option) const {
  const auto it = values.find(option);
  if (it == values.end()) throw PreconditionViolation("query option " + option_flag(option) + " was not given");
  return it->second;
}

Vec3 QueryOptions::value_or(QueryOption option, const Vec3& fallback) const {
  const auto it = values.find(option);
  return it == values.end() ? fallback : it->second;
}

std::string vector_text(const Vec3& v) {
  std::string text;
  for (double x : v) {
    // The shortest %.{p}g text that reads back as exactly x.
    char buffer[32];
    for (int precision = 1; precision <= 17; ++precision) {
      std::snprintf(buffer, sizeof buffer, "%.*g", precision, x == 0 ? 0.0 : x);
      if (std::strtod(buffer, nullptr) == x) break;
    }
    text += (text.empty() ? "" : ",") + std::string(buffer);
  }
  return text;
}

PrimitiveQuery box_query(const Box3& box, const std::vector<Vec3>& parameters, std::string description) {
  PrimitiveQuery q;
  for (const Vec3& p : parameters) q.parameters.insert(q.parameters.end(), p.begin(), p.end());
  q.domain = box_domain(box);
  q.description = std::move(description);
  return q;
}

PrimitiveQuery line_query(const Box3& box, const Vec3& p, const Vec3& v) {
  PrimitiveQuery q;
  const Vec3 direction = unit_vector(v);
  q.parameters = {p[0], p[1], p[2], direction[0], direction[1], direction[2]};
  q.line = LineQuery{p, direction};
  if (const auto range = clip_line_to_box(p, direction, box)) q.domain = Domain::from_box({{(*range)[0], (*range)[1]}});
  q.description = "line " + vector_text(p) + " + t (" + vector_text(direction) + ")";
  return q;
}

PrimitiveQuery plane_query(const Box3& box, const Vec3& origin, const OrthonormalFrame& frame,
                           const std::vector<Vec3>& more, std::string description) {
  PrimitiveQuery q;
  for (const Vec3& p : {origin, frame.a, frame.b}) q.parameters.insert(q.parameters.end(), p.begin(), p.end());
  for (const Vec3& p : more) q.parameters.insert(q.parameters.end(), p.begin(), p.end());
  if (const auto section = plane_box_section(origin, frame, box)) q.domain = polygon_domain(section->polygon);
  q.description = "plane origin " + vector_text(origin) + " normal " + vector_text(frame.d) + ", frame a " +
                  vector_text(frame.a) + " b " + vector_text(frame.b) + description;
  return q;
}

CompiledPrimitive::CompiledPrimitive(PrimitiveSystem s, PolynomialFormBuild forms)
    : system(std::move(s)), compiled(system, false, forms) {
  if (!system.side_conditions.empty()) {
    side_conditions = std::make_unique<CompiledSystem>(system.side_conditions, system.unknowns, system.parameters,
                                                       false, PolynomialFormBuild::never);
  }
}

std::size_t drop_spurious_roots(const CompiledPrimitive& primitive, const std::vector<double>& parameters,
                                SolveResult& result) {
  if (!primitive.side_conditions) return 0;
  const CompiledSystem& side = *primitive.side_conditions;
  RoundingGuard guard;
  std::vector<Interval> params(parameters.begin(), parameters.end()), unknowns, values(side.n_equations());
  std::vector<CertifiedRoot> kept;
  for (CertifiedRoot& root : result.roots) {
    unknowns.clear();
    for (const auto& b : root.box.bounds) unknowns.emplace_back(b[0], b[1]);
    side.values(unknowns.data(), params.data(), values.data());
    bool spurious = false;
    for (const Interval& value : values) spurious = spurious || certainly_nonzero(value);
    if (!spurious) kept.push_back(std::move(root));
  }
  const std::size_t dropped = result.roots.size() - kept.size();
  result.roots = std::move(kept);
  return dropped;
}

SolveResult solve_query(const CompiledPrimitive& primitive, const PrimitiveQuery& query,
                        const QuerySolveOptions& options, const LinePolynomial* line_polynomial) {
  SolveResult result;
  if (!query.domain) return result;  // the line or plane misses the box: no roots
  const PrimitiveSystem& system = primitive.system;
  if (options.solver == SolverBackend::homotopy) {
    if (!system.is_square()) {
      throw InvalidInput("the homotopy solver needs a square system; " + system.name +
                         " is over-determined (use the subdivision solver)");
    }
    HomotopyOptions homotopy;
    homotopy.time_limit_seconds = options.time_limit_seconds;
    result = solve_homotopy(primitive.compiled, equation_degrees(system), query.parameters, *query.domain, homotopy);
  } else if (query.line) {
    UnivariateOptions univariate;
    univariate.box_budget = options.box_budget;
    const auto& t = query.domain->box.bounds.at(0);
    result = isolate_line_roots(primitive.compiled, line_polynomial, query.line->point, query.line->direction, t[0],
                                t[1], univariate);
  } else {
    SubdivisionOptions subdivision;
    subdivision.box_budget = options.box_budget;
    subdivision.time_limit_seconds = options.time_limit_seconds;
    subdivision.exclusion_mode = !system.is_square();
    subdivision.taylor_forms = options.taylor_forms;
    result = solve_subdivision(primitive.compiled, query.parameters, *query.domain, subdivision);
  }
  drop_spurious_roots(primitive, query.parameters, result);
  return result;
}

}  // namespace delmesh
