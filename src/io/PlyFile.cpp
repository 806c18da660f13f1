#include "io/PlyFile.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "io/OutputFile.hpp"

namespace uavslam::io {
namespace {

// ---- The header: which elements the file holds and how each record is laid out. ----

enum class PlyFormat { Ascii, BinaryLittleEndian };

enum class ScalarType { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

struct PlyProperty {
  std::string name;
  ScalarType type = ScalarType::Float32;      // of the value, or of each item of a list
  std::optional<ScalarType> list_count_type;  // set for "property list <count> <item> <name>"
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t line_count = 0;  // lines up to and including end_header
};

// Where x, y and z sit in the vertex element.
struct VertexLayout {
  std::size_t element = 0;
  std::size_t x = 0, y = 0, z = 0;  // property indices
};

struct ScalarTypeName {
  std::string_view name;
  ScalarType type;
};

// Both the original names and the sized aliases of the PLY specification.
constexpr ScalarTypeName kScalarTypeNames[] = {
    {"char", ScalarType::Int8},      {"int8", ScalarType::Int8},
    {"uchar", ScalarType::Uint8},    {"uint8", ScalarType::Uint8},
    {"short", ScalarType::Int16},    {"int16", ScalarType::Int16},
    {"ushort", ScalarType::Uint16},  {"uint16", ScalarType::Uint16},
    {"int", ScalarType::Int32},      {"int32", ScalarType::Int32},
    {"uint", ScalarType::Uint32},    {"uint32", ScalarType::Uint32},
    {"float", ScalarType::Float32},  {"float32", ScalarType::Float32},
    {"double", ScalarType::Float64}, {"float64", ScalarType::Float64},
};

std::size_t size_of(ScalarType type) {
  switch (type) {
    case ScalarType::Int8:
    case ScalarType::Uint8:
      return 1;
    case ScalarType::Int16:
    case ScalarType::Uint16:
      return 2;
    case ScalarType::Int32:
    case ScalarType::Uint32:
    case ScalarType::Float32:
      return 4;
    case ScalarType::Float64:
      return 8;
  }
  return 0;
}

bool is_floating(ScalarType type) {
  return type == ScalarType::Float32 || type == ScalarType::Float64;
}

std::vector<std::string> split_words(const std::string& line) {
  std::istringstream stream(line);
  return {std::istream_iterator<std::string>(stream), std::istream_iterator<std::string>()};
}

// Reads one header line without the "\r" a Windows editor may have added.
bool next_header_line(std::istream& in, std::string& line) {
  if (!std::getline(in, line)) return false;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

class HeaderParser {
 public:
  explicit HeaderParser(const std::string& path) : path_(path) {}

  PlyHeader parse(std::istream& in) {
    std::string line;
    header_.line_count = 1;
    if (!next_header_line(in, line) || line != "ply")
      fail("not a PLY file: first line must be 'ply'");
    bool has_format = false;
    while (next_header_line(in, line)) {
      ++header_.line_count;
      const std::vector<std::string> words = split_words(line);
      if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
      if (words[0] == "end_header") {
        if (!has_format) fail("header has no 'format' line");
        return header_;
      }
      if (words[0] == "format") {
        parse_format(words);
        has_format = true;
      } else if (words[0] == "element") {
        parse_element(words);
      } else if (words[0] == "property") {
        parse_property(words);
      } else {
        fail("unknown header keyword '" + words[0] + "'");
      }
    }
    throw file_error(path_, "header ends without 'end_header'");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw line_error(path_, header_.line_count, what);
  }

  void parse_format(const std::vector<std::string>& words) {
    if (words.size() != 3) fail("expected 'format <ascii|binary_little_endian> 1.0'");
    if (words[1] == "ascii") {
      header_.format = PlyFormat::Ascii;
    } else if (words[1] == "binary_little_endian") {
      header_.format = PlyFormat::BinaryLittleEndian;
    } else {
      fail("unsupported format '" + words[1] + "' (ascii and binary_little_endian are read)");
    }
  }

  void parse_element(const std::vector<std::string>& words) {
    if (words.size() != 3) fail("expected 'element <name> <count>'");
    PlyElement element;
    element.name = words[1];
    const std::string& count = words[2];
    const auto [end, error] =
        std::from_chars(count.data(), count.data() + count.size(), element.count);
    if (error != std::errc() || end != count.data() + count.size()) {
      fail("element count '" + count + "' is not a non-negative integer");
    }
    header_.elements.push_back(element);
  }

  void parse_property(const std::vector<std::string>& words) {
    if (header_.elements.empty()) fail("property before any element");
    PlyProperty property;
    if (words.size() == 5 && words[1] == "list") {
      property.list_count_type = scalar_type(words[2]);
      property.type = scalar_type(words[3]);
      property.name = words[4];
    } else if (words.size() == 3) {
      property.type = scalar_type(words[1]);
      property.name = words[2];
    } else {
      fail("expected 'property <type> <name>' or 'property list <type> <type> <name>'");
    }
    header_.elements.back().properties.push_back(property);
  }

  ScalarType scalar_type(const std::string& name) const {
    for (const ScalarTypeName& entry : kScalarTypeNames) {
      if (entry.name == name) return entry.type;
    }
    fail("unknown property type '" + name + "'");
  }

  const std::string& path_;
  PlyHeader header_;
};

std::size_t property_index(const std::string& path, const PlyElement& vertex, const char* name) {
  for (std::size_t i = 0; i < vertex.properties.size(); ++i) {
    const PlyProperty& property = vertex.properties[i];
    if (property.name != name) continue;
    if (property.list_count_type || !is_floating(property.type)) {
      throw file_error(path, std::string("vertex property '") + name + "' must be float or double");
    }
    return i;
  }
  throw file_error(path, std::string("vertex element has no property '") + name + "'");
}

VertexLayout find_vertex_layout(const std::string& path, const PlyHeader& header) {
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    if (element.name != "vertex") continue;
    return {e, property_index(path, element, "x"), property_index(path, element, "y"),
            property_index(path, element, "z")};
  }
  throw file_error(path, "header declares no 'vertex' element");
}

// ---- binary_little_endian records ----

// Decodes byte by byte, so the reader is right on big-endian hosts too.
std::uint64_t load_little_endian(const unsigned char* bytes, std::size_t size) {
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < size; ++i) bits |= std::uint64_t{bytes[i]} << (8 * i);
  return bits;
}

double decode_floating(const unsigned char* bytes, ScalarType type) {
  if (type == ScalarType::Float32) {
    const auto bits = static_cast<std::uint32_t>(load_little_endian(bytes, 4));
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  const std::uint64_t bits = load_little_endian(bytes, 8);
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// A list's item count; signed types are sign-extended so a negative count can be refused.
std::int64_t decode_count(const unsigned char* bytes, ScalarType type) {
  const std::size_t size = size_of(type);
  const std::uint64_t bits = load_little_endian(bytes, size);
  const bool is_signed =
      type == ScalarType::Int8 || type == ScalarType::Int16 || type == ScalarType::Int32;
  const std::uint64_t sign_bit = std::uint64_t{1} << (8 * size - 1);
  if (is_signed && (bits & sign_bit) != 0) return -1;
  return static_cast<std::int64_t>(bits);
}

// Walks the binary body record by record; every read is checked against the end of the file.
class BinaryBodyReader {
 public:
  BinaryBodyReader(const std::string& path, std::vector<unsigned char> body)
      : path_(path), body_(std::move(body)) {}

  Points read(const PlyHeader& header, const VertexLayout& layout) {
    for (std::size_t e = 0; e < layout.element; ++e) {
      for (std::size_t i = 0; i < header.elements[e].count; ++i) skip_record(header.elements[e], i);
    }
    const PlyElement& vertex = header.elements[layout.element];
    Points points;
    points.reserve(std::min(vertex.count, body_.size() / 12));  // x y z take >= 12 bytes
    std::vector<double> values(vertex.properties.size());
    for (std::size_t i = 0; i < vertex.count; ++i) {
      read_record(vertex, i, values);
      points.emplace_back(values[layout.x], values[layout.y], values[layout.z]);
    }
    return points;
  }

 private:
  void skip_record(const PlyElement& element, std::size_t index) {
    std::vector<double> ignored(element.properties.size());
    read_record(element, index, ignored);
  }

  // Fills values[p] for the float/double scalar properties; skips the others by their size.
  void read_record(const PlyElement& element, std::size_t index, std::vector<double>& values) {
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const PlyProperty& property = element.properties[p];
      std::size_t items = 1;
      if (property.list_count_type)
        items = read_list_count(element, index, *property.list_count_type);
      const unsigned char* bytes = take(element, index, items * size_of(property.type));
      if (!property.list_count_type && is_floating(property.type)) {
        values[p] = decode_floating(bytes, property.type);
      }
    }
  }

  std::size_t read_list_count(const PlyElement& element, std::size_t index, ScalarType type) {
    const std::int64_t count = decode_count(take(element, index, size_of(type)), type);
    if (count < 0) {
      throw file_error(path_,
                       "negative list length in " + element.name + " " + std::to_string(index));
    }
    return static_cast<std::size_t>(count);
  }

  const unsigned char* take(const PlyElement& element, std::size_t index, std::size_t size) {
    if (size > body_.size() - offset_) {
      throw file_error(path_, "file ends inside " + element.name + " " + std::to_string(index) +
                                  " of " + std::to_string(element.count) + " declared");
    }
    const unsigned char* bytes = body_.data() + offset_;
    offset_ += size;
    return bytes;
  }

  const std::string& path_;
  std::vector<unsigned char> body_;
  std::size_t offset_ = 0;
};

// ---- ascii records: one line per record, values separated by whitespace ----

class AsciiBodyReader {
 public:
  AsciiBodyReader(const std::string& path, std::istream& in, std::size_t header_lines)
      : path_(path), in_(in), line_number_(header_lines) {}

  Points read(const PlyHeader& header, const VertexLayout& layout) {
    for (std::size_t e = 0; e < layout.element; ++e) {
      for (std::size_t i = 0; i < header.elements[e].count; ++i) read_record(header.elements[e], i);
    }
    const PlyElement& vertex = header.elements[layout.element];
    Points points;
    for (std::size_t i = 0; i < vertex.count; ++i) {
      const std::vector<double> values = read_record(vertex, i);
      points.emplace_back(values[layout.x], values[layout.y], values[layout.z]);
    }
    return points;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw line_error(path_, line_number_, what);
  }

  // The value of each scalar property of the record (lists are skipped, their slot left 0).
  std::vector<double> read_record(const PlyElement& element, std::size_t index) {
    const std::vector<std::string> words = next_record_words(element, index);
    std::vector<double> values(element.properties.size(), 0.0);
    std::size_t word = 0;
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const bool is_list = element.properties[p].list_count_type.has_value();
      const double value = number(words, word++, element, index);
      if (is_list) {
        if (value < 0 || value != std::floor(value)) fail("list length is not a count");
        word += static_cast<std::size_t>(value);
      } else {
        values[p] = value;
      }
    }
    if (word != words.size()) fail(count_mismatch(element, index, word, words.size()));
    return values;
  }

  std::vector<std::string> next_record_words(const PlyElement& element, std::size_t index) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      std::vector<std::string> words = split_words(line);
      if (!words.empty()) return words;
    }
    fail("file ends before " + element.name + " " + std::to_string(index) + " of " +
         std::to_string(element.count) + " declared");
  }

  double number(const std::vector<std::string>& words, std::size_t word, const PlyElement& element,
                std::size_t index) const {
    if (word >= words.size()) fail(count_mismatch(element, index, word + 1, words.size()));
    const std::string& text = words[word];
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) {
      fail("'" + text + "' is not a number in " + element.name + " " + std::to_string(index));
    }
    return value;
  }

  static std::string count_mismatch(const PlyElement& element, std::size_t index,
                                    std::size_t expected, std::size_t got) {
    return element.name + " " + std::to_string(index) + " has " + std::to_string(got) +
           " values, the header declares " + std::to_string(expected);
  }

  const std::string& path_;
  std::istream& in_;
  std::size_t line_number_;  // of the line read last
};

std::vector<unsigned char> read_rest(std::istream& in) {
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// ---- writing ----

void append_float_little_endian(std::vector<unsigned char>& bytes, float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<unsigned char>(bits >> (8 * i)));
}

std::string binary_header(std::size_t vertex_count, bool with_intensity) {
  std::string header =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment written by uavslam\n"
      "element vertex " +
      std::to_string(vertex_count) +
      "\n"
      "property float x\n"
      "property float y\n"
      "property float z\n";
  if (with_intensity) header += "property float intensity\n";
  return header + "end_header\n";
}

std::vector<unsigned char> binary_body(const Points& points,
                                       const std::vector<float>* intensities) {
  const std::size_t floats_per_point = intensities ? 4 : 3;
  std::vector<unsigned char> bytes;
  bytes.reserve(points.size() * floats_per_point * 4);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      append_float_little_endian(bytes, static_cast<float>(points[i][axis]));
    }
    if (intensities) append_float_little_endian(bytes, (*intensities)[i]);
  }
  return bytes;
}

void write_binary_ply(const std::string& path, const Points& points,
                      const std::vector<float>* intensities) {
  const std::string header = binary_header(points.size(), intensities != nullptr);
  const std::vector<unsigned char> body = binary_body(points, intensities);
  OutputFile file(path);
  file.write(header);
  file.write(body.data(), body.size());
  file.close();
}

std::vector<unsigned char> dense_body(const std::vector<DensePoint>& points) {
  std::vector<unsigned char> bytes;
  bytes.reserve(points.size() * (4 * 4 + 8));
  for (const DensePoint& p : points) {
    for (int axis = 0; axis < 3; ++axis) {
      append_float_little_endian(bytes, static_cast<float>(p.position[axis]));
    }
    append_float_little_endian(bytes, p.intensity);
    std::uint64_t bits;
    std::memcpy(&bits, &p.time, sizeof bits);
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<unsigned char>(bits >> (8 * i)));
  }
  return bytes;
}

}  // namespace

void write_ply(const std::string& path, const std::vector<DensePoint>& points) {
  std::string header = binary_header(points.size(), true);
  header.insert(header.size() - std::string("end_header\n").size(), "property double time\n");
  const std::vector<unsigned char> body = dense_body(points);
  OutputFile file(path);
  file.write(header);
  file.write(body.data(), body.size());
  file.close();
}

void write_ply(const std::string& path, const Points& points) {
  write_binary_ply(path, points, nullptr);
}

void write_ply(const std::string& path, const Points& points,
               const std::vector<float>& intensities) {
  if (intensities.size() != points.size()) {
    throw std::invalid_argument("write_ply: " + std::to_string(intensities.size()) +
                                " intensities for " + std::to_string(points.size()) + " points");
  }
  write_binary_ply(path, points, &intensities);
}

Points read_ply(const std::string& path) {
  errno = 0;
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    const char* reason = errno != 0 ? std::strerror(errno) : "unknown error";
    throw file_error(path, std::string("cannot open: ") + reason);
  }
  const PlyHeader header = HeaderParser(path).parse(file);
  const VertexLayout layout = find_vertex_layout(path, header);
  if (header.format == PlyFormat::Ascii) {
    return AsciiBodyReader(path, file, header.line_count).read(header, layout);
  }
  return BinaryBodyReader(path, read_rest(file)).read(header, layout);
}

}  // namespace uavslam::io
