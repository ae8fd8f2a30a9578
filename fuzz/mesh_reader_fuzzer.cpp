//! \file mesh_reader_fuzzer.cpp
//! libFuzzer targets fuzz_read_off, fuzz_read_ply, fuzz_read_obj, fuzz_read_stl (DELMESH_FUZZ_EXTENSION): the
//! input is written to a scratch file with that extension, then read as `delmesh check` does:
//! read_triangle_soup (which parses the file as a polygon soup, as `delmesh mesh --input-mesh`
//! does, then requires triangles), check_mesh on the soup, read_mesh and check_mesh on the mesh.  Each either succeeds or throws InvalidInput; anything else is a finding.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz/fuzz_support.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/inputs/mesh_io.h"

#ifndef DELMESH_FUZZ_EXTENSION
#error "DELMESH_FUZZ_EXTENSION (.off, .ply, .obj or .stl) must be defined"
#endif

namespace {

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
