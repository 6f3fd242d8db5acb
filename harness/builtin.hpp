#pragma once
// Everything this build can run, registered by name: the clique algorithms (cliques/), our solvers
// (solvers/) and the peers that were built (peers/).
namespace verifybench {

/// Registers every built solver and clique algorithm once; safe to call from anywhere, often.
void register_builtin_solvers();

}  // namespace verifybench
