// DIMACS reader errors, and every exact algorithm against the known clique numbers of
// ../shared/data/dimacs/MANIFEST.tsv (skipped when the folder is absent).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "cliques/max_clique.hpp"
#include "datasets/dimacs.hpp"

namespace verifybench {
namespace {

namespace fs = std::filesystem;

std::string write_temp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / name;
  std::ofstream(p) << text;
  return p.string();
}

std::string error_of(const std::string& path) {
  try {
    read_dimacs(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Dimacs, ReadsEdgesToleratingDuplicatesAndSelfLoops) {
  const auto path =
      write_temp("vb_ok.clq", "c comment\np edge 4 5\ne 1 2\ne 2 1\ne 2 3\ne 3 3\ne 1 3\n");
  const BitGraph g = read_dimacs(path);
  EXPECT_EQ(g.size(), 4);
  EXPECT_EQ(g.edge_count(), 3);
  EXPECT_TRUE(g.adjacent(0, 2));
  EXPECT_FALSE(g.adjacent(2, 2));
  EXPECT_TRUE(g.is_clique({0, 1, 2}));
}

TEST(Dimacs, ClearErrorsOnMalformedInput) {
  EXPECT_NE(error_of(write_temp("vb_b1.clq", "e 1 2\n")).find("vb_b1.clq:1: edge before"),
            std::string::npos);
  EXPECT_NE(error_of(write_temp("vb_b2.clq", "p edge 3 1\ne 1 4\n"))
                .find("vb_b2.clq:2: vertex '4' is outside 1..3"),
            std::string::npos);
  EXPECT_NE(error_of(write_temp("vb_b3.clq", "p edge 3 1\ne 1 x\n"))
                .find("vb_b3.clq:2: field v: 'x' is not an integer"),
            std::string::npos);
  EXPECT_NE(error_of(write_temp("vb_b4.clq", "p edge 3 1\nq 1 2\n")).find("unknown line type 'q'"),
            std::string::npos);
  EXPECT_NE(error_of(write_temp("vb_b5.clq", "c nothing\n")).find("no 'p edge N M' line"),
            std::string::npos);
  EXPECT_NE(error_of(write_temp("vb_b6.clq", "p edge 3 1\ne 0 1\n")).find("vertex '0'"),
            std::string::npos);
  EXPECT_NE(error_of("/nonexistent.clq").find("cannot open"), std::string::npos);
  EXPECT_THROW(read_dimacs(write_temp("vb_b7.clq", "p edge 100000 0\n"), 1 << 20),
               InputError);  // over the cap
}

// Deterministic budget: a node limit (not a clock), so the same instances are solved on any
// machine.
constexpr long long kNodeLimit = 3'000'000;

TEST(Dimacs, ExactAlgorithmsMatchKnownCliqueNumbers) {
  const fs::path dir = fs::path(VERIFYBENCH_SHARED_DATA) / "dimacs";
  if (!fs::exists(dir / "MANIFEST.tsv")) GTEST_SKIP() << "shared data absent: " << dir;
  register_clique_algorithms();
  const auto omega = read_manifest((dir / "MANIFEST.tsv").string());
  ASSERT_GE(omega.size(), 10u);
  for (const char* algorithm : {"bbmc", "bbmc-kcore", "bbmc-dec"}) {
    int solved = 0;
    for (const auto& [name, known] : omega) {
      const BitGraph g = read_dimacs((dir / (name + ".clq")).string());
      CliqueSearchParams p;
      p.node_limit = kNodeLimit;
      const auto r = CliqueAlgorithms::get(algorithm).run(g, p);
      ASSERT_TRUE(g.is_clique(r.clique)) << algorithm << " " << name;
      ASSERT_LE(static_cast<int>(r.clique.size()), known) << algorithm << " " << name;
      if (r.optimal) {
        ++solved;
        EXPECT_EQ(static_cast<int>(r.clique.size()), known) << algorithm << " " << name;
      }
    }
    // All but the hardest (brock400_4) solve within the node budget.
    EXPECT_GE(solved, static_cast<int>(omega.size()) - 1) << algorithm;
  }
}

// The Russian doll search is there for the small vertex-transitive graphs, where colouring bounds
// sit far above omega (hamming8-4: 16 against 32 greedy colours; johnson16-2-4: 8 against 14);
// elsewhere it may run out of nodes, but whatever it proves must be the known clique number.
TEST(Dimacs, RussianDollProvesTheVertexTransitiveGraphs) {
  const fs::path dir = fs::path(VERIFYBENCH_SHARED_DATA) / "dimacs";
  if (!fs::exists(dir / "MANIFEST.tsv")) GTEST_SKIP() << "shared data absent: " << dir;
  register_clique_algorithms();
  const auto omega = read_manifest((dir / "MANIFEST.tsv").string());
  std::set<std::string> proved;
  for (const auto& [name, known] : omega) {
    const BitGraph g = read_dimacs((dir / (name + ".clq")).string());
    CliqueSearchParams p;
    p.node_limit = kNodeLimit;
    const auto r = CliqueAlgorithms::get("doll").run(g, p);
    ASSERT_TRUE(g.is_clique(r.clique)) << name;
    ASSERT_LE(static_cast<int>(r.clique.size()), known) << name;
    if (!r.optimal) continue;
    EXPECT_EQ(static_cast<int>(r.clique.size()), known) << name;
    proved.insert(name);
  }
  for (const char* name : {"hamming8-4", "johnson16-2-4", "hamming8-2", "c-fat500-10"})
    EXPECT_TRUE(proved.count(name)) << name << " not proved within " << kNodeLimit << " nodes";
}

}  // namespace
}  // namespace verifybench
