#pragma once
// The fields of an uncompressed map file (format in src/stillslam/map/
// map_file.cpp), walked from the bytes, so tests can damage one field of a
// real saved map and put the checksum back the way the writer does.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "stillslam/core/fnv1a.h"

namespace stillslam::test {

enum class FieldKind {
  Count,         // u32 number of the records that follow
  KeyFrameId,    // u64 id of a keyframe (a record's own or a reference)
  PointId,       // u64 id of a map point (a record's own or a keyframe slot)
  KeypointIndex, // u32 index into a keyframe's keypoints
  Float64,       // pose, position, normal, distance, camera number
  Float32,       // keypoint coordinates, size, angle, right coordinate, depth
  Int32,         // octave, counts of a point, image size, levels
  Flag,          // u8 origin flag
};

struct Field {
  std::size_t offset = 0;  // in the whole file
  FieldKind kind = FieldKind::Count;
  std::string record;      // e.g. "keyframe 3 keypoint 7 octave"
};

class MapFileLayout {
 public:
  static constexpr std::size_t kHeaderBytes = 32;

  // `file` must be an uncompressed map file.
  explicit MapFileLayout(const std::string& file) : bytes_(file), at_(kHeaderBytes) {
    at_ += 4 + u32();  // sensor
    add(FieldKind::Int32, "camera model", 4);
    for (const char* n : {"fx", "fy", "cx", "cy"}) add(FieldKind::Float64, std::string("camera ") + n, 8);
    const std::uint32_t distortion = u32();
    add(FieldKind::Count, "camera distortion count", 4);
    for (std::uint32_t i = 0; i < distortion; ++i) add(FieldKind::Float64, "camera distortion", 8);
    add(FieldKind::Int32, "camera width", 4);
    add(FieldKind::Int32, "camera height", 4);
    add(FieldKind::Float64, "camera bf", 8);
    add(FieldKind::Float64, "camera close depth", 8);
    add(FieldKind::Int32, "camera levels", 4);
    add(FieldKind::Float32, "camera scale factor", 4);
    at_ += 8;  // vocabulary fingerprint
    at_ += 8;  // active map id
    at_ += 8;  // next map id
    add(FieldKind::KeyFrameId, "next keyframe id", 8);
    add(FieldKind::PointId, "next point id", 8);
    const std::uint32_t maps = u32();
    add(FieldKind::Count, "map count", 4);
    for (std::uint32_t m = 0; m < maps; ++m) walk_map();
  }

  const std::vector<Field>& fields() const { return fields_; }
  std::uint64_t u64_at(std::size_t offset) const { return read<std::uint64_t>(offset); }

  // The checksum of `file` (its last 8 bytes) recomputed as the writer does.
  static void put_checksum(std::string& file) {
    const std::uint64_t sum = fnv1a(file.data(), file.size() - 8);
    std::memcpy(file.data() + file.size() - 8, &sum, 8);
  }

 private:
  template <typename T>
  T read(std::size_t offset) const {
    T v;
    std::memcpy(&v, bytes_.data() + offset, sizeof(T));
    return v;
  }
  std::uint32_t u32() const { return read<std::uint32_t>(at_); }
  void add(FieldKind kind, const std::string& record, std::size_t bytes) {
    fields_.push_back({at_, kind, record});
    at_ += bytes;
  }

  void walk_map() {
    at_ += 8;  // map id
    const std::uint32_t keyframes = u32();
    add(FieldKind::Count, "keyframe count", 4);
    for (std::uint32_t k = 0; k < keyframes; ++k) {
      const std::string kf = "keyframe " + std::to_string(read<std::uint64_t>(at_));
      add(FieldKind::KeyFrameId, kf + " id", 8);
      at_ += 8;  // frame id
      add(FieldKind::Float64, kf + " timestamp", 8);
      for (int i = 0; i < 12; ++i) add(FieldKind::Float64, kf + " pose", 8);
      const std::uint32_t n = u32();
      add(FieldKind::Count, kf + " keypoint count", 4);
      for (std::uint32_t i = 0; i < n; ++i) {
        for (const char* f : {"x", "y", "size", "angle", "response"}) add(FieldKind::Float32, kf + " keypoint " + f, 4);
        add(FieldKind::Int32, kf + " keypoint octave", 4);
        at_ += 4;  // class id
      }
      at_ += 32 * n;  // descriptors
      for (std::uint32_t i = 0; i < n; ++i) add(FieldKind::Float32, kf + " right coordinate", 4);
      for (std::uint32_t i = 0; i < n; ++i) add(FieldKind::Float32, kf + " depth", 4);
      for (std::uint32_t i = 0; i < n; ++i) {
        if (read<std::uint64_t>(at_) == ~0ULL) {
          at_ += 8;
        } else {
          add(FieldKind::PointId, kf + " slot", 8);
        }
      }
      if (read<std::uint64_t>(at_) == ~0ULL) {
        at_ += 8;
      } else {
        add(FieldKind::KeyFrameId, kf + " parent", 8);
      }
      add(FieldKind::Flag, kf + " origin flag", 1);
    }
    const std::uint32_t points = u32();
    add(FieldKind::Count, "point count", 4);
    for (std::uint32_t p = 0; p < points; ++p) {
      const std::string mp = "point " + std::to_string(read<std::uint64_t>(at_));
      add(FieldKind::PointId, mp + " id", 8);
      add(FieldKind::KeyFrameId, mp + " first keyframe", 8);
      for (int i = 0; i < 3; ++i) add(FieldKind::Float64, mp + " position", 8);
      for (int i = 0; i < 3; ++i) add(FieldKind::Float64, mp + " normal", 8);
      at_ += 32;  // descriptor
      add(FieldKind::Float64, mp + " min distance", 8);
      add(FieldKind::Float64, mp + " max distance", 8);
      at_ += 8;  // reference keyframe (any keyframe of the map may be it)
      add(FieldKind::Int32, mp + " visible", 4);
      add(FieldKind::Int32, mp + " found", 4);
      const std::uint32_t m = u32();
      add(FieldKind::Count, mp + " observation count", 4);
      for (std::uint32_t i = 0; i < m; ++i) {
        add(FieldKind::KeyFrameId, mp + " observation keyframe", 8);
        add(FieldKind::KeypointIndex, mp + " observation index", 4);
      }
    }
    const std::uint32_t edges = u32();
    add(FieldKind::Count, "loop edge count", 4);
    for (std::uint32_t e = 0; e < 2 * edges; ++e) add(FieldKind::KeyFrameId, "loop edge end", 8);
  }

  const std::string& bytes_;
  std::size_t at_;
  std::vector<Field> fields_;
};

}  // namespace stillslam::test
