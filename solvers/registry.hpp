#pragma once
// Name-keyed solver registry (after google/benchmark's benchmark_register.cc).
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/solver.hpp"

namespace verifybench {

struct SolverInfo {
  std::string name;
  std::string description;  ///< one line, shown by `verifybench list`
  std::function<std::unique_ptr<Solver>()> make;
};

class UnknownSolver : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class SolverRegistry {
 public:
  /// Throws std::logic_error on a duplicate name.
  static void add(SolverInfo info);
  /// Throws UnknownSolver listing the registered names.
  static std::unique_ptr<Solver> create(const std::string& name);
  static bool contains(const std::string& name);
  /// Registered solvers, sorted by name.
  static std::vector<SolverInfo> list();
};

/// Registers the built-in solvers once (explicit, so that no linker drops a static registrant).
void register_builtin_solvers();

}  // namespace verifybench
