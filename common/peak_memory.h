#pragma once
//! \file peak_memory.h
//! The peak resident memory of the running program, as the kernel counts it.

#include <cstdint>
#include <fstream>
#include <string>

#include <sys/resource.h>

namespace delmesh {

//! The largest resident set size of this program's address space so far, in bytes: every page it
//! touched and held at one time, whatever allocated it (the meshing stores, the allocator's
//! caches, the libraries).  Read from VmHWM in /proc/self/status, which counts the address space
//! made by the program's exec alone; getrusage's ru_maxrss, the fallback where /proc is missing,
//! also counts the address space of the process that spawned it, up to the exec (a large parent
//! that starts the program with vfork or posix_spawn raises it).  0 if neither is available.
inline std::uint64_t peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;  // "VmHWM:   1234 kB"
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0 || usage.ru_maxrss < 0) return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;
}

}  // namespace delmesh
