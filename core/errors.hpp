#pragma once
// The two kinds of bad input every stage reports the same way: the CLI prints the message on one
// line and exits with code 2.
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace verifybench {

/// Malformed input: the message names the file, the line, the field and the offending value.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad command line: the message names the option and the value.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws InputError("FILE:LINE: WHAT"), or "FILE: WHAT" when line <= 0.
[[noreturn]] void input_error(const std::string& file, long long line, const std::string& what);

/// Why a token is not the number asked for.
enum class NumberError { none, not_a_number, not_finite };

/// Strict parsing of one whole token: no leading or trailing characters, no overflow. A value too
/// small for a double (1e-320) is read as the nearest subnormal or zero, not refused.
struct ParsedReal {
  double value = 0.0;
  NumberError error = NumberError::not_a_number;
};
ParsedReal parse_real_token(std::string_view token);
std::optional<long long> parse_integer_token(std::string_view token);  ///< base 10, signed
std::optional<unsigned long long> parse_unsigned_token(std::string_view token);  ///< no sign

}  // namespace verifybench
