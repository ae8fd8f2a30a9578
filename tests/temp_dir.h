#pragma once
//! \file temp_dir.h
//! A fresh temporary directory for one test, shared by the tests that write files.

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace delmesh::test {

//! A new directory under the system's temporary directory (named by the process id and a
//! counter, so tests running at once do not share one), removed with its content at the end.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    static int counter = 0;
    path = std::filesystem::temp_directory_path() /
           ("delmesh_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path);  // left by an earlier process with the same id
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  //! The path of `name` in the directory.
  std::filesystem::path operator/(const std::string& name) const { return path / name; }
  //! The same, as a string.
  std::string file(const std::string& name) const { return (path / name).string(); }
  //! Writes `content` (bytes) as `name` and returns its path.
  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream(file(name), std::ios::binary) << content;
    return file(name);
  }
};

}  // namespace delmesh::test
