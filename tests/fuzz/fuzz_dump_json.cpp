// libFuzzer: the dump v1 reader: dump.json (first part) and matches.tsv (second part).
#include "datasets/dump_format.hpp"
#include "fuzz_util.hpp"

namespace vb = verifybench;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto p = vb::fuzz::parts(data, size, 2);
  vb::fuzz::put("corr.txt", "", false);
  vb::fuzz::put("dump.json", p[0]);
  vb::fuzz::put("matches.tsv", p.size() > 1 ? p[1] : "", p.size() > 1);
  vb::fuzz::refuse_or_read([] { vb::read_dump(vb::fuzz::scratch()); });
  vb::fuzz::refuse_or_read([] { vb::manifest_expected(vb::fuzz::scratch() + "/sub"); });
  return 0;
}
