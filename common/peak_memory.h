#pragma once
//! \file peak_memory.h
//! The peak resident memory of the running process, as the kernel counts it.

#include <cstdint>

#include <sys/resource.h>

namespace delmesh {

//! The largest resident set size this process has had so far, in bytes (getrusage's ru_maxrss,
//! which Linux reports in KiB): every page the process touched and held at one time, whatever
//! allocated it (the meshing stores, the allocator's caches, the libraries).  0 if the kernel does
//! not report it.
inline std::uint64_t peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0 || usage.ru_maxrss < 0) return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;
}

}  // namespace delmesh
