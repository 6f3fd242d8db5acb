// libFuzzer: the DIMACS graph reader (capped at 1 MiB of adjacency) and the DIMACS manifest reader.
#include "datasets/dimacs.hpp"
#include "fuzz_util.hpp"

namespace vb = verifybench;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string path = vb::fuzz::put("g.clq", text);
  vb::fuzz::refuse_or_read([&] { vb::read_dimacs(path, std::size_t{1} << 20); });
  vb::fuzz::refuse_or_read([&] { vb::read_manifest(path); });
  return 0;
}
