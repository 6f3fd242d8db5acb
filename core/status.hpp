#pragma once
// How a solve or a search ended: the enums every result and report row carries in memory; the
// report writes their names and the shard merger reads them back (from_name refuses any other).
#include <optional>
#include <string_view>
#include <type_traits>

namespace verifybench {

/// A solver's result and a report row (solvers/solver.hpp, reports/record.hpp).
enum class Status {
  ok,          ///< search completed and the pair is accepted
  rejected,    ///< search completed; the accept rule (or a check after it) said no
  time_limit,  ///< limit reached; the result is the best found so far (accepted may still be true)
  error,       ///< the solver could not run (see message)
};

/// A maximum clique search on one graph (DIMACS mode, reports/record.hpp's CliqueRecord).
enum class SearchStatus {
  ok,          ///< proven maximum
  time_limit,  ///< limit reached; the best clique found so far
  unproven,    ///< a heuristic's clique, never proven maximum
  error,       ///< the search could not run (see message)
};

constexpr const char* to_string(Status s) {
  switch (s) {
    case Status::ok:
      return "ok";
    case Status::rejected:
      return "rejected";
    case Status::time_limit:
      return "time_limit";
    case Status::error:
      return "error";
  }
  return "error";
}

constexpr const char* to_string(SearchStatus s) {
  switch (s) {
    case SearchStatus::ok:
      return "ok";
    case SearchStatus::time_limit:
      return "time_limit";
    case SearchStatus::unproven:
      return "unproven";
    case SearchStatus::error:
      return "error";
  }
  return "error";
}

/// The enumerator named `name` (as to_string writes it); nullopt for any other text.
template <class E>
std::optional<E> status_from_name(std::string_view name) {
  for (E e : {E::ok, E::time_limit, E::error}) {
    if (name == to_string(e)) return e;
  }
  if constexpr (std::is_same_v<E, Status>) {
    if (name == to_string(Status::rejected)) return Status::rejected;
  } else {
    if (name == to_string(SearchStatus::unproven)) return SearchStatus::unproven;
  }
  return std::nullopt;
}

}  // namespace verifybench
