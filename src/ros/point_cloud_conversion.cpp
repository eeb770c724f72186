#include "pda_registration/ros/point_cloud_conversion.hpp"

#include <cmath>
#include <cstring>
#include <sstream>

namespace pda_registration {
namespace {

bool hostIsBigEndian() {
  const uint16_t probe = 1;
  uint8_t first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 0;
}

struct FieldLayout {
  uint32_t offset = 0;
  bool is_double = false;
};

bool findCoordinate(const sensor_msgs::PointCloud2& m, const std::string& name, FieldLayout* out,
                    std::string* error) {
  for (const sensor_msgs::PointField& f : m.fields) {
    if (f.name != name) continue;
    if (f.datatype != sensor_msgs::PointField::FLOAT32 &&
        f.datatype != sensor_msgs::PointField::FLOAT64) {
      *error = "field '" + name + "' is not FLOAT32 or FLOAT64";
      return false;
    }
    out->is_double = f.datatype == sensor_msgs::PointField::FLOAT64;
    out->offset = f.offset;
    const uint64_t end = static_cast<uint64_t>(f.offset) + (out->is_double ? 8u : 4u);
    if (end > m.point_step) {
      *error = "field '" + name + "' lies outside point_step";
      return false;
    }
    return true;
  }
  *error = "no '" + name + "' field (the cloud needs x, y and z)";
  return false;
}

double readCoordinate(const uint8_t* point, const FieldLayout& field) {
  if (field.is_double) {
    double v;
    std::memcpy(&v, point + field.offset, sizeof v);
    return v;
  }
  float v;
  std::memcpy(&v, point + field.offset, sizeof v);
  return v;
}

}  // namespace

CloudConversion fromPointCloud2(const sensor_msgs::PointCloud2& m) {
  CloudConversion out;
  const uint64_t count = static_cast<uint64_t>(m.width) * m.height;
  if (count == 0) {
    out.error = "empty cloud (width x height = 0)";
    return out;
  }
  if (m.is_bigendian != hostIsBigEndian()) {
    out.error = "byte order differs from this machine's";
    return out;
  }
  FieldLayout x, y, z;
  if (!findCoordinate(m, "x", &x, &out.error) || !findCoordinate(m, "y", &y, &out.error) ||
      !findCoordinate(m, "z", &z, &out.error)) {
    return out;
  }
  // findCoordinate put x, y and z inside point_step, so point_step >= 4 here. Both products have
  // 32-bit factors: neither the checks nor the numbers in the messages can wrap around.
  const uint64_t row_bytes = static_cast<uint64_t>(m.width) * m.point_step;
  const uint64_t data_bytes = static_cast<uint64_t>(m.row_step) * m.height;
  if (m.row_step < row_bytes) {
    std::ostringstream error;
    error << "row_step " << m.row_step << " is shorter than width x point_step = " << row_bytes;
    out.error = error.str();
    return out;
  }
  if (data_bytes > m.data.size()) {
    std::ostringstream error;
    error << "data holds " << m.data.size() << " bytes but height x row_step needs " << data_bytes;
    out.error = error.str();
    return out;
  }
  out.points.reserve(count);
  for (uint32_t row = 0; row < m.height; ++row) {
    const uint8_t* row_start = m.data.data() + static_cast<size_t>(row) * m.row_step;
    for (uint32_t column = 0; column < m.width; ++column) {
      const uint8_t* point = row_start + static_cast<size_t>(column) * m.point_step;
      const Point p(readCoordinate(point, x), readCoordinate(point, y), readCoordinate(point, z));
      if (p.allFinite()) {
        out.points.push_back(p);
      } else {
        ++out.non_finite;
      }
    }
  }
  if (out.points.empty()) {
    std::ostringstream error;
    error << "all " << out.non_finite << " points are NaN or Inf";
    out.error = error.str();
  }
  return out;
}

namespace {
// A multiply-xorshift mix per 8-byte word: a few milliseconds for a million points, and any
// changed byte changes the result (this guards against re-indexing, not against an adversary).
struct Fingerprint {
  uint64_t state = 0x9E3779B97F4A7C15ull;
  void add(uint64_t word) {
    state ^= word + 0x9E3779B97F4A7C15ull + (state << 6) + (state >> 2);
    state *= 0xBF58476D1CE4E5B9ull;
    state ^= state >> 31;
  }
  void addBytes(const uint8_t* bytes, size_t size) {
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
      uint64_t word;
      std::memcpy(&word, bytes + i, 8);
      add(word);
    }
    uint64_t tail = 0;
    if (size > i) std::memcpy(&tail, bytes + i, size - i);
    add(tail ^ (static_cast<uint64_t>(size) << 56));
  }
  void addText(const std::string& text) {
    addBytes(reinterpret_cast<const uint8_t*>(text.data()), text.size());
  }
};
}  // namespace

uint64_t cloudFingerprint(const sensor_msgs::PointCloud2& m) {
  Fingerprint f;
  f.addText(m.header.frame_id);
  f.add((static_cast<uint64_t>(m.width) << 32) | m.height);
  f.add((static_cast<uint64_t>(m.point_step) << 32) | m.row_step);
  f.add(m.is_bigendian);
  for (const sensor_msgs::PointField& field : m.fields) {
    f.addText(field.name);
    f.add((static_cast<uint64_t>(field.offset) << 16) | (field.datatype << 8) | field.count);
  }
  f.addBytes(m.data.data(), m.data.size());
  return f.state;
}

sensor_msgs::PointCloud2 toPointCloud2(const PointList& points, const std_msgs::Header& header) {
  sensor_msgs::PointCloud2 m;
  m.header = header;
  m.height = 1;
  m.width = static_cast<uint32_t>(points.size());
  m.is_bigendian = hostIsBigEndian();
  m.is_dense = true;
  m.point_step = 12;
  m.row_step = m.point_step * m.width;
  const char* names[3] = {"x", "y", "z"};
  for (uint32_t i = 0; i < 3; ++i) {
    sensor_msgs::PointField field;
    field.name = names[i];
    field.offset = 4 * i;
    field.datatype = sensor_msgs::PointField::FLOAT32;
    field.count = 1;
    m.fields.push_back(field);
  }
  m.data.resize(static_cast<size_t>(m.row_step));
  for (size_t i = 0; i < points.size(); ++i) {
    const float xyz[3] = {static_cast<float>(points[i].x()), static_cast<float>(points[i].y()),
                          static_cast<float>(points[i].z())};
    std::memcpy(&m.data[i * 12], xyz, sizeof xyz);
  }
  return m;
}

}  // namespace pda_registration
