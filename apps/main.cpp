//! \file main.cpp
//! The `delmesh` command line: subcommands surfaces, solve, mesh, check, report.  See command_line.h for
//! the exit codes.  Every failure ends as one `error:` line and an exit code: the program never
//! dies by a signal or an abort.  The signal handlers (apps/interrupt.h) are installed before
//! anything else (before the shared libraries are initialised, and again first in main), SIGPIPE is ignored (a closed pipe is a write error), std::terminate is
//! intercepted, and every write to standard output is checked at the end (exit code 6 if one
//! failed).

#include <csignal>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <vector>
#include <new>

#include <CLI/CLI.hpp>

#include "apps/command_line.h"
#include "apps/interrupt.h"
#include "apps/output_files.h"
#include "common/errors.h"
#include "common/huge_page_heap.h"
#include "common/run_limits.h"

namespace {

using delmesh::app::ExitCode;

[[noreturn]] void on_terminate() {
  delmesh::app::remove_registered_temporaries();
  std::cerr << "error: internal: unexpected termination" << std::endl;
  std::_Exit(static_cast<int>(ExitCode::internal_error));
}

//! Installs the signal handlers before the shared libraries' initialisers run (an entry of the
//! executable's ELF .preinit_array runs right after the dynamic loader's relocation), so that
//! the window in which a signal still has its default action is as short as a program can make
//! it; `main` installs them again first thing (idempotent).
extern "C" void delmesh_install_handlers_early(int, char**, char**) { delmesh::app::install_interrupt_handlers(); }
__attribute__((section(".preinit_array"), used)) void (*const install_handlers_early)(int, char**, char**) =
    delmesh_install_handlers_early;

int code(ExitCode c) { return static_cast<int>(c); }

//! The exit code of a command that returned `result`: an I/O error if a write to standard output
//! failed, else limit_reached if a signal arrived while it ran (it finished its output first).
int finish(ExitCode result) {
  try {
    delmesh::app::finish_standard_output();
  } catch (const delmesh::app::OutputError& e) {
    delmesh::app::print_error(e.what());
    return code(ExitCode::io_error);
  }
  if (delmesh::app::interrupt_flag().load() &&
      (result == ExitCode::complete || result == ExitCode::check_failed || result == ExitCode::uncertified)) {
    delmesh::app::print_warning("interrupted by " + delmesh::app::interrupt_signal_name() +
                                " (status interrupted) after the command had done its work: its output is complete");
    return code(ExitCode::limit_reached);
  }
  return code(result);
}

}  // namespace

int main(int argc, char** argv) {
  delmesh::app::install_interrupt_handlers();
  delmesh::back_heap_with_huge_pages();
  std::set_terminate(on_terminate);
  std::ios::sync_with_stdio(true);
  delmesh::app::route_standard_output();

  CLI::App app{
      "delmesh: meshes a smooth closed implicit surface E(x,y,z) = 0 with DelMesh (Cheng, Dey, Ramos,\n"
      "Ray), with guaranteed topology (homeomorphic to the surface) and guaranteed triangle quality.\n"
      "Exit codes: 0 complete; 1 `check --lambda` found a bound violated; 2 invalid input or usage\n"
      "(one line `error: ...` on stderr); 3 stopped by a limit (partial output written); 4 internal\n"
      "error; 5 `mesh` ended uncertified (output written, see \"unsettled\" in the statistics); 6 an\n"
      "output could not be written (disk full, permission, closed pipe; existing files untouched).\n"
      "Signals: a first SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU, SIGUSR1, SIGUSR2 or SIGALRM stops\n"
      "the run like a limit (exit code 3); a second one removes temporary files and exits with 3.",
      "delmesh"};
  app.set_version_flag("--version", "delmesh 0.1.0");
  app.require_subcommand(1);
  app.fallthrough(false);
  app.get_formatter()->column_width(34);

  std::vector<delmesh::app::Command> commands;
  try {
    commands.push_back(delmesh::app::add_surfaces_command(app));
    commands.push_back(delmesh::app::add_solve_command(app));
    commands.push_back(delmesh::app::add_mesh_command(app));
    commands.push_back(delmesh::app::add_check_command(app));
    commands.push_back(delmesh::app::add_report_command(app));
  } catch (const std::exception& e) {
    delmesh::app::print_error(std::string("internal: ") + e.what());
    return code(ExitCode::internal_error);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return finish(static_cast<ExitCode>(app.exit(e)));  // --help, --help-all, --version
    delmesh::app::print_error(e.what());
    return code(ExitCode::invalid_input);
  } catch (const std::exception& e) {
    delmesh::app::print_error(e.what());
    return code(ExitCode::invalid_input);
  }

  try {
    for (auto& command : commands) {
      if (command.subcommand->parsed()) return finish(command.run());
    }
    delmesh::app::print_error("no subcommand given (try --help)");
    return code(ExitCode::invalid_input);
  } catch (const delmesh::InvalidInput& e) {
    delmesh::app::print_error(e.what());
    return code(ExitCode::invalid_input);
  } catch (const delmesh::app::OutputError& e) {
    delmesh::app::print_error(e.what());
    return code(ExitCode::io_error);
  } catch (const delmesh::RunStopped& e) {
    // A limit or a signal before any result existed: nothing to write.
    delmesh::app::print_warning(std::string(e.reason() == delmesh::StopReason::interrupted
                                                ? "interrupted by a signal (status interrupted)"
                                                : "stopped by --time-limit (status time_limit)") +
                                " while " + e.phase() + "; no output written");
    return code(ExitCode::limit_reached);
  } catch (const std::invalid_argument& e) {
    delmesh::app::print_error(e.what());
    return code(ExitCode::invalid_input);
  } catch (const std::bad_alloc&) {
    delmesh::app::print_error("internal: out of memory");
    return code(ExitCode::internal_error);
  } catch (const std::exception& e) {
    delmesh::app::print_error(std::string("internal: ") + e.what());
    return code(ExitCode::internal_error);
  } catch (...) {
    delmesh::app::print_error("internal: unknown exception");
    return code(ExitCode::internal_error);
  }
}
