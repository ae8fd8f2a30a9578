#pragma once
//! \file kernel_memory.h
//! Test support: the kernel's memory settings that the huge-page heap depends on.

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace delmesh::test {

//! The kernel's transparent huge page mode: "always", "madvise" or "never" (empty if unknown).
inline std::string huge_page_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  const auto open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos ? "" : line.substr(open + 1, close - open - 1);
}

//! Whether the kernel charges untouched address space (vm.overcommit_memory = 2).
inline bool strict_overcommit() {
  std::ifstream in("/proc/sys/vm/overcommit_memory");
  int mode = 0;
  return in >> mode && mode == 2;
}

//! One mapping of /proc/self/smaps: its address range [lo, hi), its header line, whether it is
//! advised MADV_HUGEPAGE (VmFlags "hg") and its kB of anonymous huge pages.
struct Mapping {
  std::uintptr_t lo = 0, hi = 0;
  std::string header;
  bool advised = false;
  long huge_kb = 0;
};

//! This process's mappings (/proc/self/smaps: a header line "lo-hi perms … [name]" per mapping,
//! then its "Field: value" lines).
inline std::vector<Mapping> mappings() {
  std::ifstream in("/proc/self/smaps");
  std::vector<Mapping> all;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string first;
    fields >> first;
    if (first.empty()) continue;
    if (first.back() != ':') {
      const auto dash = first.find('-');
      if (dash == std::string::npos) continue;
      Mapping m;
      m.lo = std::stoull(first.substr(0, dash), nullptr, 16);
      m.hi = std::stoull(first.substr(dash + 1), nullptr, 16);
      m.header = line;
      all.push_back(m);
    } else if (!all.empty() && first == "AnonHugePages:") {
      fields >> all.back().huge_kb;
    } else if (!all.empty() && first == "VmFlags:") {
      std::string flag;
      while (fields >> flag) all.back().advised = all.back().advised || flag == "hg";
    }
  }
  return all;
}

}  // namespace delmesh::test
