#pragma once
//! \file interrupt.h
//! Signals that ask the program to stop: SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU, SIGUSR1,
//! SIGUSR2 and SIGALRM (interrupt_signals).  `main` installs the handler before anything else, so
//! from then on the program never dies by one of them:
//!  - the first one sets interrupt_flag(), which the mesher and the certificate read between
//!    checks (DelMeshOptions::interrupt, CertificateOptions::interrupt): the run stops like a
//!    limit, with its partial output written, and exit code 3 (limit_reached); a subcommand
//!    without such a loop finishes and then exits with code 3;
//!  - a further one removes every registered temporary file (register_temporary) and ends the
//!    process with one line on stderr and `_exit(3)`; inside a DeferredExit scope it is acted on
//!    when the scope ends, so a group of renames is never cut in half.
//! The handler is async-signal-safe: it touches lock-free atomics and fixed-size arrays filled
//! before use, and calls only unlink(2), write(2) and _exit(2).  SIGPIPE is ignored, so a write
//! to a closed pipe fails with EPIPE instead of ending the process.

#include <array>
#include <atomic>
#include <csignal>
#include <cstddef>
#include <string>

namespace delmesh::app {

//! The signals handled by install_interrupt_handlers().
inline constexpr std::array<int, 8> interrupt_signals{SIGINT, SIGTERM, SIGHUP, SIGQUIT,
                                                      SIGXCPU, SIGUSR1, SIGUSR2, SIGALRM};

//! Installs the handler for every signal of interrupt_signals and ignores SIGPIPE (idempotent).
void install_interrupt_handlers();
//! Set once one of interrupt_signals has arrived.
const std::atomic<bool>& interrupt_flag();
//! The name of the first signal that arrived ("SIGINT", …), or "" if none has.
std::string interrupt_signal_name();

//! At most this many temporary files are registered at once.
inline constexpr std::size_t max_registered_temporaries = 16;

//! Registers `path` (absolute, or relative to a working directory that does not change) for
//! removal by a second signal or remove_registered_temporaries(), and returns its slot.  Throws
//! std::length_error if every slot is taken or the path is longer than the slot (4095 bytes).
std::size_t register_temporary(const std::string& path);
//! Frees a slot of register_temporary() (the file itself is the caller's: renamed or removed).
void unregister_temporary(std::size_t slot);
//! Removes every registered temporary file and frees its slot (async-signal-safe: unlink(2) only).
void remove_registered_temporaries() noexcept;

//! While one of these exists, a second signal only marks the process to end; the last
//! DeferredExit to end then removes the temporaries and ends it as the handler would have.
class DeferredExit {
 public:
  DeferredExit();
  ~DeferredExit();
  DeferredExit(const DeferredExit&) = delete;
  DeferredExit& operator=(const DeferredExit&) = delete;
};

}  // namespace delmesh::app
