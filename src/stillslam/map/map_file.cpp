// Map file format, version 1 (all integers little-endian):
//   8 bytes  magic "STILLMAP"
//   u32      format version
//   u32      compression of the payload (0: none, 1: zstd, one frame)
//   u64      stored payload size, u64 payload size after decompression
//   payload
//   u64      FNV-1a 64 checksum of every byte before it
// Payload:
//   context: str sensor; camera (u32 model, f64 fx fy cx cy, u32 n + n f64
//            distortion, i32 width height, f64 bf close_depth, i32 levels,
//            f32 scale factor); u64 vocabulary fingerprint
//   u64 active map id, next map id, next keyframe id, next point id (the
//       atlas' counters: ids are unique across maps)
//   u32 map count, per map:
//     u64 id
//     u32 keyframes, each: u64 id, frame id; f64 timestamp; 12 f64 T_cam_world
//         (3x4, row-major); u32 n; n x (f32 x y size angle response, i32 octave
//         class_id); n x 32 descriptor bytes; n f32 u_right; n f32 depth;
//         n u64 map-point id (kNone: empty slot); u64 parent id; u8 origin flag
//     u32 points, each: u64 id, first keyframe id; 3 f64 position; 3 f64 normal;
//         32 descriptor bytes; f64 min, max distance; u64 reference keyframe id;
//         i32 visible, found; u32 m; m x (u64 keyframe id, u32 keypoint index)
//     u32 loop edges, each u64 a, b
// (str = u32 length + bytes.)
#include "stillslam/map/map_file.h"

#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "stillslam/core/atomic_file.h"
#include "stillslam/core/byte_io.h"
#include "stillslam/core/error.h"
#include "stillslam/core/fnv1a.h"
#include "stillslam/map/frame.h"
#include "stillslam/map/map_file_checks.h"

namespace stillslam {

namespace {

constexpr char kMagic[8] = {'S', 'T', 'I', 'L', 'L', 'M', 'A', 'P'};
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8;
constexpr std::size_t kChecksumBytes = 8;
constexpr std::uint64_t kNone = ~0ULL;
constexpr std::uint32_t kNoCompression = 0;
constexpr std::uint32_t kZstd = 1;
constexpr std::uint64_t kMaxZstdRatio = 64;

std::string rerun_hint() { return "re-create it with `stillslam run --save-map`"; }

// A payload reader whose errors name the file (`name`) and say how to fix it.
ByteReader map_file_reader(const char* data, std::size_t size, const std::string& name) {
  return ByteReader(data, size, [name](const std::string& detail) {
    return Error(name + ": damaged map file (" + detail + "); " + rerun_hint());
  });
}

// The camera numbers that must agree between the map and the running system.
struct CameraRecord {
  std::uint32_t model = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::vector<double> distortion;
  std::int32_t width = 0, height = 0;
  double bf = 0, close_depth = 0;
  std::int32_t levels = 0;
  float scale_factor = 0;

  static CameraRecord of(const CameraSetup& setup) {
    const CameraCalibration& c = setup.camera.calibration();
    CameraRecord r;
    r.model = static_cast<std::uint32_t>(c.model);
    r.fx = setup.camera.fx();
    r.fy = setup.camera.fy();
    r.cx = setup.camera.cx();
    r.cy = setup.camera.cy();
    r.distortion = c.distortion;
    r.width = c.width;
    r.height = c.height;
    r.bf = setup.camera.bf();
    r.close_depth = setup.close_depth;
    r.levels = setup.pyramid.n_levels;
    r.scale_factor = setup.pyramid.scale_factor;
    return r;
  }
  void write(ByteWriter& w) const {
    w.put(model);
    for (double v : {fx, fy, cx, cy}) w.put(v);
    w.put(static_cast<std::uint32_t>(distortion.size()));
    for (double v : distortion) w.put(v);
    w.put(width);
    w.put(height);
    w.put(bf);
    w.put(close_depth);
    w.put(levels);
    w.put(scale_factor);
  }
  static CameraRecord read(ByteReader& r) {
    CameraRecord c;
    c.model = r.get<std::uint32_t>();
    c.fx = r.get<double>();
    c.fy = r.get<double>();
    c.cx = r.get<double>();
    c.cy = r.get<double>();
    c.distortion.resize(r.get_count(sizeof(double)));
    for (double& v : c.distortion) v = r.get<double>();
    c.width = r.get<std::int32_t>();
    c.height = r.get<std::int32_t>();
    c.bf = r.get<double>();
    c.close_depth = r.get<double>();
    c.levels = r.get<std::int32_t>();
    c.scale_factor = r.get<float>();
    if (const auto problem = c.problem()) r.fail("camera: " + *problem);
    return c;
  }
  // What makes the record impossible for a camera the system could have run with.
  std::optional<std::string> problem() const {
    const auto bad = [](double v) { return !std::isfinite(v); };
    if (model > 1) return "model " + std::to_string(model);
    if (bad(fx) || bad(fy) || fx <= 0 || fy <= 0) return "focal length " + describe();
    if (bad(cx) || bad(cy) || bad(bf) || bad(close_depth) || bf < 0 || close_depth < 0) return describe();
    if (distortion.size() > 14 || std::any_of(distortion.begin(), distortion.end(), bad)) return describe();
    if (width < 0 || height < 0) return "image size " + describe();
    if (levels < 1 || levels > 32 || !std::isfinite(scale_factor) || scale_factor < 1 || scale_factor > 4) {
      return "pyramid " + describe();
    }
    return std::nullopt;
  }
  // Equal up to text round-off of the settings (relative 1e-9).
  bool matches(const CameraRecord& o) const {
    const auto same = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)}); };
    if (model != o.model || width != o.width || height != o.height || levels != o.levels ||
        distortion.size() != o.distortion.size() || !same(scale_factor, o.scale_factor)) {
      return false;
    }
    for (std::size_t i = 0; i < distortion.size(); ++i) {
      if (!same(distortion[i], o.distortion[i])) return false;
    }
    return same(fx, o.fx) && same(fy, o.fy) && same(cx, o.cx) && same(cy, o.cy) && same(bf, o.bf) &&
           same(close_depth, o.close_depth);
  }
  std::string describe() const {
    std::ostringstream s;
    s << (model == 0 ? "pinhole" : "KannalaBrandt8") << " " << width << "x" << height << " fx " << fx << " fy " << fy
      << " cx " << cx << " cy " << cy << " bf " << bf << " distortion [";
    for (std::size_t i = 0; i < distortion.size(); ++i) s << (i ? " " : "") << distortion[i];
    s << "] close depth " << close_depth << " m, " << levels << " ORB levels x " << scale_factor;
    return s.str();
  }
};

std::string hex(std::uint64_t v) {
  std::ostringstream s;
  s << std::hex << v;
  return s.str();
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw Error("map file " + path.string() + " not found or unreadable: pass a file written by "
                "`stillslam run --save-map FILE`");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

// Reads and writes the private state of keyframes, points and maps.
struct MapFileAccess {
  static void write_payload(ByteWriter& w, const MapFileContext& context, const std::vector<MapToSave>& maps,
                            std::uint64_t active_map_id, std::uint64_t next_map_id) {
    w.put_string(context.sensor);
    CameraRecord::of(*context.setup).write(w);
    w.put(context.vocabulary_checksum);
    std::uint64_t next_keyframe_id = 0, next_point_id = 0;
    for (const MapToSave& m : maps) {
      next_keyframe_id = std::max(next_keyframe_id, m.map->id_counters()->next_keyframe.load());
      next_point_id = std::max(next_point_id, m.map->id_counters()->next_point.load());
      next_map_id = std::max(next_map_id, m.map->id() + 1);
    }
    w.put(active_map_id);
    w.put(next_map_id);
    w.put(next_keyframe_id);
    w.put(next_point_id);
    w.put(static_cast<std::uint32_t>(maps.size()));
    for (const MapToSave& m : maps) write_map(w, m);
  }

  static MapFileContents read_payload(ByteReader& r, const std::filesystem::path& path,
                                      const MapFileContext& expected, const std::shared_ptr<MapIdCounters>& ids) {
    const std::string sensor = r.get_string();
    const CameraRecord camera = CameraRecord::read(r);
    const auto vocabulary = r.get<std::uint64_t>();
    if (sensor != expected.sensor) {
      throw Error(path.string() + ": the map was made with a " + sensor + " sensor, this run is " + expected.sensor +
                  "; run it with the kind of input the map was saved from");
    }
    const CameraRecord running = CameraRecord::of(*expected.setup);
    if (!camera.matches(running)) {
      throw Error(path.string() + ": calibration mismatch: the map was made with " + camera.describe() +
                  ", this run uses " + running.describe() + "; use the settings (and dataset calibration) the map "
                  "was saved with");
    }
    if (vocabulary != expected.vocabulary_checksum) {
      const auto name = [](std::uint64_t v) { return v == 0 ? std::string("none") : "fingerprint " + hex(v); };
      throw Error(path.string() + ": vocabulary mismatch: the map was saved with vocabulary " + name(vocabulary) +
                  ", this run has " + name(expected.vocabulary_checksum) +
                  "; run with the --vocabulary the map was saved with");
    }
    MapFileContents contents;
    contents.active_map_id = r.get<std::uint64_t>();
    contents.next_map_id = r.get<std::uint64_t>();
    contents.next_keyframe_id = r.get<std::uint64_t>();
    contents.next_point_id = r.get<std::uint64_t>();
    // Loaded maps share the caller's counters (an atlas') or new ones, raised
    // past every id in the file.
    const std::shared_ptr<MapIdCounters> counters = ids ? ids : std::make_shared<MapIdCounters>();
    counters->next_keyframe = std::max(counters->next_keyframe.load(), contents.next_keyframe_id);
    counters->next_point = std::max(counters->next_point.load(), contents.next_point_id);
    const std::size_t n_maps = r.get_count(8 + 4 + 4 + 4);
    for (std::size_t i = 0; i < n_maps; ++i) {
      contents.maps.push_back(read_map(r, expected.setup, counters, contents.next_keyframe_id, contents.next_point_id));
    }
    std::unordered_set<std::uint64_t> keyframe_ids, point_ids, map_ids;
    for (const LoadedMap& m : contents.maps) {
      if (!map_ids.insert(m.id).second) r.fail("duplicate map id " + std::to_string(m.id));
      for (const KeyFramePtr& kf : m.map->keyframes()) {
        if (!keyframe_ids.insert(kf->id()).second) r.fail("keyframe id " + std::to_string(kf->id()) + " in two maps");
      }
      for (const MapPointPtr& mp : m.map->map_points()) {
        if (!point_ids.insert(mp->id()).second) r.fail("point id " + std::to_string(mp->id()) + " in two maps");
      }
    }
    if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes after the last map");
    if (!contents.maps.empty() && map_ids.count(contents.active_map_id) == 0) {
      r.fail("the active map " + std::to_string(contents.active_map_id) + " is not in the file");
    }
    for (std::uint64_t id : map_ids) {
      if (id >= contents.next_map_id) r.fail("map id " + std::to_string(id) + " >= next map id");
    }
    return contents;
  }

  static void write_map(ByteWriter& w, const MapToSave& entry) {
    const Map& map = *entry.map;
    w.put(map.id());
    // Points seen on people (kept as static by the motion check) stay out of
    // the file; keyframe slots that held them are saved empty.
    std::vector<MapPointPtr> points = map.map_points();
    std::erase_if(points, [](const MapPointPtr& mp) { return mp->on_dynamic_instance(); });
    std::unordered_map<const MapPoint*, std::uint64_t> saved_points;
    for (const MapPointPtr& mp : points) saved_points.emplace(mp.get(), mp->id());
    const std::vector<KeyFramePtr> keyframes = map.keyframes();
    std::unordered_map<const KeyFrame*, std::uint64_t> saved_keyframes;
    for (const KeyFramePtr& kf : keyframes) saved_keyframes.emplace(kf.get(), kf->id());
    const auto keyframe_id = [&](const KeyFrame* kf) {
      const auto it = saved_keyframes.find(kf);
      return it == saved_keyframes.end() ? kNone : it->second;
    };

    w.put(static_cast<std::uint32_t>(keyframes.size()));
    for (const KeyFramePtr& kf : keyframes) write_keyframe(w, *kf, saved_points, keyframe_id(kf->parent()));
    w.put(static_cast<std::uint32_t>(points.size()));
    for (const MapPointPtr& mp : points) {
      w.put(mp->id_);
      w.put(mp->first_keyframe_id_);
      for (int i = 0; i < 3; ++i) w.put(mp->position_[i]);
      for (int i = 0; i < 3; ++i) w.put(mp->normal_[i]);
      w.put_bytes(mp->descriptor_.data(), mp->descriptor_.size());
      w.put(mp->min_distance_);
      w.put(mp->max_distance_);
      w.put(keyframe_id(mp->reference_));
      w.put(static_cast<std::int32_t>(mp->visible_));
      w.put(static_cast<std::int32_t>(mp->found_));
      std::vector<std::pair<std::uint64_t, std::uint32_t>> observations;
      for (const auto& [kf, index] : mp->observations_) {
        const std::uint64_t id = keyframe_id(kf);
        if (id != kNone) observations.emplace_back(id, static_cast<std::uint32_t>(index));
      }
      w.put(static_cast<std::uint32_t>(observations.size()));
      for (const auto& [id, index] : observations) {
        w.put(id);
        w.put(index);
      }
    }
    // Edges to keyframes culled since the loop closed are left out (the
    // reader refuses edges to keyframes the map does not have).
    std::unordered_set<std::uint64_t> saved_ids;
    for (const KeyFramePtr& kf : keyframes) saved_ids.insert(kf->id());
    std::vector<std::pair<std::uint64_t, std::uint64_t>> edges;
    for (const auto& [a, b] : entry.loop_edges) {
      if (saved_ids.count(a) != 0 && saved_ids.count(b) != 0) edges.emplace_back(a, b);
    }
    w.put(static_cast<std::uint32_t>(edges.size()));
    for (const auto& [a, b] : edges) {
      w.put(a);
      w.put(b);
    }
  }

  static void write_keyframe(ByteWriter& w, const KeyFrame& kf,
                             const std::unordered_map<const MapPoint*, std::uint64_t>& saved_points,
                             std::uint64_t parent_id) {
    w.put(kf.id());
    w.put(kf.frame_id());
    w.put(kf.timestamp());
    const Eigen::Matrix<double, 3, 4> T = kf.T_cam_world().matrix().topRows<3>();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) w.put(T(r, c));
    }
    const std::size_t n = kf.size();
    w.put(static_cast<std::uint32_t>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const cv::KeyPoint& kp = kf.keypoint(i);
      for (float v : {kp.pt.x, kp.pt.y, kp.size, kp.angle, kp.response}) w.put(v);
      w.put(static_cast<std::int32_t>(kp.octave));
      w.put(static_cast<std::int32_t>(kp.class_id));
    }
    for (std::size_t i = 0; i < n; ++i) w.put_bytes(kf.descriptor(i), 32);
    for (std::size_t i = 0; i < n; ++i) w.put(kf.u_right(i));
    for (std::size_t i = 0; i < n; ++i) w.put(kf.depth(i));
    for (const MapPointPtr& mp : kf.map_points()) {
      const auto it = mp ? saved_points.find(mp.get()) : saved_points.end();
      w.put(it == saved_points.end() ? kNone : it->second);
    }
    w.put(parent_id);
    w.put(static_cast<std::uint8_t>(kf.is_origin() ? 1 : 0));
  }

  static LoadedMap read_map(ByteReader& r, const std::shared_ptr<const CameraSetup>& setup,
                            const std::shared_ptr<MapIdCounters>& ids, std::uint64_t next_keyframe_id,
                            std::uint64_t next_point_id) {
    LoadedMap loaded;
    loaded.id = r.get<std::uint64_t>();
    loaded.map = std::make_unique<Map>(loaded.id, ids);
    Map& map = *loaded.map;
    const std::string map_label = "map " + std::to_string(loaded.id);
    // Errors name the record: "map 0, keyframe 12, keypoint 40: ...".
    const auto fail = [&](const std::string& record, const std::string& why) {
      r.fail(map_label + ", " + record + ": " + why);
    };

    struct PendingKeyFrame {
      std::vector<std::uint64_t> slots;
      std::uint64_t parent = kNone;
    };
    std::vector<PendingKeyFrame> pending(r.get_count(8 + 8 + 8 + 96 + 4 + 9));
    std::vector<KeyFramePtr> keyframes;
    keyframes.reserve(pending.size());
    for (PendingKeyFrame& p : pending) {
      KeyFramePtr kf = read_keyframe(r, setup, p.slots, fail);
      const std::string label = "keyframe " + std::to_string(kf->id());
      p.parent = r.get<std::uint64_t>();
      const auto origin = r.get<std::uint8_t>();
      if (origin > 1) fail(label, "origin flag " + std::to_string(origin));
      kf->set_origin(origin != 0);
      if (kf->id() >= next_keyframe_id) fail(label, "id >= the file's next keyframe id");
      if (map.keyframe(kf->id())) fail(label, "id saved twice");
      map.add_keyframe(kf);
      keyframes.push_back(std::move(kf));
    }
    const auto keyframe_at = [&](std::uint64_t id, const std::string& record) -> KeyFrame* {
      if (id == kNone) return nullptr;
      KeyFrame* kf = map.keyframe(id).get();
      if (kf == nullptr) fail(record, "names keyframe " + std::to_string(id) + ", which the map does not have");
      return kf;
    };

    std::unordered_map<std::uint64_t, MapPointPtr> points;
    const std::size_t n_points = r.get_count(8 + 8 + 48 + 32 + 16 + 8 + 8 + 4);
    for (std::size_t i = 0; i < n_points; ++i) {
      const auto id = r.get<std::uint64_t>();
      const std::string label = "map point " + std::to_string(id);
      const auto first_keyframe_id = r.get<std::uint64_t>();
      Eigen::Vector3d position, normal;
      for (int k = 0; k < 3; ++k) position[k] = r.get<double>();
      for (int k = 0; k < 3; ++k) normal[k] = r.get<double>();
      auto mp = std::make_shared<MapPoint>(id, position, nullptr);
      mp->first_keyframe_id_ = first_keyframe_id;
      mp->culling_start_keyframe_id_ = first_keyframe_id;
      mp->normal_ = normal;
      std::memcpy(mp->descriptor_.data(), r.get_bytes(32), 32);
      mp->min_distance_ = r.get<double>();
      mp->max_distance_ = r.get<double>();
      mp->reference_ = keyframe_at(r.get<std::uint64_t>(), label + " (reference keyframe)");
      mp->visible_ = r.get<std::int32_t>();
      mp->found_ = r.get<std::int32_t>();
      if (id >= next_point_id) fail(label, "id >= the file's next point id");
      if (first_keyframe_id >= next_keyframe_id) fail(label, "first keyframe id >= the file's next keyframe id");
      if (const auto problem = map_file_checks::point(position, normal, mp->min_distance_, mp->max_distance_,
                                                      mp->visible_, mp->found_)) {
        fail(label, *problem);
      }
      const std::size_t n_obs = r.get_count(12);
      if (n_obs == 0) fail(label, "no observations");
      for (std::size_t k = 0; k < n_obs; ++k) {
        const std::string record = label + ", observation " + std::to_string(k);
        KeyFrame* kf = keyframe_at(r.get<std::uint64_t>(), record);
        const auto index = r.get<std::uint32_t>();
        if (kf == nullptr) fail(record, "no keyframe");
        if (index >= kf->size()) {
          fail(record, "keypoint " + std::to_string(index) + " of keyframe " + std::to_string(kf->id()) +
                           ", which has " + std::to_string(kf->size()));
        }
        if (mp->is_observed_by(kf)) fail(record, "keyframe " + std::to_string(kf->id()) + " observes it twice");
        mp->add_observation(kf, index);
      }
      if (!points.emplace(id, mp).second) fail(label, "id saved twice");
      map.add_map_point(mp);
    }

    for (std::size_t k = 0; k < keyframes.size(); ++k) {
      KeyFrame& kf = *keyframes[k];
      const std::string label = "keyframe " + std::to_string(kf.id());
      for (std::size_t i = 0; i < pending[k].slots.size(); ++i) {
        const std::uint64_t id = pending[k].slots[i];
        if (id == kNone) continue;
        const std::string record = label + ", keypoint " + std::to_string(i);
        const auto it = points.find(id);
        if (it == points.end()) fail(record, "names map point " + std::to_string(id) + ", which the map does not have");
        // Slots and observations are two views of one association.
        const auto obs = it->second->observations().find(&kf);
        if (obs == it->second->observations().end() || obs->second != i) {
          fail(record, "holds map point " + std::to_string(id) + ", whose observations do not list it");
        }
        kf.set_map_point(i, it->second);
      }
      KeyFrame* parent = keyframe_at(pending[k].parent, label + " (parent)");
      if (parent == &kf) fail(label, "is its own parent");
      // Before the connections are rebuilt: the saved parent, not the first connection's.
      if (parent) kf.change_parent(parent);
    }
    for (const auto& [id, mp] : points) {
      for (const auto& [kf, index] : mp->observations()) {
        if (kf->map_point(index) != mp) {
          fail("map point " + std::to_string(id), "observed as keypoint " + std::to_string(index) + " of keyframe " +
                                                      std::to_string(kf->id()) + ", whose slot does not hold it");
        }
      }
    }
    check_spanning_tree(keyframes, fail);
    // A map's first keyframe is its origin (a merge clears the other map's):
    // exactly one, the root of the spanning tree.
    const auto origins = std::count_if(keyframes.begin(), keyframes.end(), [](const auto& kf) { return kf->is_origin(); });
    if (!keyframes.empty() && origins != 1) fail("keyframes", std::to_string(origins) + " origins, a map has one");
    for (const KeyFramePtr& kf : keyframes) {
      if (kf->is_origin() && kf->parent() != nullptr) fail("keyframe " + std::to_string(kf->id()), "the origin has a parent");
    }
    for (const KeyFramePtr& kf : keyframes) kf->update_connections();

    const std::size_t n_edges = r.get_count(16);
    for (std::size_t k = 0; k < n_edges; ++k) {
      const auto a = r.get<std::uint64_t>();
      const auto b = r.get<std::uint64_t>();
      const std::string record = "loop edge " + std::to_string(k);
      if (keyframe_at(a, record) == nullptr || keyframe_at(b, record) == nullptr || a == b) {
        fail(record, "joins keyframes " + std::to_string(a) + " and " + std::to_string(b));
      }
      loaded.loop_edges.emplace(a, b);
    }
    // Loop closing records each loop in both directions.
    for (const auto& [a, b] : loaded.loop_edges) {
      if (loaded.loop_edges.count({b, a}) == 0) {
        fail("loop edges", "keyframe " + std::to_string(a) + " to " + std::to_string(b) + " without its reverse");
      }
    }
    return loaded;
  }

  // The parent links form a forest: following them from any keyframe ends.
  template <typename Fail>
  static void check_spanning_tree(const std::vector<KeyFramePtr>& keyframes, const Fail& fail) {
    for (const KeyFramePtr& kf : keyframes) {
      std::size_t steps = 0;
      for (const KeyFrame* p = kf->parent(); p != nullptr; p = p->parent()) {
        if (++steps > keyframes.size()) fail("keyframe " + std::to_string(kf->id()), "its parents form a cycle");
      }
    }
  }

  template <typename Fail>
  static KeyFramePtr read_keyframe(ByteReader& r, const std::shared_ptr<const CameraSetup>& setup,
                                   std::vector<std::uint64_t>& slots, const Fail& fail) {
    const auto id = r.get<std::uint64_t>();
    const std::string label = "keyframe " + std::to_string(id);
    const auto frame_id = r.get<std::uint64_t>();
    const auto timestamp = r.get<double>();
    if (!std::isfinite(timestamp)) fail(label, "timestamp " + std::to_string(timestamp));
    Eigen::Matrix<double, 3, 4> T3x4;
    for (int row = 0; row < 3; ++row) {
      for (int c = 0; c < 4; ++c) T3x4(row, c) = r.get<double>();
    }
    if (const auto problem = map_file_checks::pose(T3x4)) fail(label, *problem);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.matrix().topRows<3>() = T3x4;
    const std::size_t n = r.get_count(28 + 32 + 8 + 8);
    std::vector<cv::KeyPoint> keypoints(n);
    for (std::size_t i = 0; i < n; ++i) {
      cv::KeyPoint& kp = keypoints[i];
      kp.pt.x = r.get<float>();
      kp.pt.y = r.get<float>();
      kp.size = r.get<float>();
      kp.angle = r.get<float>();
      kp.response = r.get<float>();
      kp.octave = r.get<std::int32_t>();
      kp.class_id = r.get<std::int32_t>();
      if (const auto problem = map_file_checks::keypoint(kp, setup->pyramid.n_levels)) {
        fail(label + ", keypoint " + std::to_string(i), *problem);
      }
    }
    cv::Mat descriptors(static_cast<int>(n), 32, CV_8U);
    if (n > 0) std::memcpy(descriptors.data, r.get_bytes(n * 32), n * 32);
    std::vector<float> u_right(n), depth(n);
    for (float& v : u_right) v = r.get<float>();
    for (float& v : depth) v = r.get<float>();
    for (std::size_t i = 0; i < n; ++i) {
      if (const auto problem = map_file_checks::stereo(u_right[i], depth[i])) {
        fail(label + ", keypoint " + std::to_string(i), *problem);
      }
    }
    slots.resize(n);
    for (std::uint64_t& s : slots) s = r.get<std::uint64_t>();
    Frame frame(frame_id, timestamp, setup, keypoints, keypoints, std::move(descriptors), std::move(u_right),
                std::move(depth));
    frame.set_pose(T);
    return std::make_shared<KeyFrame>(id, frame);
  }
};

MapFileStats save_map_file(const std::filesystem::path& path, const MapFileContext& context,
                           const std::vector<MapToSave>& maps, std::uint64_t active_map_id,
                           std::uint64_t next_map_id, const MapFileSaveOptions& options) {
  if (!context.setup) throw Error("save_map_file: no camera setup given for " + path.string());
  ByteWriter payload;
  MapFileAccess::write_payload(payload, context, maps, active_map_id, next_map_id);
  const std::string& raw = payload.bytes();

  ByteWriter file;
  file.put_bytes(kMagic, sizeof(kMagic));
  file.put(kMapFileVersion);
  file.put(options.compress ? kZstd : kNoCompression);
  std::string& out = file.bytes();
  const std::size_t sizes_at = out.size();
  file.put(std::uint64_t{0});  // stored size, filled in below
  file.put(static_cast<std::uint64_t>(raw.size()));
  if (options.compress) {
    out.resize(kHeaderBytes + ZSTD_compressBound(raw.size()));
    const std::size_t n = ZSTD_compress(out.data() + kHeaderBytes, out.size() - kHeaderBytes, raw.data(), raw.size(),
                                        options.zstd_level);
    if (ZSTD_isError(n)) throw Error("cannot compress map for " + path.string() + ": " + ZSTD_getErrorName(n));
    out.resize(kHeaderBytes + n);
  } else {
    out += raw;
  }
  const auto stored = static_cast<std::uint64_t>(out.size() - kHeaderBytes);
  std::memcpy(out.data() + sizes_at, &stored, sizeof(stored));
  MapFileStats stats;
  stats.raw_bytes = raw.size();
  payload.bytes().clear();
  payload.bytes().shrink_to_fit();
  file.put(fnv1a(out.data(), out.size()));

  write_file_atomically(path, file.bytes(), "map file");

  stats.bytes = file.bytes().size();
  stats.maps = maps.size();
  for (const MapToSave& m : maps) {
    stats.keyframes += m.map->num_keyframes();
    for (const MapPointPtr& mp : m.map->map_points()) {
      ++(mp->on_dynamic_instance() ? stats.points_on_people : stats.map_points);
    }
  }
  return stats;
}

MapFileStats save_map_file(const std::filesystem::path& path, const MapFileContext& context, const Map& map,
                           const MapLoopEdges& loop_edges, const MapFileSaveOptions& options) {
  return save_map_file(path, context, {MapToSave{&map, loop_edges}}, map.id(), 0, options);
}

MapFileContents load_map_file(const std::filesystem::path& path, const MapFileContext& expected,
                              const std::shared_ptr<MapIdCounters>& ids) {
  if (!expected.setup) throw Error("load_map_file: no camera setup given for " + path.string());
  const std::string bytes = read_file(path);
  const std::string name = path.string();
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    throw Error(name + ": not a stillslam map file (no STILLMAP header); pass a file written by "
                "`stillslam run --save-map FILE`");
  }
  if (bytes.size() < kHeaderBytes + kChecksumBytes) {
    throw Error(name + ": truncated map file (" + std::to_string(bytes.size()) + " bytes); " + rerun_hint());
  }
  ByteReader header = map_file_reader(bytes.data() + sizeof(kMagic), kHeaderBytes - sizeof(kMagic), name);
  const auto version = header.get<std::uint32_t>();
  if (version != kMapFileVersion) {
    throw Error(name + ": map file format version " + std::to_string(version) + ", this build reads version " +
                std::to_string(kMapFileVersion) + "; " + rerun_hint() + " using this build");
  }
  const auto compression = header.get<std::uint32_t>();
  const auto stored = header.get<std::uint64_t>();
  const auto raw = header.get<std::uint64_t>();
  const std::uint64_t expected_size = kHeaderBytes + stored + kChecksumBytes;
  if (bytes.size() < expected_size) {
    throw Error(name + ": truncated map file (" + std::to_string(bytes.size()) + " bytes, the header says " +
                std::to_string(expected_size) + "); " + rerun_hint());
  }
  std::uint64_t checksum;
  std::memcpy(&checksum, bytes.data() + bytes.size() - kChecksumBytes, kChecksumBytes);
  if (bytes.size() != expected_size || fnv1a(bytes.data(), bytes.size() - kChecksumBytes) != checksum) {
    throw Error(name + ": damaged map file (checksum mismatch); " + rerun_hint());
  }
  const char* data = bytes.data() + kHeaderBytes;
  std::string decompressed;
  if (compression == kZstd) {
    // The payload (descriptors, ids, floats) compresses to about two thirds;
    // a size far past that is a damaged header, not a reason to allocate it.
    if (raw > kMaxZstdRatio * stored + 4096) {
      throw Error(name + ": damaged map file (payload of " + std::to_string(raw) + " bytes from " +
                  std::to_string(stored) + " compressed); " + rerun_hint());
    }
    decompressed.resize(raw);
    const std::size_t n = ZSTD_decompress(decompressed.data(), decompressed.size(), data, stored);
    if (ZSTD_isError(n) || n != raw) {
      throw Error(name + ": damaged map file (zstd: " + (ZSTD_isError(n) ? ZSTD_getErrorName(n) : "size mismatch") +
                  "); " + rerun_hint());
    }
    data = decompressed.data();
  } else if (compression != kNoCompression || raw != stored) {
    throw Error(name + ": damaged map file (unknown payload compression " + std::to_string(compression) + "); " +
                rerun_hint());
  }
  ByteReader payload = map_file_reader(data, raw, name);
  return MapFileAccess::read_payload(payload, path, expected, ids);
}

}  // namespace stillslam
