#include "io/PcdFile.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "io/OutputFile.hpp"

namespace uavslam::io {
namespace {

constexpr std::size_t kPointBytes = 4 * 4 + 8;  // x y z intensity as float32, time as float64

std::string header(std::size_t count) {
  const std::string n = std::to_string(count);
  return "# .PCD v0.7 - Point Cloud Data file format (written by uavslam)\n"
         "VERSION 0.7\n"
         "FIELDS x y z intensity time\n"
         "SIZE 4 4 4 4 8\n"
         "TYPE F F F F F\n"
         "COUNT 1 1 1 1 1\n"
         "WIDTH " +
         n +
         "\n"
         "HEIGHT 1\n"
         "VIEWPOINT 0 0 0 1 0 0 0\n"
         "POINTS " +
         n +
         "\n"
         "DATA binary\n";
}

// PCD's binary data is the in-memory layout of the writing machine; PCL assumes little-endian.
template <typename T>
void put(unsigned char*& out, T value) {
  static_assert(sizeof(float) == 4 && sizeof(double) == 8);
  std::memcpy(out, &value, sizeof value);
  out += sizeof value;
}

std::vector<unsigned char> body(const std::vector<DensePoint>& points) {
  std::vector<unsigned char> bytes(points.size() * kPointBytes);
  unsigned char* out = bytes.data();
  for (const DensePoint& p : points) {
    put(out, float(p.position.x()));
    put(out, float(p.position.y()));
    put(out, float(p.position.z()));
    put(out, p.intensity);
    put(out, p.time);
  }
  return bytes;
}

// ---- reading ----

struct PcdField {
  std::string name;
  std::size_t size = 0;
  char type = 'F';
  std::size_t count = 1;
  std::size_t offset = 0;  // within a binary record
};

struct PcdHeader {
  std::vector<PcdField> fields;
  std::size_t points = 0;
  std::string data;
  std::size_t record_bytes = 0;
};

std::vector<std::string> words_after(std::istringstream& line) {
  std::vector<std::string> words;
  for (std::string w; line >> w;) words.push_back(w);
  return words;
}

std::size_t parse_count(const std::string& path, const std::string& key, const std::string& word) {
  std::size_t value = 0;
  std::size_t used = 0;
  try {
    value = std::stoull(word, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != word.size() || word.empty() || word[0] == '-') {
    throw file_error(path, key + " must be a non-negative integer, got '" + word + "'");
  }
  return value;
}

void apply_header_line(const std::string& path, const std::string& key,
                       const std::vector<std::string>& words, PcdHeader& h) {
  if (key == "FIELDS") {
    h.fields.clear();
    for (const std::string& w : words) h.fields.push_back({w});
  } else if (key == "SIZE" || key == "TYPE" || key == "COUNT") {
    if (words.size() != h.fields.size()) {
      throw file_error(path, key + " has " + std::to_string(words.size()) + " entries for " +
                                 std::to_string(h.fields.size()) + " FIELDS");
    }
    for (std::size_t i = 0; i < words.size(); ++i) {
      if (key == "SIZE") h.fields[i].size = parse_count(path, key, words[i]);
      if (key == "COUNT") h.fields[i].count = parse_count(path, key, words[i]);
      if (key == "TYPE") h.fields[i].type = words[i].empty() ? '?' : words[i][0];
    }
  } else if (key == "POINTS" && words.size() == 1) {
    h.points = parse_count(path, key, words[0]);
  } else if (key == "DATA" && words.size() == 1) {
    h.data = words[0];
  }
}

PcdHeader read_header(const std::string& path, std::istream& in) {
  PcdHeader h;
  for (std::string text; h.data.empty() && std::getline(in, text);) {
    if (text.empty() || text[0] == '#') continue;
    std::istringstream line(text);
    std::string key;
    line >> key;
    apply_header_line(path, key, words_after(line), h);
  }
  if (h.data.empty()) throw file_error(path, "not a PCD file: no DATA line");
  if (h.data != "ascii" && h.data != "binary") {
    throw file_error(path, "DATA " + h.data + " is not supported (ascii or binary)");
  }
  for (PcdField& f : h.fields) {
    if (f.size == 0) throw file_error(path, "field " + f.name + " has no SIZE");
    f.offset = h.record_bytes;
    h.record_bytes += f.size * f.count;
  }
  return h;
}

const PcdField* find_field(const PcdHeader& h, const std::string& name) {
  for (const PcdField& f : h.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

double decode(const unsigned char* record, const PcdField& f) {
  if (f.type == 'F' && f.size == 4) {
    float v;
    std::memcpy(&v, record + f.offset, 4);
    return v;
  }
  if (f.type == 'F' && f.size == 8) {
    double v;
    std::memcpy(&v, record + f.offset, 8);
    return v;
  }
  return 0.0;
}

struct FieldSet {
  const PcdField* x;
  const PcdField* y;
  const PcdField* z;
  const PcdField* intensity;
  const PcdField* time;
};

FieldSet point_fields(const std::string& path, const PcdHeader& h) {
  FieldSet set{find_field(h, "x"), find_field(h, "y"), find_field(h, "z"),
               find_field(h, "intensity"), find_field(h, "time")};
  for (const PcdField* f : {set.x, set.y, set.z}) {
    if (!f) throw file_error(path, "no x, y or z field");
    if (f->type != 'F' || (f->size != 4 && f->size != 8)) {
      throw file_error(path, "field " + f->name + " must be F 4 or F 8");
    }
  }
  return set;
}

DensePoint decode_point(const unsigned char* record, const FieldSet& f) {
  DensePoint p;
  p.position = Vec3(decode(record, *f.x), decode(record, *f.y), decode(record, *f.z));
  if (f.intensity) p.intensity = float(decode(record, *f.intensity));
  if (f.time) p.time = decode(record, *f.time);
  return p;
}

std::vector<DensePoint> read_binary(const std::string& path, std::istream& in, const PcdHeader& h,
                                    const FieldSet& fields) {
  const std::vector<unsigned char> data{std::istreambuf_iterator<char>(in),
                                        std::istreambuf_iterator<char>()};
  if (h.record_bytes == 0 || data.size() / h.record_bytes < h.points) {
    throw file_error(path, "data holds " + std::to_string(data.size()) + " bytes, " +
                               std::to_string(h.points) + " points need " +
                               std::to_string(h.points * h.record_bytes));
  }
  std::vector<DensePoint> points;
  points.reserve(h.points);
  for (std::size_t i = 0; i < h.points; ++i) {
    points.push_back(decode_point(data.data() + i * h.record_bytes, fields));
  }
  return points;
}

std::vector<DensePoint> read_ascii(const std::string& path, std::istream& in, const PcdHeader& h,
                                   const FieldSet& fields) {
  std::vector<DensePoint> points;
  std::vector<unsigned char> record(h.record_bytes);
  for (std::size_t i = 0; i < h.points; ++i) {
    for (const PcdField& f : h.fields) {
      for (std::size_t c = 0; c < f.count; ++c) {
        double value = 0.0;
        if (!(in >> value)) {
          throw file_error(path, "point " + std::to_string(i) + " of " + std::to_string(h.points) +
                                     ": missing or bad value of " + f.name);
        }
        if (c == 0 && f.type == 'F' && f.size == 4) {
          const float v = float(value);
          std::memcpy(record.data() + f.offset, &v, 4);
        } else if (c == 0 && f.type == 'F' && f.size == 8) {
          std::memcpy(record.data() + f.offset, &value, 8);
        }
      }
    }
    points.push_back(decode_point(record.data(), fields));
  }
  return points;
}

}  // namespace

void write_pcd(const std::string& path, const std::vector<DensePoint>& points) {
  const std::vector<unsigned char> bytes = body(points);
  OutputFile file(path);
  file.write(header(points.size()));
  file.write(bytes.data(), bytes.size());
  file.close();
}

std::vector<DensePoint> read_pcd(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, std::string("cannot open: ") + std::strerror(errno));
  const PcdHeader h = read_header(path, in);
  const FieldSet fields = point_fields(path, h);
  return h.data == "binary" ? read_binary(path, in, h, fields) : read_ascii(path, in, h, fields);
}

}  // namespace uavslam::io
