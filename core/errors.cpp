#include "core/errors.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace verifybench {

void input_error(const std::string& file, long long line, const std::string& what) {
  throw InputError(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what);
}

ParsedReal parse_real_token(std::string_view token) {
  const std::string text(token);
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return {};
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return {};
  // ERANGE on underflow returns a subnormal or zero: a valid reading of a tiny number.
  if (errno == ERANGE && std::fabs(v) > 1.0) return {v, NumberError::not_finite};
  if (!std::isfinite(v)) return {v, NumberError::not_finite};
  return {v, NumberError::none};
}

std::optional<long long> parse_integer_token(std::string_view token) {
  const std::string text(token);
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE) return std::nullopt;
  return v;
}

std::optional<unsigned long long> parse_unsigned_token(std::string_view token) {
  const std::string text(token);
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(text.front()))) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE) return std::nullopt;
  return v;
}

}  // namespace verifybench
