#pragma once
//! \file interrupt.h
//! SIGINT and SIGTERM during a long run: the first one sets a flag that the mesher reads between
//! checks (DelMeshOptions::interrupt), so the run stops like a limit, with its partial mesh and
//! statistics written; a second one ends the process at once with the signal's default action.
//! The handler only stores to a lock-free atomic and, on the second signal, restores the default
//! action and raises the signal again: both are async-signal-safe.

#include <atomic>

namespace delmesh::app {

//! Installs the handlers for SIGINT and SIGTERM (idempotent).
void install_interrupt_handlers();
//! Set once a SIGINT or SIGTERM has arrived.
const std::atomic<bool>& interrupt_flag();

}  // namespace delmesh::app
