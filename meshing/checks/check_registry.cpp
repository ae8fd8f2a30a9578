#include "meshing/checks/check_registry.h"

#include <algorithm>

#include "common/errors.h"

namespace delmesh {

namespace {

//! The built-in kinds, seed … distance; registered rows are numbered after them.
constexpr int paper_kind_count = static_cast<int>(CheckKind::distance) + 1;

//! The rows registered by CheckRegistration, and whether the registry has been read.
struct Registered {
  std::vector<CheckInfo> rows;
  bool read = false;
};
Registered& registered() {
  static Registered r;
  return r;
}

std::string known_names(const std::vector<CheckInfo>& rows) {
  std::string names;
  for (const CheckInfo& row : rows) names += (names.empty() ? "" : ", ") + row.name;
  return names;
}

}  // namespace

CheckRegistration::CheckRegistration(CheckInfo row) {
  Registered& r = registered();
  if (r.read) throw PreconditionViolation("check " + row.name + " registered after the registry was read");
  for (const std::vector<CheckInfo>* rows : {&builtin_checks(), static_cast<const std::vector<CheckInfo>*>(&r.rows)})
    for (const CheckInfo& other : *rows)
      if (other.name == row.name) throw PreconditionViolation("check " + row.name + " is registered twice");
  if (!row.check) throw PreconditionViolation("check " + row.name + " has no check function");
  if ((row.dirtied == Dirtied::restricted_star && row.face != FaceKind::vertex) ||
      (row.dirtied == Dirtied::restricted_triangles && row.face != FaceKind::triangle))
    throw PreconditionViolation("check " + row.name + ": restricted_star needs vertex faces, "
                                "restricted_triangles triangle faces");
  kind_ = static_cast<CheckKind>(paper_kind_count + static_cast<int>(r.rows.size()));
  row.kind = kind_;
  r.rows.push_back(std::move(row));
}

const std::vector<CheckInfo>& check_registry() {
  static const std::vector<CheckInfo> registry = [] {
    Registered& r = registered();
    r.read = true;
    std::vector<CheckInfo> rows = builtin_checks();
    // A row of the paper names its own enumerator, neither seed nor a control of the Quality row.
    std::vector<bool> taken(paper_kind_count, false);
    for (CheckKind k : {CheckKind::seed, CheckKind::size, CheckKind::distance}) taken[static_cast<int>(k)] = true;
    for (const CheckInfo& row : rows) {
      const int k = static_cast<int>(row.kind);
      if (k < 0 || k >= paper_kind_count || taken[k])
        throw PreconditionViolation("built-in check " + row.name + " needs a CheckKind enumerator of its own");
      taken[k] = true;
    }
    rows.insert(rows.end(), r.rows.begin(), r.rows.end());
    // Topology rows before geometry rows (a topology witness goes in before any geometric one),
    // each group in the order above.
    std::stable_partition(rows.begin(), rows.end(), [](const CheckInfo& row) { return row.phase == CheckPhase::topology; });
    return rows;
  }();
  return registry;
}

const CheckInfo& find_check(const std::string& name) {
  for (const CheckInfo& row : check_registry())
    if (row.name == name) return row;
  throw InvalidInput("unknown check '" + name + "'; known checks: " + known_names(check_registry()));
}

int check_kind_count() { return paper_kind_count + static_cast<int>(check_registry().size() - builtin_checks().size()); }

std::string check_kind_name(CheckKind kind) {
  const int k = static_cast<int>(kind);
  if (k >= paper_kind_count) {
    for (const CheckInfo& row : check_registry())
      if (row.kind == kind) return row.name;
    return "unknown";
  }
  const char* name = enum_name(kind);
  return name ? name : "unknown";
}

std::ostream& operator<<(std::ostream& out, CheckKind kind) { return out << check_kind_name(kind); }

}  // namespace delmesh
