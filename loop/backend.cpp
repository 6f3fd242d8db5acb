// The back ends by name (loop/backend.hpp), the built-in ones added on first use.
#include "loop/backend.hpp"

#include "core/registry.hpp"

namespace verifybench {
namespace {

Registry<BackendInfo>& backends() {
  static Registry<BackendInfo> reg("back end", Registry<BackendInfo>::Order::as_added);
  static const bool builtins = [] {
    reg.add(ceres_plain_backend());
    reg.add(ceres_robust_backend());
    return true;
  }();
  (void)builtins;
  return reg;
}

}  // namespace

std::vector<BackendInfo> list_backends() { return backends().list(); }

const BackendInfo& find_backend(const std::string& name) { return backends().get(name); }

void register_backend(BackendInfo info) { backends().add(std::move(info)); }

}  // namespace verifybench
