#pragma once
// Name-keyed solver registry (after google/benchmark's benchmark_register.cc).
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "solvers/solver.hpp"

namespace verifybench {

struct SolverInfo {
  std::string name;
  std::string description;  ///< one line, shown by `verifybench list`
  std::function<std::unique_ptr<Solver>()> make;
};

using UnknownSolver = UnknownName;

class SolverRegistry {
 public:
  /// Throws std::logic_error on a duplicate name.
  static void add(SolverInfo info);
  /// Throws UnknownSolver listing the registered names.
  static std::unique_ptr<Solver> create(const std::string& name);
  static bool contains(const std::string& name);
  /// Registered solvers, sorted by name.
  static std::vector<SolverInfo> list();
  /// Throws UnknownSolver unless every name is registered.
  static void check(const std::vector<std::string>& names);

 private:
  static Registry<SolverInfo>& table();
};

/// Registers this folder's solvers once (explicit, so that no linker drops a static registrant);
/// harness/builtin.hpp registers every solver of the build.
void register_solvers();

}  // namespace verifybench
