#include "solvers/primitive_registry.h"

#include <sstream>

#include "common/errors.h"

namespace delmesh {

namespace {

//! The rows registered by PrimitiveRegistration, and whether the registry has been read.
struct Registered {
  std::vector<PrimitiveInfo> rows;
  bool read = false;
};
Registered& registered() {
  static Registered r;
  return r;
}

std::string known_names(const std::vector<PrimitiveInfo>& rows) {
  std::string names;
  for (const PrimitiveInfo& row : rows) names += (names.empty() ? "" : ", ") + row.name;
  return names;
}

}  // namespace

PrimitiveSystem PrimitiveInfo::build(const Surface& surface) const {
  PrimitiveSystem system = builder(surface);
  system.name = name;
  if (system.unknowns.empty() || system.equations.size() < system.unknowns.size()) {
    throw PreconditionViolation("the builder of primitive " + name + " gives " +
                                std::to_string(system.equations.size()) + " equations in " +
                                std::to_string(system.unknowns.size()) + " unknowns");
  }
  derive_jacobian(system);
  return system;
}

void PrimitiveInfo::check_query_options(const QueryOptions& given) const {
  for (const auto& entry : given.values) {
    bool read = false;
    for (const OptionUse& use : options) read = read || use.option == entry.first;
    if (!read) throw InvalidInput(option_flag(entry.first) + " is not a parameter of " + name);
  }
  for (const OptionUse& use : options) {
    if (use.required && !given.has(use.option)) throw InvalidInput(name + " needs " + option_flag(use.option));
  }
}

PrimitiveQuery PrimitiveInfo::query(const QueryOptions& given, const Box3& box) const {
  check_query_options(given);
  return make_query(given, box);
}

PrimitiveRegistration::PrimitiveRegistration(PrimitiveInfo row) {
  Registered& r = registered();
  if (r.read) throw PreconditionViolation("primitive " + row.name + " registered after the registry was read");
  for (const PrimitiveInfo& other : builtin_primitives())
    if (other.name == row.name) throw PreconditionViolation("primitive " + row.name + " is registered twice");
  for (const PrimitiveInfo& other : r.rows)
    if (other.name == row.name) throw PreconditionViolation("primitive " + row.name + " is registered twice");
  r.rows.push_back(std::move(row));
}

const std::vector<PrimitiveInfo>& primitive_registry() {
  static const std::vector<PrimitiveInfo> registry = [] {
    Registered& r = registered();
    r.read = true;
    std::vector<PrimitiveInfo> rows = builtin_primitives();
    rows.insert(rows.end(), r.rows.begin(), r.rows.end());
    return rows;
  }();
  return registry;
}

const PrimitiveInfo& find_primitive(const std::string& name) {
  for (const PrimitiveInfo& row : primitive_registry())
    if (row.name == name) return row;
  throw InvalidInput("unknown primitive '" + name + "'; known primitives: " + known_names(primitive_registry()));
}

PrimitiveSystem build_primitive(const std::string& name, const Surface& surface) {
  return find_primitive(name).build(surface);
}

std::string options_text(const PrimitiveInfo& row) {
  std::string text;
  for (const OptionUse& use : row.options) {
    const std::string item = option_flag(use.option) + " (" + use.meaning + ")";
    text += (text.empty() ? "" : ", ") + (use.required ? item : "[" + item + "]");
  }
  return text.empty() ? "none" : text;
}

std::string primitive_table_markdown(const std::vector<PrimitiveInfo>& rows) {
  std::ostringstream out;
  out << "| `--primitive` | solves | options (optional in brackets) | domain searched |\n";
  out << "|---|---|---|---|\n";
  for (const PrimitiveInfo& row : rows) {
    out << "| `" << row.name << "` | " << row.summary << " | " << options_text(row) << " | " << row.domain << " |\n";
  }
  return out.str();
}

std::string primitive_table_text(const std::vector<PrimitiveInfo>& rows) {
  std::ostringstream out;
  for (const PrimitiveInfo& row : rows) {
    out << "  " << row.name << ": " << row.summary << "\n";
    out << "      options: " << options_text(row) << "; domain: " << row.domain << "\n";
  }
  return out.str();
}

}  // namespace delmesh
