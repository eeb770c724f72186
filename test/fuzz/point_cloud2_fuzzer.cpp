// fromPointCloud2: what the nodelet does with every incoming dense or sparse map. Two modes,
// chosen by the input's first byte:
//  - structured: a message built field by field (sizes, steps, endianness, a list of fields
//    with names from x/y/z/intensity/... or random, offsets, datatypes, counts, and data),
//    which reaches deep layouts quickly;
//  - wire: the bytes are a serialized sensor_msgs/PointCloud2, read with roscpp's own
//    deserializer as a subscriber does, then converted.
// Invariants: ok() ⇒ at least one point, every point finite, points + non_finite = width x
// height; !ok() ⇒ a one-line reason.
#include <fuzzer/FuzzedDataProvider.h>
#include <ros/serialization.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_invariant.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"

using namespace pda_registration;

namespace {

// Mostly small sizes (the interesting layouts), sometimes any 32-bit value (the overflows).
uint32_t size32(FuzzedDataProvider& input, uint32_t small_max) {
  return input.ConsumeBool() ? input.ConsumeIntegralInRange<uint32_t>(0, small_max)
                             : input.ConsumeIntegral<uint32_t>();
}

sensor_msgs::PointField someField(FuzzedDataProvider& input) {
  static const char* const kNames[] = {"x", "y", "z", "intensity", "rgb", "ring", "X", ""};
  sensor_msgs::PointField f;
  f.name = input.ConsumeBool() ? std::string(kNames[input.ConsumeIntegralInRange<size_t>(0, 7)])
                               : input.ConsumeRandomLengthString(8);
  f.offset = size32(input, 40);
  // 1..8 are INT8..FLOAT64; anything else is an unknown type.
  f.datatype = input.ConsumeBool() ? input.ConsumeIntegralInRange<uint8_t>(1, 8)
                                   : input.ConsumeIntegral<uint8_t>();
  f.count = size32(input, 2);
  return f;
}

sensor_msgs::PointCloud2 structuredMessage(FuzzedDataProvider& input) {
  sensor_msgs::PointCloud2 m;
  m.height = size32(input, 3);
  m.width = size32(input, 8);
  m.point_step = size32(input, 48);
  // A consistent row_step (with some padding) is what real clouds have; any value otherwise.
  // (Truncated to 32 bits like a sender's own arithmetic would be.)
  const uint64_t packed_row = static_cast<uint64_t>(m.width) * m.point_step;
  m.row_step =
      input.ConsumeBool()
          ? static_cast<uint32_t>(packed_row + input.ConsumeIntegralInRange<uint32_t>(0, 8))
          : input.ConsumeIntegral<uint32_t>();
  m.is_bigendian = input.ConsumeIntegralInRange<uint8_t>(0, 7) == 0;  // mostly this host's order
  const size_t fields = input.ConsumeIntegralInRange<size_t>(0, 6);
  for (size_t i = 0; i < fields; ++i) m.fields.push_back(someField(input));
  // Usually exactly the bytes the layout needs (zero padded), so conversion goes all the way.
  const uint64_t needed = static_cast<uint64_t>(m.row_step) * m.height;
  if (input.ConsumeBool() && needed <= (1u << 20)) {
    m.data = input.ConsumeBytes<uint8_t>(needed);
    m.data.resize(needed, 0);
  } else {
    m.data = input.ConsumeRemainingBytes<uint8_t>();
  }
  return m;
}

// roscpp's deserializer resizes each vector to its length prefix before it checks the buffer, so
// a 20-byte message can make it allocate 4 GB. That happens inside roscpp, before the nodelet
// sees a message, so inputs whose length prefixes promise more than the buffer holds are skipped
// rather than reported as roscpp's out-of-memory.
class WireWalk {
 public:
  explicit WireWalk(const std::vector<uint8_t>& bytes) : left_(bytes.size()), next_(bytes.data()) {}
  bool skip(size_t n) {
    if (n > left_) return false;
    left_ -= n;
    next_ += n;
    return true;
  }
  bool length(uint32_t* n) {
    if (left_ < 4) return false;
    std::memcpy(n, next_, 4);
    return skip(4) && *n <= left_;
  }
  bool string() {
    uint32_t n = 0;
    return length(&n) && skip(n);
  }

 private:
  size_t left_;
  const uint8_t* next_;
};

bool lengthPrefixesFit(const std::vector<uint8_t>& bytes) {
  WireWalk walk(bytes);
  uint32_t count = 0;
  // header (seq, stamp, frame_id), height, width, fields[]
  if (!walk.skip(12) || !walk.string() || !walk.skip(8) || !walk.length(&count)) return false;
  for (uint32_t i = 0; i < count; ++i) {
    if (!walk.string() || !walk.skip(9)) return false;  // name, offset, datatype, count
  }
  // is_bigendian, point_step, row_step, data[]
  return walk.skip(9) && walk.length(&count);
}

bool wireMessage(FuzzedDataProvider& input, sensor_msgs::PointCloud2* m) {
  std::vector<uint8_t> bytes = input.ConsumeRemainingBytes<uint8_t>();
  if (!lengthPrefixesFit(bytes)) return false;
  try {
    ros::serialization::IStream stream(bytes.data(), static_cast<uint32_t>(bytes.size()));
    ros::serialization::deserialize(stream, *m);
  } catch (const ros::Exception&) {
    return false;  // truncated: roscpp drops it, the nodelet never sees it
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const bool wire = data[0] & 1;
  FuzzedDataProvider input(data + 1, size - 1);
  sensor_msgs::PointCloud2 message;
  if (wire) {
    if (!wireMessage(input, &message)) return 0;
  } else {
    message = structuredMessage(input);
  }

  const CloudConversion cloud = fromPointCloud2(message);
  if (!cloud.ok()) {
    fuzzing::require(fuzzing::isOneLineMessage(cloud.error), "refusal is a one-line reason",
                     cloud.error);
    return 0;
  }
  fuzzing::require(!cloud.points.empty(), "accepted cloud has a point");
  for (const Point& p : cloud.points) fuzzing::require(p.allFinite(), "points are finite");
  const uint64_t count = static_cast<uint64_t>(message.width) * message.height;
  fuzzing::require(cloud.points.size() + cloud.non_finite == count,
                   "every point is either kept or counted as non-finite");
  return 0;
}
