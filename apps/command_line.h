#pragma once
//! \file command_line.h
//! What the subcommands of `delmesh` share: the exit-code policy, the surface options
//! (--surface | --expr with --box), parsing of vectors, and messages.  Output files are
//! apps/output_files.h, signals apps/interrupt.h.
//!
//! Exit codes (the program's contract, also listed in docs/cli.md):
//!   0  complete;
//!   1  `delmesh check --lambda L` ran and some bound of Theorem 6.1 failed;
//!   2  invalid input or usage: exactly one line on stderr, beginning `error:`;
//!   3  stopped by a limit (--max-points, --time-limit) or a signal (apps/interrupt.h): the partial
//!      mesh and statistics are written; a subcommand without outputs to stop finishes first;
//!   4  internal error (an unexpected exception): one line `error: internal: …` on stderr;
//!   5  uncertified: the run ended but something was not settled; mesh and statistics are written;
//!   6  an output could not be written (disk full, permission denied, closed pipe; OutputError of
//!      apps/output_files.h): one line `error:` on stderr; existing output files are left as they were.

#include <array>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/enum_names.h"
#include "symbolic/surface.h"

namespace delmesh::app {

enum class ExitCode : int {
  complete = 0,
  check_failed = 1,
  invalid_input = 2,
  limit_reached = 3,
  internal_error = 4,
  uncertified = 5,
  io_error = 6
};
constexpr auto enum_names(ExitCode) {
  return name_table<ExitCode>("ExitCode", {{ExitCode::complete, "complete"},
                                           {ExitCode::check_failed, "check_failed"},
                                           {ExitCode::invalid_input, "invalid_input"},
                                           {ExitCode::limit_reached, "limit_reached"},
                                           {ExitCode::internal_error, "internal_error"},
                                           {ExitCode::uncertified, "uncertified"},
                                           {ExitCode::io_error, "io_error"}});
}
inline std::ostream& operator<<(std::ostream& out, ExitCode code) { return write_enum(out, code); }

//! The action of a subcommand, run after parsing when the subcommand was selected.
using Action = std::function<ExitCode()>;

//! A registered subcommand and its action.
struct Command {
  CLI::App* subcommand = nullptr;
  Action run;
};
//! Each subcommand registers itself (options, help) on the main app and returns its action.
Command add_surfaces_command(CLI::App& parent);
Command add_solve_command(CLI::App& parent);
Command add_mesh_command(CLI::App& parent);
Command add_check_command(CLI::App& parent);
Command add_report_command(CLI::App& parent);

//! Ranges of the numeric options (input limits, not tolerances).  A count (--max-points,
//! --max-boxes) is at most max_count; a time limit at most max_time_limit_seconds
//! (meshing/driver/del_mesh.h); --threads at most max_threads (more than the hardware threads run as
//! many as there are).
inline constexpr unsigned long long max_count = 1000000000ULL;
inline constexpr unsigned long long max_threads = 1024;

//! A CLI11 validator for an integer option: the whole text is a decimal integer (an optional
//! sign, then digits; no fraction, exponent, spaces or other text) in [min, max].  Otherwise the
//! option fails with "OPTION: expected a whole number from MIN to MAX, got 'TEXT'".  It runs
//! before CLI11's conversion, so a negative count never wraps around to a huge unsigned one.
CLI::Validator whole_number(unsigned long long min, unsigned long long max);
//! A CLI11 validator for a real option: the whole text is a finite decimal number (not nan, not
//! inf, not one that overflows to inf such as 1e400, not a nonzero one that underflows to 0 such
//! as 1e-400; subnormal numbers such as 5e-324 are finite and accepted).  The message says which:
//! "expected a finite number, got '1e400' (it overflows double precision: …)", "'1e-400'
//! underflows double precision: …".  Range checks are the command's.
CLI::Validator finite_number();

//! The checks of whole_number() and finite_number() on an option's text, for callers without a
//! command line: throw InvalidInput with the message the command line gives,
//! "OPTION: expected …, got 'TEXT'".
void require_whole_number(const std::string& option, std::string text, unsigned long long min,
                          unsigned long long max);
void require_finite_number(const std::string& option, std::string text);

//! Parses "a,b,c" into three finite doubles (subnormal numbers included); throws InvalidInput
//! naming `option` otherwise: "expected three numbers" for text that is not three numbers, the
//! messages of finite_number() for a number that is nan, inf, overflows or underflows to 0.
std::array<double, 3> parse_vector3(const std::string& text, const std::string& option);

//! A surface given on the command line, resolved: its name (catalog name, or "surface" for
//! --expr), E, and the box Σ must lie in.
struct SurfaceInput {
  std::string name;
  Surface surface;
  Box3 box;
};

//! The values of --surface NAME, --expr E, --box x0,x1,y0,y1,z0,z1 (nullopt: not given).
struct SurfaceArguments {
  std::optional<std::string> surface, expr, box;
  //! Exactly one of --surface and --expr; --expr needs --box; --box with --surface replaces the
  //! catalog box.  Throws InvalidInput (from the catalog, the parser, or here).
  SurfaceInput resolve() const;
};

//! The options --surface NAME, --expr E, --box x0,x1,y0,y1,z0,z1 of `solve` and `mesh`.
struct SurfaceOptions {
  std::string surface;
  std::string expr;
  std::string box;
  CLI::Option* surface_option = nullptr;
  CLI::Option* expr_option = nullptr;
  CLI::Option* box_option = nullptr;

  //! Adds the three options to app.
  void add_to(CLI::App& app);
  //! True if --surface or --expr was given.
  bool given() const;
  //! The options given, as values.
  SurfaceArguments arguments() const;
  //! arguments().resolve().
  SurfaceInput resolve() const;
};

//! The shortest decimal text that reads back as exactly x.
std::string format_number(double x);
//! "x0,x1,y0,y1,z0,z1", the --box syntax.
std::string format_box(const Box3& box);

//! Lower-case extension of path including the dot ("" if none).
std::string extension_of(const std::string& path);

//! Prints a JSON object with one top-level key per line, each value on one line (readable and
//! still valid JSON); other values as one line.
void print_json(std::ostream& out, const nlohmann::ordered_json& object);

//! `text` with every control character (bytes 0x00–0x1f and 0x7f, e.g. ESC) written as \xHH, so
//! that echoing user text cannot drive the terminal.
std::string printable(const std::string& text);
//! `message` on one line: line breaks become spaces, trailing spaces go, other control
//! characters are escaped (printable()).
std::string one_line(std::string message);
//! Prints `error: <message>` (newlines flattened) as a single line on stderr.
void print_error(const std::string& message);
//! Prints `warning: <message>` on stderr.
void print_warning(const std::string& message);

}  // namespace delmesh::app
