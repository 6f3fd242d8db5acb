// libFuzzer: KITTI pose files and calib.txt (`loop --trajectory`, `--calib`, `--sequence`).
#include "datasets/trajectory.hpp"
#include "fuzz_util.hpp"

namespace vb = verifybench;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string path = vb::fuzz::put("poses.txt", text);
  vb::fuzz::refuse_or_read([&] { vb::read_kitti_poses(path); });
  vb::fuzz::refuse_or_read([&] { vb::read_kitti_calib_tr(path); });
  return 0;
}
