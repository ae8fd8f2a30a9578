//! \file surfaces_command.cpp
//! `delmesh surfaces [--json]`: the catalog of named surfaces.

#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "apps/command_line.h"
#include "apps/commands.h"
#include "symbolic/catalog.h"

namespace delmesh::app {

nlohmann::ordered_json catalog_json() {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const CatalogEntry& e : catalog()) {
    nlohmann::ordered_json item;
    item["name"] = e.name;
    item["equation"] = e.equation;
    item["box"] = {e.box.lo[0], e.box.hi[0], e.box.lo[1], e.box.hi[1], e.box.lo[2], e.box.hi[2]};
    item["components"] = e.components;
    item["genus_per_component"] = e.genus_per_component;
    item["description"] = e.description;
    item["analytic_lfs"] = static_cast<bool>(e.local_feature_size);
    out.push_back(std::move(item));
  }
  return out;
}

Command add_surfaces_command(CLI::App& parent) {
  CLI::App* sub = parent.add_subcommand("surfaces", "List the catalog of named surfaces");
  sub->footer("List the catalog of named surfaces: name, equation E (the surface is E = 0), the box it lies "
      "in, its number of components and the genus of each, and a description.");
  auto json = std::make_shared<bool>(false);
  sub->add_flag("--json", *json, "Print a JSON array of objects {name, equation, box (x0,x1,y0,y1,"
                                  "z0,z1), components, genus_per_component, description, analytic_lfs}");

  return {sub, [json]() {
            const auto& entries = catalog();
            if (*json) {
              std::cout << catalog_json().dump(2) << std::endl;
              return ExitCode::complete;
            }
            for (const CatalogEntry& e : entries) {
              std::cout << e.name << "\n";
              std::cout << "  equation:    " << e.equation << " = 0\n";
              std::cout << "  box:         " << format_box(e.box) << "\n";
              std::cout << "  components:  " << e.components << ", genus";
              for (std::size_t i = 0; i < e.genus_per_component.size(); ++i) {
                std::cout << (i == 0 ? " " : ", ") << e.genus_per_component[i];
              }
              std::cout << "\n";
              std::cout << "  lfs:         " << (e.local_feature_size ? "analytic" : "not known in closed form")
                        << "\n";
              std::cout << "  description: " << e.description << "\n\n";
            }
            std::cout.flush();
            return ExitCode::complete;
          }};
}

}  // namespace delmesh::app
