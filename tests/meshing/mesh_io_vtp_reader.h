#pragma once
//! \file mesh_io_vtp_reader.h
//! A reader of the ASCII .vtp files write_mesh writes (meshing/inputs/mesh_io.h), for the tests: it
//! checks the XML skeleton of VTK's PolyData format (root element, piece counts, matching
//! DataArray tags) and returns the arrays as numbers.  Not a general VTK reader.

#include <cstddef>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace delmesh::test {

struct VtpFile {
  std::size_t points = 0, polys = 0;  //!< NumberOfPoints, NumberOfPolys of the piece
  //! Each DataArray's numbers by its Name ("Points", "Normals", "connectivity", "offsets").
  std::map<std::string, std::vector<double>> arrays;
};

//! The value of attribute `name` in the tag that starts at `at` of text; throws if absent.
inline std::string vtp_attribute(const std::string& text, std::size_t at, const std::string& name) {
  const std::size_t end = text.find('>', at);
  const std::size_t key = text.find(" " + name + "=\"", at);
  if (key == std::string::npos || key > end) throw std::runtime_error("vtp: no attribute " + name);
  const std::size_t first = key + name.size() + 3;
  return text.substr(first, text.find('"', first) - first);
}

inline VtpFile read_vtp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::runtime_error("vtp: " + what);
  };
  require(text.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\"", 0) == 0, "not a PolyData VTKFile");
  require(text.size() >= 11 && text.compare(text.size() - 11, 11, "</VTKFile>\n") == 0, "no closing </VTKFile>");
  const std::size_t piece = text.find("<Piece ");
  require(piece != std::string::npos, "no <Piece>");
  VtpFile file;
  file.points = std::stoul(vtp_attribute(text, piece, "NumberOfPoints"));
  file.polys = std::stoul(vtp_attribute(text, piece, "NumberOfPolys"));
  for (std::size_t at = text.find("<DataArray "); at != std::string::npos; at = text.find("<DataArray ", at + 1)) {
    const std::size_t body = text.find('>', at) + 1;
    const std::size_t close = text.find("</DataArray>", body);
    require(close != std::string::npos && text.find("<DataArray ", body) > close, "unclosed <DataArray>");
    require(vtp_attribute(text, at, "format") == "ascii", "not ascii");
    std::istringstream numbers(text.substr(body, close - body));
    std::vector<double>& values = file.arrays[vtp_attribute(text, at, "Name")];
    for (double v; numbers >> v;) values.push_back(v);
    require(numbers.eof(), "a DataArray holds something other than numbers");
  }
  return file;
}

}  // namespace delmesh::test
