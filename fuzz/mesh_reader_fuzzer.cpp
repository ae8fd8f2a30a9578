//! \file mesh_reader_fuzzer.cpp
//! libFuzzer targets fuzz_read_off, fuzz_read_ply, fuzz_read_obj (DELMESH_FUZZ_EXTENSION): the
//! input is written to a scratch file with that extension, then read as `delmesh check` and
//! `delmesh mesh --input-mesh` do: read_triangle_soup, check_mesh on the soup, read_mesh and
//! check_mesh on the mesh.  Each either succeeds or throws InvalidInput; anything else is a finding.

#include <unistd.h>

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fuzz/fuzz_support.h"
#include "meshing/mesh_checker.h"
#include "meshing/mesh_io.h"

#ifndef DELMESH_FUZZ_EXTENSION
#error "DELMESH_FUZZ_EXTENSION (.off, .ply or .obj) must be defined"
#endif

namespace {

//! Inputs of crashes already found and kept under fuzz/crashes/ that are not fixed yet; they are
//! skipped so that fuzzing gets past them, unless DELMESH_FUZZ_ALL_INPUTS=1.  Remove a rule when its
//! crash is fixed.
//!   fuzz_read_off: CGAL's File_scanner_OFF::scan_color reads past its entries (heap overflow) and
//!     converts out-of-range colours to unsigned char: any OFF variant with vertex colours (COFF...).
//!   fuzz_read_off: CGAL's File_scanner_OFF reads face sizes and indices as double and casts them
//!     to std::size_t: undefined for a negative one ("-4"); any OFF with a '-' is skipped (this also
//!     skips negative coordinates).
//!   fuzz_read_ply: CGAL's PLY_reader::init calls back() on its empty element list for a "property"
//!     line before the first "element" line (header keywords read as CGAL does, word by word).
bool known_crash(const std::string& text) {
  static const bool skip = [] {
    const char* all = std::getenv("DELMESH_FUZZ_ALL_INPUTS");
    const bool s = !(all && std::string(all) == "1");
    if (s) std::fprintf(stderr, "fuzz: skipping the inputs of known crashes (DELMESH_FUZZ_ALL_INPUTS=1 runs them)\n");
    return s;
  }();
  if (!skip) return false;
  const std::string extension = DELMESH_FUZZ_EXTENSION;
  if (extension == ".off") {
    // The first token after comments and white space is the header keyword.
    std::size_t at = 0;
    while (at < text.size()) {
      if (std::isspace(static_cast<unsigned char>(text[at]))) {
        ++at;
      } else if (text[at] == '#') {
        at = text.find('\n', at);
        if (at == std::string::npos) return false;
      } else {
        break;
      }
    }
    std::size_t end = at;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
    return text.substr(at, end - at).find('C') != std::string::npos || text.find('-') != std::string::npos;
  }
  if (extension == ".ply") {
    std::istringstream header(text);
    for (std::string line; std::getline(header, line);) {
      std::istringstream words(line);
      std::string keyword;
      words >> keyword;
      if (keyword == "element" || keyword == "end_header") return false;
      if (keyword == "property") return true;
    }
  }
  return false;
}

//! One scratch file per process (libFuzzer's -jobs/-fork run several), removed at exit.
const std::string& scratch_path() {
  static const std::string path = [] {
    std::error_code ec;
    std::filesystem::path dir = std::filesystem::is_directory("/dev/shm", ec)
                                    ? std::filesystem::path("/dev/shm")
                                    : std::filesystem::temp_directory_path();
    std::string p = (dir / ("delmesh-fuzz-" + std::to_string(::getpid()) + DELMESH_FUZZ_EXTENSION)).string();
    static std::string to_remove;
    to_remove = p;
    std::atexit([] { std::remove(to_remove.c_str()); });
    return p;
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (known_crash(std::string(reinterpret_cast<const char*>(data), size))) return 0;
  const std::string& path = scratch_path();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) {
      std::fprintf(stderr, "fuzz: cannot write the scratch file %s\n", path.c_str());
      std::abort();
    }
  }
  using delmesh::fuzz::expect_valid_or_invalid_input;
  delmesh::TriangleSoup soup;
  const bool read = expect_valid_or_invalid_input("read_triangle_soup", [&] { soup = delmesh::read_triangle_soup(path); });
  if (!read) return 0;
  expect_valid_or_invalid_input("check_mesh(soup)", [&] { (void)delmesh::check_mesh(soup.points, soup.triangles); });
  expect_valid_or_invalid_input("read_mesh", [&] {
    const delmesh::SurfaceMesh mesh = delmesh::read_mesh(path);
    (void)delmesh::check_mesh(mesh);
  });
  return 0;
}
