// Meshes the catalog torus through the installed library; exits 0 if the run is complete and the
// independent checker finds one component of genus 1.
#include <iostream>
#include <vector>

#include "meshing/core/mesh_checker.h"
#include "meshing/driver/del_mesh.h"
#include "symbolic/catalog.h"

int main() {
  const delmesh::CatalogEntry& torus = delmesh::catalog_entry("torus");
  const delmesh::DelMeshResult result = delmesh::del_mesh(torus.surface(), torus.box, delmesh::DelMeshOptions{});
  const delmesh::MeshReport report = delmesh::check_mesh(result.mesh);
  std::cout << result.status << ", " << report.vertices << " vertices, genus per component";
  for (int g : report.genus_per_component) std::cout << " " << g;
  std::cout << std::endl;
  return result.status == delmesh::MeshStatus::complete && report.genus_per_component == std::vector<int>{1} ? 0 : 1;
}
