// Our own check of PCD and PLY headers before PCL's readers see a file: PCL crashes on empty or
// garbage PCD files, loops on negative PLY counts, asserts on PLY face lists and allocates what a
// header claims. Here a header is parsed, its counts and field layout checked, and the data it
// promises bounded by the file's size; anything else is an InputError naming the file.
#include "frontend/cloud_header.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/errors.hpp"

namespace verifybench {

namespace {

constexpr std::size_t kMaxHeaderBytes = 1 << 16;  // a header is a few hundred bytes

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  input_error(path, line, what);
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return w;
}

/// A non-negative decimal integer that fits in 63 bits; -1 otherwise.
long long count_of(const std::string& s) {
  if (s.empty() || s.size() > 18 || !std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c) != 0; })) return -1;
  return std::stoll(s);
}

/// The header's lines up to and including `last` (e.g. "end_header"), and the bytes they take.
std::pair<std::vector<std::string>, std::size_t> header_lines(const std::string& path,
                                                              const std::string& first_key,
                                                              const std::string& last_key) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, "cannot open");
  std::vector<std::string> lines;
  std::size_t bytes = 0;
  for (std::string line; std::getline(in, line);) {
    bytes += line.size() + 1;
    if (bytes > kMaxHeaderBytes) break;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
    const auto w = words(line);
    if (!w.empty() && w[0] == last_key) return {lines, bytes};
  }
  if (lines.empty()) fail(path, 0, "empty file; expected a " + first_key + " header");
  fail(path, 0, "no '" + last_key + "' line in the first " + std::to_string(kMaxHeaderBytes) +
                    " bytes: not a " + first_key + " header");
}

}  // namespace

void check_pcd_header(const std::string& path) {
  const auto file_bytes = std::filesystem::file_size(path);
  const auto [lines, header_bytes] = header_lines(path, "PCD", "DATA");
  std::vector<std::string> fields, sizes, types, counts;
  long long width = -1, height = -1, points = -1;
  std::string data;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const auto w = words(lines[k]);
    const int line = static_cast<int>(k) + 1;
    if (w.empty() || w[0][0] == '#') continue;
    const std::vector<std::string> rest(w.begin() + 1, w.end());
    if (w[0] == "FIELDS") fields = rest;
    else if (w[0] == "SIZE") sizes = rest;
    else if (w[0] == "TYPE") types = rest;
    else if (w[0] == "COUNT") counts = rest;
    else if (w[0] == "WIDTH" || w[0] == "HEIGHT" || w[0] == "POINTS") {
      const long long v = rest.size() == 1 ? count_of(rest[0]) : -1;
      if (v < 0) fail(path, line, "field " + w[0] + " = '" + lines[k].substr(w[0].size()) +
                                      "' is not a non-negative integer");
      (w[0] == "WIDTH" ? width : w[0] == "HEIGHT" ? height : points) = v;
    } else if (w[0] == "DATA") data = rest.empty() ? "" : rest[0];
    else if (w[0] != "VERSION" && w[0] != "VIEWPOINT") {
      fail(path, line, "unknown PCD header key '" + w[0] + "'");
    }
  }
  if (fields.empty()) fail(path, 0, "PCD header has no FIELDS");
  for (const char* axis : {"x", "y", "z"}) {
    if (std::find(fields.begin(), fields.end(), axis) == fields.end()) {
      fail(path, 0, std::string("PCD FIELDS has no '") + axis + "'");
    }
  }
  if (counts.empty()) counts.assign(fields.size(), "1");
  if (sizes.size() != fields.size() || types.size() != fields.size() ||
      counts.size() != fields.size()) {
    fail(path, 0, "PCD header: FIELDS, SIZE, TYPE and COUNT differ in length");
  }
  long long stride = 0;
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const long long size = count_of(sizes[f]), count = count_of(counts[f]);
    if ((size != 1 && size != 2 && size != 4 && size != 8) || (types[f] != "F" && types[f] != "I" &&
                                                               types[f] != "U")) {
      fail(path, 0, "PCD field " + fields[f] + ": SIZE " + sizes[f] + " TYPE " + types[f] +
                        " is not a supported type");
    }
    if (fields.size() > 1024) fail(path, 0, "PCD header: more than 1024 FIELDS");
    if (count < 1 || count > 4096) fail(path, 0, "PCD field " + fields[f] + ": COUNT " + counts[f]);
    stride += size * count;
  }
  if (width < 0 || height < 0) fail(path, 0, "PCD header needs WIDTH and HEIGHT");
  if (points < 0) points = width * height;
  if (width * height != points) {
    fail(path, 0, "PCD header: WIDTH x HEIGHT = " + std::to_string(width * height) +
                      " but POINTS = " + std::to_string(points));
  }
  const long long left = static_cast<long long>(file_bytes) - static_cast<long long>(header_bytes);
  if (data == "binary") {
    if (static_cast<double>(points) * static_cast<double>(stride) > static_cast<double>(left)) {
      fail(path, 0, "PCD header promises " + std::to_string(points) + " points of " +
                        std::to_string(stride) + " bytes but the file holds " +
                        std::to_string(std::max(0LL, left)) + " bytes of data");
    }
  } else if (data == "ascii") {
    if (2.0 * static_cast<double>(points) * static_cast<double>(fields.size()) > left + 1.0) {
      fail(path, 0, "PCD header promises " + std::to_string(points) +
                        " points, more than the file's text can hold");
    }
  } else if (data == "binary_compressed") {
    if (left < 8) fail(path, 0, "PCD binary_compressed data has no size words");
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(header_bytes));
    std::uint32_t compressed = 0, uncompressed = 0;
    in.read(reinterpret_cast<char*>(&compressed), 4);
    in.read(reinterpret_cast<char*>(&uncompressed), 4);
    if (!in || static_cast<long long>(compressed) > left - 8 ||
        static_cast<double>(uncompressed) != static_cast<double>(points) * static_cast<double>(stride)) {
      fail(path, 0, "PCD binary_compressed sizes (" + std::to_string(compressed) + ", " +
                        std::to_string(uncompressed) + ") do not match the header and file");
    }
  } else {
    fail(path, static_cast<int>(lines.size()),
         "field DATA = '" + data + "'; expected ascii, binary or binary_compressed");
  }
}

void check_ply_header(const std::string& path) {
  const auto file_bytes = std::filesystem::file_size(path);
  const auto [lines, header_bytes] = header_lines(path, "PLY", "end_header");
  if (lines.empty() || words(lines[0]) != std::vector<std::string>{"ply"}) {
    fail(path, 1, "first line is not 'ply'");
  }
  std::string format;
  long long vertices = -1, stride = 0;
  bool in_vertex = false, has[3] = {false, false, false};
  auto type_size = [](const std::string& t) -> long long {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" ||
        t == "float32")
      return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
  };
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto w = words(lines[k]);
    const int line = static_cast<int>(k) + 1;
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info" || w[0] == "end_header") continue;
    if (w[0] == "format") {
      if (w.size() != 3 || (w[1] != "ascii" && w[1] != "binary_little_endian" &&
                            w[1] != "binary_big_endian")) {
        fail(path, line, "field format = '" + lines[k] + "' is not a PLY format");
      }
      format = w[1];
    } else if (w[0] == "element") {
      if (w.size() != 3) fail(path, line, "malformed element line '" + lines[k] + "'");
      const long long n = count_of(w[2]);
      if (n < 0) fail(path, line, "element " + w[1] + " count = '" + w[2] + "' is not a non-negative integer");
      in_vertex = w[1] == "vertex";
      if (in_vertex) {
        if (vertices >= 0) fail(path, line, "a second vertex element");
        vertices = n;
      } else if (n > 0) {
        fail(path, line, "element " + w[1] + " (" + w[2] +
                             "): only vertex elements are read; faces and others are refused");
      }
    } else if (w[0] == "property") {
      if (w.size() >= 2 && w[1] == "list") {
        fail(path, line, "property lists (faces) are not read; refused before PCL sees them");
      }
      if (w.size() != 3 || type_size(w[1]) == 0) {
        fail(path, line, "malformed property line '" + lines[k] + "'");
      }
      if (in_vertex) {
        stride += type_size(w[1]);
        for (int a = 0; a < 3; ++a) has[a] = has[a] || w[2] == std::string(1, char('x' + a));
      }
    } else {
      fail(path, line, "unknown PLY header line '" + lines[k] + "'");
    }
  }
  if (format.empty()) fail(path, 0, "PLY header has no format line");
  if (vertices < 0) fail(path, 0, "PLY header has no vertex element");
  if (!has[0] || !has[1] || !has[2]) fail(path, 0, "PLY vertex element lacks x, y or z");
  const long long left = static_cast<long long>(file_bytes) - static_cast<long long>(header_bytes);
  const bool binary = format != "ascii";
  const double promised = static_cast<double>(vertices) * (binary ? static_cast<double>(stride) : 6.0);
  if (promised > static_cast<double>(left) + (binary ? 0.0 : 1.0)) {
    fail(path, 0, "PLY header promises " + std::to_string(vertices) +
                      " vertices, more than the file's " + std::to_string(std::max(0LL, left)) +
                      " bytes of data hold");
  }
}

}  // namespace verifybench
