// The sequence layouts by name (core/registry.hpp), the built-in ones added on first use.
#include "core/registry.hpp"

#include <stdexcept>

#include "loop/sources/common.hpp"

namespace verifybench {
namespace {

Registry<SourceInfo>& registry() {
  static Registry<SourceInfo> reg("sequence format");
  static const bool builtins = [] {
    for (auto make : {sources::carmen_source, sources::folder_source, sources::helipr_source,
                      sources::kitti_source, sources::mulran_source, sources::nclt_source}) {
      reg.add(make());
    }
    return true;
  }();
  (void)builtins;
  return reg;
}

}  // namespace

void register_source(SourceInfo info) { registry().add(std::move(info)); }

std::vector<SourceInfo> list_sources() { return registry().list(); }

std::unique_ptr<SequenceSource> open_sequence(const std::string& dir, const std::string& format,
                                              const SourceOptions& options) {
  if (!format.empty()) return registry().get(format).open(dir, options);
  std::vector<SourceInfo> matches;
  for (auto& s : registry().list()) {
    if (s.detect && s.detect(dir)) matches.push_back(std::move(s));
  }
  if (matches.size() == 1) return matches[0].open(dir, options);
  if (matches.empty()) {
    throw std::invalid_argument(dir + ": no known sequence layout (formats: " + registry().known() +
                                "); pass the format");
  }
  std::string names;
  for (const auto& m : matches) names += (names.empty() ? "" : ", ") + m.name;
  throw std::invalid_argument(dir + ": matches several sequence layouts (" + names +
                              "); pass the format");
}

}  // namespace verifybench
