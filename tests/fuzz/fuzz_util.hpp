#pragma once
// What every libFuzzer target shares: the input written as files of one scratch folder (the
// parsers read files), split into parts at lines holding only "--", and the rule that a parser may
// refuse an input only by throwing a std::exception that says why. An allocation failure is not a
// refusal (it is rethrown, so the input is reported), and neither is a crash or a sanitizer report.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <new>
#include <string>
#include <vector>

namespace verifybench::fuzz {

/// A folder of this process, made once (mkdtemp under $TMPDIR or /tmp).
inline const std::string& scratch() {
  static const std::string dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/vbfuzz.XXXXXX";
    if (!::mkdtemp(pattern.data())) std::abort();
    return pattern;
  }();
  return dir;
}

/// The input cut at lines that are exactly "--" (at most `max_parts` parts; the rest stays in the
/// last).
inline std::vector<std::string> parts(const std::uint8_t* data, std::size_t size,
                                      std::size_t max_parts) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> out;
  std::size_t start = 0;
  while (out.size() + 1 < max_parts) {
    const std::size_t cut = text.find("\n--\n", start);
    if (cut == std::string::npos) break;
    out.push_back(text.substr(start, cut + 1 - start));
    start = cut + 4;
  }
  out.push_back(text.substr(start));
  return out;
}

/// Writes `text` to scratch()/name, or removes that file when `present` is false.
inline std::string put(const std::string& name, const std::string& text, bool present = true) {
  const std::string path = scratch() + "/" + name;
  ::unlink(path.c_str());
  if (present) std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// Runs `parse`; a std::exception is a refusal, except std::bad_alloc.
template <class F>
void refuse_or_read(F&& parse) {
  try {
    parse();
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception&) {
  }
}

}  // namespace verifybench::fuzz
