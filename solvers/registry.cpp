#include "solvers/registry.hpp"

#include <map>
#include <mutex>

namespace verifybench {

namespace {
std::map<std::string, SolverInfo>& table() {
  static std::map<std::string, SolverInfo> solvers;
  return solvers;
}
std::string known_names() {
  std::string names;
  for (const auto& [name, info] : table()) names += (names.empty() ? "" : ", ") + name;
  return names;
}
}  // namespace

void SolverRegistry::add(SolverInfo info) {
  const std::string name = info.name;
  if (!table().emplace(name, std::move(info)).second) {
    throw std::logic_error("solver '" + name + "' is registered twice");
  }
}

std::unique_ptr<Solver> SolverRegistry::create(const std::string& name) {
  const auto it = table().find(name);
  if (it == table().end()) {
    throw UnknownSolver("unknown solver '" + name + "' (known: " + known_names() + ")");
  }
  return it->second.make();
}

bool SolverRegistry::contains(const std::string& name) { return table().count(name) > 0; }

std::vector<SolverInfo> SolverRegistry::list() {
  std::vector<SolverInfo> out;
  for (const auto& entry : table()) out.push_back(entry.second);
  return out;
}

}  // namespace verifybench
