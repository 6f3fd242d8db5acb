#include "solvers/registry.hpp"

namespace verifybench {

Registry<SolverInfo>& SolverRegistry::table() {
  static Registry<SolverInfo> solvers("solver");
  return solvers;
}

void SolverRegistry::add(SolverInfo info) { table().add(std::move(info)); }

std::unique_ptr<Solver> SolverRegistry::create(const std::string& name) {
  return table().get(name).make();
}

bool SolverRegistry::contains(const std::string& name) { return table().contains(name); }

std::vector<SolverInfo> SolverRegistry::list() { return table().list(); }

void SolverRegistry::check(const std::vector<std::string>& names) {
  for (const auto& name : names) table().get(name);
}

}  // namespace verifybench
