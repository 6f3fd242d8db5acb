// libFuzzer: the plain-text dump reader (corr.txt, label.txt, GTmat.txt) and the dump v1 reader
// (dump.json, matches.tsv), one folder; the input's parts are the files, in that order.
#include "datasets/dump_format.hpp"
#include "fuzz_util.hpp"

namespace vb = verifybench;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto p = vb::fuzz::parts(data, size, 3);
  // Text layout: corr.txt always, label.txt and GTmat.txt when the input has those parts.
  vb::fuzz::put("dump.json", "", false);
  vb::fuzz::put("matches.tsv", "", false);
  vb::fuzz::put("corr.txt", p[0]);
  vb::fuzz::put("label.txt", p.size() > 1 ? p[1] : "", p.size() > 1);
  vb::fuzz::put("GTmat.txt", p.size() > 2 ? p[2] : "", p.size() > 2);
  vb::fuzz::refuse_or_read([] { vb::read_dump(vb::fuzz::scratch()); });
  return 0;
}
