#pragma once
//! \file primitive_query.h
//! One query of a primitive: the options it is asked with (points and directions, the vocabulary
//! of `delmesh solve`), the parameter vector and solver domain they turn into (PrimitiveQuery,
//! built by the primitive's make_query in its registry row, solvers/primitive_registry.h), and
//! the certified solve of that query (solve_query), shared by `delmesh solve`, the benchmarks
//! and the tests.  The spurious roots that a primitive's side conditions disprove are dropped
//! here (drop_spurious_roots).

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "common/tolerances.h"
#include "solvers/domain.h"
#include "solvers/query_geometry.h"
#include "solvers/solver_backend.h"
#include "solvers/solve_result.h"
#include "solvers/subdivision_solver.h"
#include "symbolic/compiled_system.h"
#include "symbolic/line_polynomial.h"
#include "symbolic/primitive_system.h"

namespace delmesh {

//! The options a query may give, each a vector of three numbers.  A new primitive reads some of
//! these; a primitive that needs a quantity of another kind needs a new enumerator here (and
//! `delmesh solve` offers it at once).
enum class QueryOption {
  point,         //!< --point: a position (a point of a line, a query point)
  direction,     //!< --direction: a non-zero direction
  direction2,    //!< --direction2: a second non-zero direction
  plane_origin,  //!< --plane-origin: a point of a plane
  plane_normal   //!< --plane-normal: a plane's non-zero normal
};
//! Every QueryOption, in the order of the help text.
inline constexpr std::array<QueryOption, 5> all_query_options{QueryOption::point, QueryOption::direction,
                                                              QueryOption::direction2, QueryOption::plane_origin,
                                                              QueryOption::plane_normal};
//! Prints the command-line flag, e.g. "--plane-origin".
constexpr auto enum_names(QueryOption) {
  return name_table<QueryOption>("QueryOption", {{QueryOption::point, "--point"},
                                                 {QueryOption::direction, "--direction"},
                                                 {QueryOption::direction2, "--direction2"},
                                                 {QueryOption::plane_origin, "--plane-origin"},
                                                 {QueryOption::plane_normal, "--plane-normal"}});
}
inline std::ostream& operator<<(std::ostream& out, QueryOption option) { return write_enum(out, option); }
//! The command-line flag as text, e.g. "--plane-origin".
std::string option_flag(QueryOption option);
//! True for the options that are positions (point, plane_origin), false for directions.
bool is_position(QueryOption option);

//! The options given to one query, as numbers.
struct QueryOptions {
  std::map<QueryOption, Vec3> values;

  bool has(QueryOption option) const { return values.count(option) > 0; }
  //! The value given.  Throws PreconditionViolation if the option was not given (the registry
  //! checks required options before make_query runs).
  const Vec3& at(QueryOption option) const;
  //! The value given, or `fallback`.
  Vec3 value_or(QueryOption option, const Vec3& fallback) const;
};

//! A line p + t v whose system is E(p + t v) in the single unknown t: solved by the univariate
//! isolator (univariate_isolator.h) over the domain's interval of t.
struct LineQuery {
  Vec3 point{}, direction{};
};

//! What a primitive's make_query returns: the parameter vector (in the order of the system's
//! parameters) and the domain searched.  domain is empty when there is nothing to solve (a line
//! or plane that misses the box): the answer is then complete with no roots.
struct PrimitiveQuery {
  std::vector<double> parameters;
  std::optional<Domain> domain;
  std::optional<LineQuery> line;  //!< set for a system E(p + t v) = 0 in t (see LineQuery)
  std::string description;        //!< the parameters as used, one line of text
};

//! The query of a 3-D system over the whole box, with the given vector parameters in order.
PrimitiveQuery box_query(const Box3& box, const std::vector<Vec3>& parameters, std::string description);
//! The query of a line system with parameters p, v (v normalised here): the line clipped to the
//! box (clip_line_to_box), or nothing to solve if it misses the box.
PrimitiveQuery line_query(const Box3& box, const Vec3& p, const Vec3& v);
//! The query of a plane system with parameters o, a, b and then `more`: the polygon plane ∩ box
//! in the frame (a, b) (plane_box_section, polygon_domain), or nothing to solve if the plane
//! misses the box.  Precondition: frame orthonormal.
PrimitiveQuery plane_query(const Box3& box, const Vec3& origin, const OrthonormalFrame& frame,
                           const std::vector<Vec3>& more, std::string description);
//! "x,y,z" with the shortest decimal text of each coordinate that reads back exactly.
std::string vector_text(const Vec3& v);

//! A primitive's system for one surface, compiled once: what solve_query() needs.
struct CompiledPrimitive {
  PrimitiveSystem system;
  CompiledSystem compiled;
  //! The side conditions compiled in the same unknowns and parameters; null if there are none.
  std::unique_ptr<CompiledSystem> side_conditions;

  //! Compiles `system` (its Jacobian derived, as PrimitiveInfo::build returns it), with its
  //! monomial form as `forms` says, and its side conditions (only evaluated: no monomial form).
  explicit CompiledPrimitive(PrimitiveSystem system, PolynomialFormBuild forms = PolynomialFormBuild::always);
};

//! Removes from result.roots every root on whose box (the certified box, in the unknowns) some
//! side condition evaluates, in interval arithmetic, to an interval excluding 0: such a root is
//! proved not to be one the primitive stands for.  Roots where every side condition's enclosure
//! contains 0 are kept (they are certified roots of the equations; genuine roots always are).
//! Returns the number of roots removed.  Nothing happens if primitive has no side conditions.
std::size_t drop_spurious_roots(const CompiledPrimitive& primitive, const std::vector<double>& parameters,
                                SolveResult& result);

struct QuerySolveOptions {
  SolverBackend solver = SolverBackend::subdivision;
  std::size_t box_budget = tolerances::default_box_budget;  //!< subdivision and the isolator
  double time_limit_seconds = 0;                            //!< 0: none (subdivision and homotopy)
  TaylorForms taylor_forms = TaylorForms::automatic;        //!< subdivision
};

//! Solves one query: nothing (complete, no roots) if query.domain is empty; else the homotopy
//! solver, or the univariate isolator for a LineQuery (with `line_polynomial`, the Bernstein path,
//! when given), or the subdivision solver in exclusion mode when the system is over-determined.
//! Spurious roots are dropped (drop_spurious_roots).  Throws InvalidInput when homotopy is asked
//! of a system that is not square or not polynomial in its unknowns.
SolveResult solve_query(const CompiledPrimitive& primitive, const PrimitiveQuery& query,
                        const QuerySolveOptions& options, const LinePolynomial* line_polynomial = nullptr);

}  // namespace delmesh
