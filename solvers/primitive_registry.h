#pragma once
//! \file primitive_registry.h
//! The registry of numerical primitives: one row (PrimitiveInfo) per primitive carries everything
//! about it — its name, a one-line summary, the builder of its system, the query options it
//! reads and which it requires, the domain it searches, make_query (options and box → parameters
//! and domain) and a query with a known answer.  `delmesh solve` (its option checks, dispatch and
//! help), the mesher's oracle (meshing/core/surface_oracle.h), bench_solvers and docs/cli.md's table of
//! primitives all read this registry; there is no other list of primitives.
//!
//! The registry holds, in order, the rows of builtin_primitives() (solvers/primitives.cpp: the
//! six primitives of §5.2) and then the rows registered by PrimitiveRegistration objects of the
//! program (examples/extending: one file holds a builder function and its registration).
//!
//! Adding a primitive = one builder function and one row.  The builder states the unknowns, the
//! parameters, the equations, the world point and optionally side conditions (the root filter,
//! primitive_system.h); PrimitiveInfo::build derives the Jacobian.

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "solvers/primitive_query.h"
#include "symbolic/primitive_system.h"
#include "symbolic/surface.h"

namespace delmesh {

//! One option a primitive reads: which, whether it must be given, and what it means here.
struct OptionUse {
  QueryOption option;
  bool required = true;
  std::string meaning;  //!< e.g. "the line's direction v"
};
//! An option the query must give.
inline OptionUse required_option(QueryOption option, std::string meaning) { return {option, true, std::move(meaning)}; }
//! An option the query may give (make_query supplies its default).
inline OptionUse optional_option(QueryOption option, std::string meaning) { return {option, false, std::move(meaning)}; }

//! A query whose answer is known exactly: on the catalog surface `surface` (in its catalog box),
//! with `options`, the certified solve is complete and its roots are exactly `roots` (world
//! points; the tests compare to 1e-9).  The tests solve it for every row, in the library and
//! through `delmesh solve`.
struct KnownAnswer {
  std::string surface;
  QueryOptions options;
  std::vector<Vec3> roots;
};

//! One row of the registry.
struct PrimitiveInfo {
  std::string name;     //!< e.g. "surface_line"; the builder's system gets this name
  std::string summary;  //!< one line: what it solves, its equations, unknowns and parameters
  //! States the system for a surface (unknowns, parameters, equations, world point, side
  //! conditions); the Jacobian is left to build().  Its points lie on Σ: the first equation is E
  //! at the world point.
  std::function<PrimitiveSystem(const Surface&)> builder;
  std::vector<OptionUse> options;  //!< the options it reads; every other option is refused
  std::string domain;              //!< the domain make_query searches, e.g. "the box"
  //! Turns the options (the required ones are present, checked by check_query_options) and the
  //! box into the parameters, in the order of the system's parameters, and the domain.  Throws
  //! InvalidInput for values it cannot use (a zero direction, parallel directions).
  std::function<PrimitiveQuery(const QueryOptions&, const Box3&)> make_query;
  KnownAnswer example;  //!< a query with a known answer (see KnownAnswer)

  //! builder(surface) with the name set and the Jacobian derived (derive_jacobian).  Throws
  //! PreconditionViolation if the system has no unknowns or fewer equations than unknowns.
  PrimitiveSystem build(const Surface& surface) const;
  //! Throws InvalidInput if an option given is not read by this primitive ("--point is not a
  //! parameter of surface_critical") or a required one is missing ("surface_line needs --point").
  void check_query_options(const QueryOptions& given) const;
  //! check_query_options(given), then make_query(given, box).
  PrimitiveQuery query(const QueryOptions& given, const Box3& box) const;
};

//! The rows of the six primitives of §5.2, in the paper's order (solvers/primitives.cpp).
const std::vector<PrimitiveInfo>& builtin_primitives();

//! Registers one more row, appended after the built-in rows in the order of registration.  Meant
//! for a namespace-scope object in a file compiled into the program's executable (a file in a
//! static library is linked only if something else in it is used).  Throws PreconditionViolation
//! if the registry has already been read or the name is taken.
class PrimitiveRegistration {
 public:
  explicit PrimitiveRegistration(PrimitiveInfo row);
};

//! Every primitive: builtin_primitives() followed by the registered rows.  Fixed after the first
//! call (which must come after static initialisation, i.e. from main() on).
const std::vector<PrimitiveInfo>& primitive_registry();
//! The row called name; throws InvalidInput listing the known names otherwise.
const PrimitiveInfo& find_primitive(const std::string& name);
//! find_primitive(name).build(surface).
PrimitiveSystem build_primitive(const std::string& name, const Surface& surface);

//! The options of a row as text, e.g. "--point p (a point of the line) --direction v ...":
//! each option's flag and meaning, optional ones in brackets.
std::string options_text(const PrimitiveInfo& row);
//! Rows as a Markdown table | `--primitive` | solves | options | domain searched |: docs/cli.md's
//! table is primitive_table_markdown(builtin_primitives()) (tests/apps checks it is up to date).
std::string primitive_table_markdown(const std::vector<PrimitiveInfo>& rows);
//! Rows as plain text for `delmesh solve --help`: per row its name and summary, then its options
//! and its domain on an indented line.
std::string primitive_table_text(const std::vector<PrimitiveInfo>& rows);

}  // namespace delmesh
