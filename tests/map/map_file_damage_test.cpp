// Map files whose payload is damaged but whose checksum is put back (as a
// hand edit or a faulty copy tool would): every field class of a real saved
// map is damaged with a fixed seed, and each file either gives an Error that
// names the file and says it is damaged, or loads a map of identical
// structure (same keyframes, points, associations, tree and loop edges).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <fstream>
#include <limits>
#include <map>
#include <random>

#include "io/temp_dir.h"
#include "map/map_builder.h"
#include "map/map_file_layout.h"
#include "map/synthetic_scene.h"
#include "stillslam/core/error.h"
#include "stillslam/map/map_file.h"

namespace stillslam {
namespace {

std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
void write_bytes(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

// Everything but the numbers: ids, associations, tree, covisibility, loop edges.
std::string structure_of(const MapFileContents& contents) {
  std::ostringstream s;
  for (const LoadedMap& m : contents.maps) {
    s << "map " << m.id << "\n";
    for (const KeyFramePtr& kf : m.map->keyframes()) {
      s << "kf " << kf->id() << " n " << kf->size() << " origin " << kf->is_origin() << " parent "
        << (kf->parent() ? static_cast<long long>(kf->parent()->id()) : -1) << " slots";
      for (std::size_t i = 0; i < kf->size(); ++i) {
        s << " " << (kf->map_point(i) ? static_cast<long long>(kf->map_point(i)->id()) : -1);
      }
      s << " covisible";
      for (KeyFrame* c : kf->covisibles()) s << " " << c->id() << ":" << kf->weight(c);
      s << "\n";
    }
    for (const MapPointPtr& mp : m.map->map_points()) {
      s << "mp " << mp->id();
      for (const auto& [kf, i] : mp->observations()) s << " " << kf->id() << "/" << i;
      s << "\n";
    }
    for (const auto& [a, b] : m.loop_edges) s << "edge " << a << " " << b << "\n";
  }
  return s.str();
}

class MapFileDamageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::MapBuilder builder(scene_);
    for (int i = 0; i < 6; ++i) builder.add_keyframe(test::pose_at(0.15 * i, 0.02 * i, 4.0 * i));
    // A culled keyframe: its id (3) is below the next id but names no keyframe.
    builder.map().erase_keyframe(builder.map().keyframe(3));
    builder.map().remove_bad_points();
    for (const KeyFramePtr& kf : builder.map().keyframes()) kf->update_connections();
    context_ = MapFileContext{"rgbd", scene_.setup(), 0x1234};
    save_map_file(path(), context_, builder.map(), {{1, 4}, {4, 1}}, MapFileSaveOptions{false, 0});
    original_ = read_bytes(path());
    structure_ = structure_of(load_map_file(path(), context_));
  }
  std::filesystem::path path() const { return dir_.path() / "map.bin"; }

  // Loads `bytes` with the checksum recomputed: the Error's message, or ""
  // after checking that the map loaded has the original structure.
  std::string load_damaged(std::string bytes) {
    test::MapFileLayout::put_checksum(bytes);
    write_bytes(path(), bytes);
    try {
      const MapFileContents contents = load_map_file(path(), context_);
      EXPECT_EQ(structure_of(contents), structure_) << "a damaged file loaded a different map";
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  test::TempDir dir_;
  test::SyntheticScene scene_{400, 7};
  MapFileContext context_;
  std::string original_, structure_;
};

template <typename T>
void put(std::string& bytes, std::size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof(T));
}
template <typename T>
T get(const std::string& bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

// One damage of `field`'s class, chosen by `rng`.
void damage(std::string& bytes, const test::Field& field, std::mt19937& rng) {
  const int pick = std::uniform_int_distribution<int>(0, 3)(rng);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  switch (field.kind) {
    case test::FieldKind::Count: {
      const auto n = get<std::uint32_t>(bytes, field.offset);
      const std::uint32_t values[] = {n + 1, n - 1, n + 1000, 0xFFFFFFFFu};
      put(bytes, field.offset, values[pick]);
      break;
    }
    case test::FieldKind::KeyFrameId:
    case test::FieldKind::PointId: {
      // A culled keyframe's id / an id past the counters / a huge one / another record's.
      const auto id = get<std::uint64_t>(bytes, field.offset);
      const std::uint64_t values[] = {field.kind == test::FieldKind::KeyFrameId ? 3u : id + 100000, id + (1ULL << 40),
                                      ~0ULL - 1, id == 0 ? 1ULL : 0ULL};
      // A parent swapped for another keyframe that keeps the tree acyclic is
      // a valid tree (re-parenting after culling picks any covisible one):
      // the reader cannot tell it from the saved one, so it is not tried.
      const bool parent = field.record.ends_with(" parent");
      put(bytes, field.offset, values[parent ? pick % 3 : pick]);
      break;
    }
    case test::FieldKind::KeypointIndex: {
      const auto i = get<std::uint32_t>(bytes, field.offset);
      const std::uint32_t values[] = {i + 100000, i + 1, i == 0 ? 1u : i - 1, 0xFFFFFFFFu};
      put(bytes, field.offset, values[pick]);
      break;
    }
    case test::FieldKind::Float64: {
      const auto v = get<double>(bytes, field.offset);
      const double values[] = {nan, -inf, 1e300, v + 0.75};
      put(bytes, field.offset, values[pick]);
      break;
    }
    case test::FieldKind::Float32: {
      const auto v = get<float>(bytes, field.offset);
      const float values[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                              -3e38f, v + 0.75f};
      put(bytes, field.offset, values[pick]);
      break;
    }
    case test::FieldKind::Int32: {
      const auto v = get<std::int32_t>(bytes, field.offset);
      const std::int32_t values[] = {-1, v + 1000, std::numeric_limits<std::int32_t>::min(), v - 1};
      put(bytes, field.offset, values[pick]);
      break;
    }
    case test::FieldKind::Flag: {
      const auto v = get<std::uint8_t>(bytes, field.offset);
      const std::uint8_t values[] = {2, static_cast<std::uint8_t>(1 - v), 0xFF, static_cast<std::uint8_t>(1 - v)};
      put(bytes, field.offset, values[pick]);
      break;
    }
  }
}

TEST_F(MapFileDamageTest, DamagedFieldsGiveAnErrorOrTheSameMap) {
  const test::MapFileLayout layout(original_);
  ASSERT_GT(layout.fields().size(), 10000u);
  std::mt19937 rng(15);
  // Fields drawn class by class so the rare ones (flags, counts) are damaged too.
  std::map<test::FieldKind, std::vector<const test::Field*>> by_kind;
  for (const test::Field& f : layout.fields()) by_kind[f.kind].push_back(&f);
  ASSERT_EQ(by_kind.size(), 8u);
  int damaged = 0, refused = 0;
  std::map<test::FieldKind, int> refused_of_kind;
  for (int trial = 0; trial < 240; ++trial) {
    auto& fields = std::next(by_kind.begin(), trial % static_cast<int>(by_kind.size()))->second;
    const test::Field& field = *fields[std::uniform_int_distribution<std::size_t>(0, fields.size() - 1)(rng)];
    std::string bytes = original_;
    damage(bytes, field, rng);
    if (bytes == original_) continue;
    ++damaged;
    SCOPED_TRACE(field.record + " at byte " + std::to_string(field.offset));
    const std::string e = load_damaged(bytes);
    if (e.empty()) continue;
    ++refused;
    ++refused_of_kind[field.kind];
    EXPECT_NE(e.find(path().string() + ": "), std::string::npos) << e;
    const bool damaged_message = e.find("damaged map file (") != std::string::npos;
    const bool camera_message = e.find("calibration mismatch") != std::string::npos;
    EXPECT_TRUE(damaged_message || camera_message) << e;
    if (damaged_message) {
      EXPECT_NE(e.find("re-create it with `stillslam run --save-map`"), std::string::npos) << e;
    }
  }
  EXPECT_GE(damaged, 230);
  // Ids, counts, indices and flags are structure: every damage is refused.
  // Numbers changed by a finite amount (v + 0.75) can still make a valid map.
  EXPECT_GE(refused, 200) << "of " << damaged;
  for (const auto& [kind, n] : refused_of_kind) EXPECT_GE(n, 15) << "field kind " << static_cast<int>(kind);
}

// The error names the record: which keyframe or point, which keypoint or observation.
TEST_F(MapFileDamageTest, ErrorsNameTheRecord) {
  const test::MapFileLayout layout(original_);
  const auto first = [&](const std::string& record) -> const test::Field& {
    for (const test::Field& f : layout.fields()) {
      if (f.record.find(record) != std::string::npos) return f;
    }
    throw std::runtime_error("no field " + record);
  };
  struct Case {
    std::string record;
    std::function<void(std::string&, std::size_t)> damage;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"observation index", [](std::string& b, std::size_t at) { put<std::uint32_t>(b, at, 900000); },
       ", observation 0: keypoint 900000 of keyframe"},
      {"observation keyframe", [](std::string& b, std::size_t at) { put<std::uint64_t>(b, at, 3); },
       ", observation 0: names keyframe 3, which the map does not have"},
      {"keyframe 1 slot", [](std::string& b, std::size_t at) { put<std::uint64_t>(b, at, 1ULL << 40); },
       "map 0, keyframe 1, keypoint "},
      {"keyframe 2 pose", [](std::string& b, std::size_t at) { put<double>(b, at, 0.5); },
       "map 0, keyframe 2: pose rotation is not a rotation"},
      {"keyframe 2 timestamp", [](std::string& b, std::size_t at) { put<double>(b, at, NAN); },
       "map 0, keyframe 2: timestamp"},
      {"keyframe 4 keypoint octave", [](std::string& b, std::size_t at) { put<std::int32_t>(b, at, 8); },
       "map 0, keyframe 4, keypoint 0: keypoint octave 8 outside the 8 levels"},
      {"keyframe 1 depth", [](std::string& b, std::size_t at) { put<float>(b, at, INFINITY); },
       "map 0, keyframe 1, keypoint 0: depth inf"},
      {"keyframe 4 parent", [](std::string& b, std::size_t at) { put<std::uint64_t>(b, at, 4); },
       "map 0, keyframe 4: is its own parent"},
      {"keyframe 0 origin flag", [](std::string& b, std::size_t at) { put<std::uint8_t>(b, at, 0); },
       "map 0, keyframes: 0 origins, a map has one"},
      {"min distance", [](std::string& b, std::size_t at) { put<double>(b, at, -1.0); },
       ": distance range [-1, "},
      {"normal", [](std::string& b, std::size_t at) { put<double>(b, at, 7.0); }, ": normal of length"},
      {"loop edge end", [](std::string& b, std::size_t at) { put<std::uint64_t>(b, at, 3); },
       "map 0, loop edge 0: names keyframe 3"},
      {"camera fx", [](std::string& b, std::size_t at) { put<double>(b, at, -500.0); },
       "damaged map file (camera: focal length"},
  };
  for (const Case& c : cases) {
    std::string bytes = original_;
    c.damage(bytes, first(c.record).offset);
    const std::string e = load_damaged(bytes);
    EXPECT_NE(e.find(c.message), std::string::npos) << c.record << ": " << e;
    EXPECT_NE(e.find("map.bin: damaged map file ("), std::string::npos) << c.record << ": " << e;
  }
}

// A spanning tree whose parents form a cycle (2 -> 4 -> 2) is refused.
TEST_F(MapFileDamageTest, ParentCycleIsRefused) {
  const test::MapFileLayout layout(original_);
  std::string bytes = original_;
  for (const test::Field& f : layout.fields()) {
    if (f.record == "keyframe 2 parent") put<std::uint64_t>(bytes, f.offset, 4);
    if (f.record == "keyframe 4 parent") put<std::uint64_t>(bytes, f.offset, 2);
  }
  EXPECT_NE(load_damaged(bytes).find("its parents form a cycle"), std::string::npos);
}

// A zstd header claiming a payload far larger than the data could hold is
// refused before anything that size is allocated.
TEST_F(MapFileDamageTest, ImplausiblePayloadSizeIsRefused) {
  test::MapBuilder builder(scene_);
  builder.add_keyframe(test::pose_at(0));
  save_map_file(path(), context_, builder.map());
  std::string bytes = read_bytes(path());
  put<std::uint64_t>(bytes, 24, 1ULL << 50);  // payload size after decompression
  const std::string e = load_damaged(bytes);
  EXPECT_NE(e.find("map.bin: damaged map file (payload of 1125899906842624 bytes from "), std::string::npos) << e;
}

}  // namespace
}  // namespace stillslam
