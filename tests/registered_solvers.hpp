#pragma once
// The built-in solvers, registered once before the first test of any test binary that includes
// this header (a gtest global environment).
#include <gtest/gtest.h>

#include "harness/builtin.hpp"

namespace verifybench::test {

class RegisteredSolvers : public ::testing::Environment {
 public:
  void SetUp() override { register_builtin_solvers(); }
};

inline const auto* const kRegisteredSolvers =
    ::testing::AddGlobalTestEnvironment(new RegisteredSolvers);

}  // namespace verifybench::test
