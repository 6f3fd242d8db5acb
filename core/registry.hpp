#pragma once
// One name-keyed registry for every pluggable stage (solvers, clique algorithms, generators,
// front-end pipelines), after google/benchmark's benchmark_register.cc: entries are plain `Info`
// structs with a `name`, added explicitly at start-up, looked up by name, listed in a stable order.
#include <algorithm>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/suggest.hpp"

namespace verifybench {

/// An unknown name; the message lists the known ones.
class UnknownName : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

template <class Info>
class Registry {
 public:
  enum class Order { by_name, as_added };
  /// `what` names an entry in messages ("solver", "clique algorithm").
  explicit Registry(std::string what, Order order = Order::by_name)
      : what_(std::move(what)), order_(order) {}

  /// Throws std::logic_error on a duplicate name.
  void add(Info info) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (find(info.name)) throw std::logic_error(what_ + " '" + info.name + "' is registered twice");
    entries_.push_back(std::make_unique<Info>(std::move(info)));
    if (order_ == Order::by_name) {
      std::stable_sort(entries_.begin(), entries_.end(),
                       [](const auto& a, const auto& b) { return a->name < b->name; });
    }
  }
  /// Throws UnknownName: "unknown WHAT 'NAME' (did you mean 'NEAR'?; known: a, b, c)", the
  /// suggestion only when a known name is a likely typo (core/suggest.hpp).
  const Info& get(const std::string& name) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (const Info* info = find(name)) return *info;
    std::vector<std::string> names;
    for (const auto& e : entries_) names.push_back(e->name);
    const std::string near = nearest_name(name, names);
    throw UnknownName("unknown " + what_ + " '" + name + "' (" +
                      (near.empty() ? "" : "did you mean '" + near + "'?; ") +
                      "known: " + known_locked() + ")");
  }
  bool contains(const std::string& name) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return find(name) != nullptr;
  }
  std::vector<Info> list() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Info> out;
    for (const auto& e : entries_) out.push_back(*e);
    return out;
  }
  /// The names, comma-separated, in list order.
  std::string known() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return known_locked();
  }

 private:
  const Info* find(const std::string& name) const {
    for (const auto& e : entries_) {
      if (e->name == name) return e.get();
    }
    return nullptr;
  }
  std::string known_locked() const {
    std::string names;
    for (const auto& e : entries_) names += (names.empty() ? "" : ", ") + e->name;
    return names;
  }

  std::string what_;
  Order order_;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<Info>> entries_;  // get()'s references outlive later add()s
};

}  // namespace verifybench
