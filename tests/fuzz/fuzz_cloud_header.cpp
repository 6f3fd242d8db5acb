// libFuzzer: our PCD and PLY header checks, which stand before PCL's readers (issue #15).
#include "frontend/cloud_header.hpp"
#include "fuzz_util.hpp"

namespace vb = verifybench;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string pcd = vb::fuzz::put("c.pcd", text), ply = vb::fuzz::put("c.ply", text);
  vb::fuzz::refuse_or_read([&] { vb::check_pcd_header(pcd); });
  vb::fuzz::refuse_or_read([&] { vb::check_ply_header(ply); });
  return 0;
}
