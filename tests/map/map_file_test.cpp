// Map save/load: a synthetic map survives the round trip field by field,
// covisibility is rebuilt to the same graph, and every bad file gives its
// own clear error naming the file.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <random>
#include <set>

#include "io/temp_dir.h"
#include "map/map_builder.h"
#include "map/synthetic_scene.h"
#include "stillslam/core/error.h"
#include "stillslam/map/atlas.h"
#include "stillslam/map/frame.h"
#include "stillslam/map/map_file.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam {
namespace {

std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
void write_bytes(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

// The message of the Error `f` throws ("" when it does not throw).
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::uint64_t id_or_none(const KeyFrame* kf) { return kf ? kf->id() : ~0ULL; }

void expect_keyframes_equal(const KeyFrame& a, const KeyFrame& b) {
  SCOPED_TRACE("keyframe " + std::to_string(a.id()));
  EXPECT_EQ(a.id(), b.id());
  EXPECT_EQ(a.frame_id(), b.frame_id());
  EXPECT_EQ(a.timestamp(), b.timestamp());
  EXPECT_TRUE(a.T_cam_world().matrix() == b.T_cam_world().matrix());
  EXPECT_EQ(a.is_origin(), b.is_origin());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    const cv::KeyPoint &ka = a.keypoint(i), &kb = b.keypoint(i);
    ASSERT_TRUE(ka.pt == kb.pt && ka.size == kb.size && ka.angle == kb.angle && ka.response == kb.response &&
                ka.octave == kb.octave && ka.class_id == kb.class_id)
        << "keypoint " << i;
    ASSERT_EQ(std::memcmp(a.descriptor(i), b.descriptor(i), 32), 0) << "descriptor " << i;
    ASSERT_EQ(a.u_right(i), b.u_right(i));
    ASSERT_EQ(a.depth(i), b.depth(i));
    const MapPointPtr &pa = a.map_point(i), &pb = b.map_point(i);
    ASSERT_EQ(pa == nullptr, pb == nullptr) << "slot " << i;
    if (pa) {
      ASSERT_EQ(pa->id(), pb->id()) << "slot " << i;
    }
  }
  EXPECT_EQ(id_or_none(a.parent()), id_or_none(b.parent()));
  std::vector<std::uint64_t> ca, cb;
  for (const KeyFrame* c : a.children()) ca.push_back(c->id());
  for (const KeyFrame* c : b.children()) cb.push_back(c->id());
  EXPECT_EQ(ca, cb);
  // Covisibility: same neighbours, same order, same weights.
  const auto na = a.covisibles(), nb = b.covisibles();
  ASSERT_EQ(na.size(), nb.size());
  for (std::size_t i = 0; i < na.size(); ++i) {
    EXPECT_EQ(na[i]->id(), nb[i]->id());
    EXPECT_EQ(a.weight(na[i]), b.weight(nb[i]));
  }
}

void expect_points_equal(const MapPoint& a, const MapPoint& b) {
  SCOPED_TRACE("point " + std::to_string(a.id()));
  EXPECT_EQ(a.id(), b.id());
  EXPECT_EQ(a.first_keyframe_id(), b.first_keyframe_id());
  EXPECT_TRUE(a.position() == b.position());
  EXPECT_TRUE(a.normal() == b.normal());
  EXPECT_EQ(std::memcmp(a.descriptor(), b.descriptor(), 32), 0);
  EXPECT_EQ(a.min_distance(), b.min_distance());
  EXPECT_EQ(a.max_distance(), b.max_distance());
  EXPECT_EQ(a.visible(), b.visible());
  EXPECT_EQ(a.found(), b.found());
  EXPECT_EQ(a.num_observations(), b.num_observations());
  std::vector<std::pair<std::uint64_t, std::size_t>> oa, ob;
  for (const auto& [kf, i] : a.observations()) oa.emplace_back(kf->id(), i);
  for (const auto& [kf, i] : b.observations()) ob.emplace_back(kf->id(), i);
  EXPECT_EQ(oa, ob);
}

void expect_maps_equal(const Map& a, const Map& b) {
  EXPECT_EQ(a.id(), b.id());
  const auto ka = a.keyframes(), kb = b.keyframes();
  ASSERT_EQ(ka.size(), kb.size());
  for (std::size_t i = 0; i < ka.size(); ++i) expect_keyframes_equal(*ka[i], *kb[i]);
  const auto pa = a.map_points(), pb = b.map_points();
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t i = 0; i < pa.size(); ++i) expect_points_equal(*pa[i], *pb[i]);
}

// The reference keyframe has no getter; update_normal_and_depth measures the
// distance range from it, so equal results after the update mean equal references.
void expect_same_reference_keyframes(const Map& a, const Map& b, const ScalePyramid& pyramid) {
  const auto pa = a.map_points(), pb = b.map_points();
  for (std::size_t i = 0; i < pa.size(); ++i) {
    pa[i]->update_normal_and_depth(pyramid);
    pb[i]->update_normal_and_depth(pyramid);
    ASSERT_EQ(pa[i]->max_distance(), pb[i]->max_distance()) << "point " << pa[i]->id();
  }
}

class MapFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (int i = 0; i < 6; ++i) builder_.add_keyframe(test::pose_at(0.15 * i, 0.02 * i, 4.0 * i));
    // Fields the builder leaves at defaults.
    const auto points = map().map_points();
    for (std::size_t i = 0; i < points.size(); i += 7) {
      points[i]->increase_visible(static_cast<int>(i % 5) + 3);
      points[i]->increase_found(static_cast<int>(i % 3));
    }
    // A culled keyframe is not saved; its children get another parent.
    map().erase_keyframe(map().keyframe(3));
    map().remove_bad_points();
    // The live graph is built incrementally (older keyframes keep only strong
    // edges to newer ones); a load rebuilds every keyframe's edges, as a
    // refresh of each keyframe does.
    for (const KeyFramePtr& kf : map().keyframes()) kf->update_connections();
    context_.sensor = "rgbd";
    context_.setup = scene_.setup();
    context_.vocabulary_checksum = 0x1234;
  }
  Map& map() { return builder_.map(); }
  std::filesystem::path saved() {
    const auto path = dir_.path() / "map.bin";
    save_map_file(path, context_, map(), {{1, 4}, {4, 1}});
    return path;
  }

  test::TempDir dir_;
  test::SyntheticScene scene_;
  test::MapBuilder builder_{scene_};
  MapFileContext context_;
};

TEST_F(MapFileTest, RoundTripKeepsEveryField) {
  const auto path = dir_.path() / "map.bin";
  const MapFileStats stats = save_map_file(path, context_, map(), {{1, 4}, {4, 1}});
  EXPECT_EQ(stats.maps, 1u);
  EXPECT_EQ(stats.keyframes, 5u);
  EXPECT_EQ(stats.map_points, map().num_map_points());
  EXPECT_GT(stats.map_points, 500u);
  EXPECT_EQ(stats.bytes, std::filesystem::file_size(path));
  EXPECT_FALSE(std::filesystem::exists(dir_.path() / "map.bin.partial"));

  const MapFileContents loaded = load_map_file(path, context_);
  ASSERT_EQ(loaded.maps.size(), 1u);
  EXPECT_EQ(loaded.active_map_id, 0u);
  EXPECT_EQ(loaded.next_keyframe_id, 6u);  // keyframe 3 was culled, the counter stays
  EXPECT_EQ(loaded.next_point_id, map().id_counters()->next_point.load());
  EXPECT_EQ(loaded.maps[0].loop_edges, (MapLoopEdges{{1, 4}, {4, 1}}));
  const Map& copy = *loaded.maps[0].map;
  EXPECT_EQ(copy.keyframe(3), nullptr);
  EXPECT_EQ(copy.id_counters()->next_keyframe.load(), 6u);
  EXPECT_EQ(copy.keyframe(4)->setup().camera.fx(), 500.0);
  expect_maps_equal(map(), copy);
  expect_same_reference_keyframes(map(), copy, scene_.setup()->pyramid);
  // Keyframe 4 lost its parent 3 to the culling: the re-parented tree is saved.
  EXPECT_NE(copy.keyframe(4)->parent(), nullptr);
  EXPECT_TRUE(copy.keyframe(0)->is_origin());
  EXPECT_EQ(copy.keyframe(0)->parent(), nullptr);
}

TEST_F(MapFileTest, CompressedAndPlainFilesHoldTheSameMap) {
  const auto plain = dir_.path() / "plain.map";
  const auto packed = dir_.path() / "packed.map";
  MapFileSaveOptions no_compression;
  no_compression.compress = false;
  const MapFileStats a = save_map_file(plain, context_, map(), {}, no_compression);
  const MapFileStats b = save_map_file(packed, context_, map());
  EXPECT_EQ(a.raw_bytes, b.raw_bytes);
  EXPECT_EQ(a.bytes, a.raw_bytes + 40);  // header and checksum
  // Synthetic descriptors are random bytes: the rest compresses.
  EXPECT_LT(b.bytes, a.bytes * 0.8);
  expect_maps_equal(*load_map_file(plain, context_).maps[0].map, *load_map_file(packed, context_).maps[0].map);
}

TEST_F(MapFileTest, LoadedMapKeepsWorking) {
  const MapFileContents loaded = load_map_file(saved(), context_);
  Map& copy = *loaded.maps[0].map;
  // New objects continue the id sequence; the feature grid was rebuilt.
  Frame frame = scene_.make_frame(99, test::pose_at(0.4));
  frame.set_pose(test::pose_at(0.4));
  EXPECT_EQ(copy.create_keyframe(frame)->id(), 6u);
  const KeyFramePtr kf = copy.keyframe(2);
  const cv::KeyPoint& kp = kf->keypoint(10);
  const auto near = kf->features_in_area(kp.pt.x, kp.pt.y, 1.f);
  EXPECT_NE(std::find(near.begin(), near.end(), 10u), near.end());
}

TEST_F(MapFileTest, SeveralMapsShareTheCallersCounters) {
  auto ids = std::make_shared<MapIdCounters>();
  test::MapBuilder first(scene_, 3, ids), second(scene_, 5, ids);
  for (int i = 0; i < 3; ++i) first.add_keyframe(test::pose_at(0.2 * i));
  for (int i = 0; i < 2; ++i) second.add_keyframe(test::pose_at(-0.2 * i, 0.1));
  const auto path = dir_.path() / "atlas.bin";
  const MapFileStats stats =
      save_map_file(path, context_, {MapToSave{&first.map(), {}}, MapToSave{&second.map(), {}}}, 5, 7);
  EXPECT_EQ(stats.maps, 2u);
  EXPECT_EQ(stats.keyframes, 5u);

  auto atlas_ids = std::make_shared<MapIdCounters>();
  const MapFileContents loaded = load_map_file(path, context_, atlas_ids);
  ASSERT_EQ(loaded.maps.size(), 2u);
  EXPECT_EQ(loaded.active_map_id, 5u);
  EXPECT_EQ(loaded.next_map_id, 7u);
  EXPECT_EQ(loaded.maps[0].map->id(), 3u);
  EXPECT_EQ(loaded.maps[1].map->id(), 5u);
  EXPECT_EQ(loaded.maps[0].map->id_counters(), atlas_ids);
  EXPECT_EQ(loaded.maps[1].map->id_counters(), atlas_ids);
  EXPECT_EQ(atlas_ids->next_keyframe.load(), 5u);
  EXPECT_EQ(atlas_ids->next_point.load(), ids->next_point.load());
  expect_maps_equal(first.map(), *loaded.maps[0].map);
  expect_maps_equal(second.map(), *loaded.maps[1].map);
  // The second map's first keyframe (id 3) is its origin.
  EXPECT_TRUE(loaded.maps[1].map->keyframe(3)->is_origin());
}

TEST_F(MapFileTest, LoadedMapsReplaceAnEmptyAtlas) {
  auto ids = std::make_shared<MapIdCounters>();
  test::MapBuilder first(scene_, 0, ids), second(scene_, 2, ids);
  for (int i = 0; i < 2; ++i) first.add_keyframe(test::pose_at(0.2 * i));
  for (int i = 0; i < 2; ++i) second.add_keyframe(test::pose_at(-0.2 * i, 0.1));
  const auto path = dir_.path() / "atlas.bin";
  save_map_file(path, context_, {MapToSave{&first.map(), {}}, MapToSave{&second.map(), {}}}, 2, 3);

  Atlas atlas;  // one empty map 0, as System starts
  MapFileContents loaded = load_map_file(path, context_, atlas.id_counters());
  std::vector<std::unique_ptr<Map>> maps;
  for (LoadedMap& m : loaded.maps) maps.push_back(std::move(m.map));
  atlas.replace_maps(std::move(maps), loaded.active_map_id, loaded.next_map_id);
  ASSERT_EQ(atlas.num_maps(), 2u);
  EXPECT_EQ(atlas.active_map_id(), 2u);
  EXPECT_EQ(atlas.active_map().num_keyframes(), 2u);
  EXPECT_EQ(atlas.map_of_keyframe(3), std::optional<std::uint64_t>(2));
  // New maps and keyframes continue after the loaded ids.
  EXPECT_EQ(atlas.create_map().id(), 3u);
  Frame frame = scene_.make_frame(50, test::pose_at(0.1));
  frame.set_pose(test::pose_at(0.1));
  EXPECT_EQ(atlas.active_map().create_keyframe(frame)->id(), 4u);
  // Only into an empty atlas.
  MapFileContents again = load_map_file(path, context_, atlas.id_counters());
  std::vector<std::unique_ptr<Map>> more;
  for (LoadedMap& m : again.maps) more.push_back(std::move(m.map));
  EXPECT_THROW(atlas.replace_maps(std::move(more), 2, 3), Error);
}

// Points the motion stage saw on a person it kept as static track, but stay
// out of the saved map; the keyframes' slots that held them load empty.
TEST_F(MapFileTest, PointsSeenOnPeopleAreNotSaved) {
  const auto points = map().map_points();
  std::set<std::uint64_t> on_people;
  for (std::size_t i = 0; i < points.size(); i += 4) {
    points[i]->mark_on_dynamic_instance();
    on_people.insert(points[i]->id());
  }
  ASSERT_GT(on_people.size(), 100u);
  const auto path = dir_.path() / "map.bin";
  const MapFileStats stats = save_map_file(path, context_, map());
  EXPECT_EQ(stats.points_on_people, on_people.size());
  EXPECT_EQ(stats.map_points, points.size() - on_people.size());

  const MapFileContents loaded = load_map_file(path, context_);
  const Map& copy = *loaded.maps[0].map;
  ASSERT_EQ(copy.num_map_points(), points.size() - on_people.size());
  for (const MapPointPtr& mp : copy.map_points()) EXPECT_EQ(on_people.count(mp->id()), 0u) << mp->id();
  std::size_t slots_before = 0, slots_after = 0;
  for (const KeyFramePtr& kf : map().keyframes()) {
    const KeyFramePtr other = copy.keyframe(kf->id());
    ASSERT_NE(other, nullptr);
    for (std::size_t i = 0; i < kf->size(); ++i) {
      const MapPointPtr& mp = kf->map_point(i);
      if (mp && !on_people.count(mp->id())) {
        ++slots_before;
        ASSERT_NE(other->map_point(i), nullptr);
        EXPECT_EQ(other->map_point(i)->id(), mp->id());
      }
      if (other->map_point(i)) ++slots_after;
    }
  }
  EXPECT_GT(slots_before, 0u);
  EXPECT_EQ(slots_after, slots_before);
  // A point fused into another passes the flag on.
  ASSERT_FALSE(points[1]->on_dynamic_instance());
  points[0]->replace_with(points[1]);
  EXPECT_TRUE(points[1]->on_dynamic_instance());
}

TEST_F(MapFileTest, MissingFileNamesIt) {
  const std::string e = error_of([&] { load_map_file(dir_.path() / "nope.bin", context_); });
  EXPECT_NE(e.find("nope.bin"), std::string::npos) << e;
  EXPECT_NE(e.find("not found"), std::string::npos) << e;
}

TEST_F(MapFileTest, NotAMapFile) {
  const auto path = dir_.write("vocabulary.bin", std::string("STILLVOC") + std::string(100, '\0'));
  const std::string e = error_of([&] { load_map_file(path, context_); });
  EXPECT_NE(e.find("vocabulary.bin: not a stillslam map file"), std::string::npos) << e;
  const auto empty = dir_.write("empty.bin", "");
  EXPECT_NE(error_of([&] { load_map_file(empty, context_); }).find("not a stillslam map file"), std::string::npos);
}

TEST_F(MapFileTest, WrongVersion) {
  const auto path = saved();
  std::string bytes = read_bytes(path);
  const std::uint32_t version = 7;
  std::memcpy(bytes.data() + 8, &version, 4);
  write_bytes(path, bytes);
  const std::string e = error_of([&] { load_map_file(path, context_); });
  EXPECT_NE(e.find("map.bin: map file format version 7, this build reads version 1"), std::string::npos) << e;
}

TEST_F(MapFileTest, VocabularyMismatch) {
  const auto path = saved();
  MapFileContext other = context_;
  other.vocabulary_checksum = 0x99;
  std::string e = error_of([&] { load_map_file(path, other); });
  EXPECT_NE(e.find("map.bin: vocabulary mismatch: the map was saved with vocabulary fingerprint 1234, this run has "
                   "fingerprint 99"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("--vocabulary"), std::string::npos) << e;
  other.vocabulary_checksum = 0;
  e = error_of([&] { load_map_file(path, other); });
  EXPECT_NE(e.find("this run has none"), std::string::npos) << e;
}

TEST_F(MapFileTest, CalibrationMismatch) {
  const auto path = saved();
  CameraCalibration calib = scene_.setup()->camera.calibration();
  calib.fx = 510;
  MapFileContext other = context_;
  other.setup = std::make_shared<CameraSetup>(PinholeCamera(calib, 40.0), scene_.setup()->pyramid,
                                              scene_.setup()->close_depth);
  const std::string e = error_of([&] { load_map_file(path, other); });
  EXPECT_NE(e.find("map.bin: calibration mismatch: the map was made with pinhole 640x480 fx 500"), std::string::npos)
      << e;
  EXPECT_NE(e.find("this run uses pinhole 640x480 fx 510"), std::string::npos) << e;
  // The pyramid is part of it (keypoint octaves and scale distances depend on it).
  other.setup = std::make_shared<CameraSetup>(scene_.setup()->camera, ScalePyramid(4, 1.2f), scene_.setup()->close_depth);
  EXPECT_NE(error_of([&] { load_map_file(path, other); }).find("calibration mismatch"), std::string::npos);
}

TEST_F(MapFileTest, SensorMismatch) {
  const auto path = saved();
  MapFileContext other = context_;
  other.sensor = "stereo";
  const std::string e = error_of([&] { load_map_file(path, other); });
  EXPECT_NE(e.find("map.bin: the map was made with a rgbd sensor, this run is stereo"), std::string::npos) << e;
}

TEST_F(MapFileTest, TruncatedFile) {
  const auto path = saved();
  const std::string bytes = read_bytes(path);
  for (std::size_t keep : {std::size_t{20}, bytes.size() / 2, bytes.size() - 1}) {
    write_bytes(path, bytes.substr(0, keep));
    const std::string e = error_of([&] { load_map_file(path, context_); });
    EXPECT_NE(e.find("map.bin: truncated map file"), std::string::npos) << keep << ": " << e;
  }
}

TEST_F(MapFileTest, EveryCorruptedByteIsDetected) {
  const auto path = saved();
  const std::string bytes = read_bytes(path);
  // Bytes after the version field: sizes, payload (keypoints, poses, ids...), checksum.
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::size_t> at(12, bytes.size() - 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::string bad = bytes;
    const std::size_t i = trial == 0 ? bytes.size() / 2 : at(rng);
    bad[i] = static_cast<char>(bad[i] ^ 0x10);
    write_bytes(path, bad);
    const std::string e = error_of([&] { load_map_file(path, context_); });
    EXPECT_NE(e.find("map.bin: "), std::string::npos) << "byte " << i << ": " << e;
    EXPECT_TRUE(e.find("damaged map file") != std::string::npos || e.find("truncated map file") != std::string::npos)
        << "byte " << i << ": " << e;
  }
  std::string bad = bytes;
  bad[bytes.size() / 2] ^= 0x01;
  write_bytes(path, bad);
  EXPECT_NE(error_of([&] { load_map_file(path, context_); }).find("damaged map file (checksum mismatch)"),
            std::string::npos);
}

TEST_F(MapFileTest, UnwritableFolderIsAnError) {
  const std::string e = error_of([&] { save_map_file(dir_.path() / "no" / "such" / "map.bin", context_, map()); });
  EXPECT_NE(e.find("cannot write map file"), std::string::npos) << e;
}

TEST(VocabularyFingerprint, SameVocabularySameFingerprintOtherVocabularyOther) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<cv::Mat> images;
  for (int im = 0; im < 8; ++im) {
    cv::Mat d(200, 32, CV_8U);
    for (int r = 0; r < d.rows; ++r) {
      for (int c = 0; c < 32; ++c) d.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(byte(rng));
    }
    images.push_back(d);
  }
  VocabularyOptions options;
  options.branching = 4;
  options.levels = 3;
  const Vocabulary a = Vocabulary::train(images, options);
  options.seed = 1;
  const Vocabulary b = Vocabulary::train(images, options);
  test::TempDir dir;
  a.save(dir.path() / "a.voc");
  const Vocabulary a_loaded = Vocabulary::load(dir.path() / "a.voc");
  EXPECT_EQ(vocabulary_fingerprint(a), vocabulary_fingerprint(a_loaded));
  EXPECT_NE(vocabulary_fingerprint(a), vocabulary_fingerprint(b));
  EXPECT_NE(vocabulary_fingerprint(a), 0u);
}

}  // namespace
}  // namespace stillslam
