// libFuzzer: the strict number parsers every reader and option goes through; a value they accept
// must be what the standard library reads from the same token.
#include <cmath>
#include <cstdlib>
#include <string>

#include "core/errors.hpp"
#include "fuzz_util.hpp"

namespace vb = verifybench;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string token(reinterpret_cast<const char*>(data), size);
  const vb::ParsedReal r = vb::parse_real_token(token);
  if (r.error == vb::NumberError::none) {
    if (!std::isfinite(r.value)) std::abort();  // accepted means finite
    if (std::strtod(token.c_str(), nullptr) != r.value) std::abort();
  }
  if (const auto i = vb::parse_integer_token(token)) {
    if (std::to_string(*i) != token && std::strtoll(token.c_str(), nullptr, 10) != *i) std::abort();
  }
  vb::parse_unsigned_token(token);
  return 0;
}
