// Relocalization verification against false place matches: the same poster
// (same points layout, same descriptors) hangs in two places, A and B, each
// with its own surroundings. A frame at B matches A's poster with hundreds of
// geometrically consistent inliers -- a confident, wrong pose 20 m off. The
// verification (the candidate's local map must be found where the pose
// predicts it) rejects it; the true place, when mapped, is accepted, also
// with half of the image without keypoints (a masked person).
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "stillslam/map/map.h"
#include "stillslam/place/vocabulary.h"
#include "stillslam/tracking/relocalizer.h"

namespace stillslam {
namespace {

constexpr int kDirectIndexLevel = 2;
constexpr double kPlaceB = 20.0;  // x of place B; place A is at x = 0 (out of sight)

using Descriptor = std::array<std::uint8_t, 32>;

// Points with fixed descriptors; frames project them exactly (level 0, depth).
class RepeatedPosterScene {
 public:
  RepeatedPosterScene() {
    const CameraCalibration calib = pinhole_calibration(500, 500, 320, 240, 640, 480);
    setup_ = std::make_shared<CameraSetup>(PinholeCamera(calib, 40.0), ScalePyramid(OrbOptions{}), 40.0 / 500 * 40);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> poster_x(-0.6, 0.6), poster_y(-0.45, 0.45);
    std::vector<Eigen::Vector3d> poster;
    std::vector<Descriptor> poster_desc;
    for (int i = 0; i < 200; ++i) {
      poster.emplace_back(poster_x(rng), poster_y(rng), 3.0);
      poster_desc.push_back(random_descriptor(rng));
    }
    std::uniform_real_distribution<double> bx(-3.0, 3.0), by(-2.2, 2.2), bz(3.5, 6.0);
    for (double place : {0.0, kPlaceB}) {
      for (std::size_t i = 0; i < poster.size(); ++i) add(poster[i] + Eigen::Vector3d(place, 0, 0), poster_desc[i]);
      for (int i = 0; i < 800; ++i) add(Eigen::Vector3d(place + bx(rng), by(rng), bz(rng)), random_descriptor(rng));
    }
  }

  // Frame seeing the scene from T_cam_world (pose not set). Keypoints with
  // x < hide_left_of are left out (a masked region).
  Frame make_frame(std::uint64_t id, const Eigen::Isometry3d& T_cam_world, std::vector<std::size_t>* ids = nullptr,
                   double hide_left_of = -1) const {
    std::vector<cv::KeyPoint> kps;
    std::vector<float> u_right, depth;
    cv::Mat desc(0, 32, CV_8U);
    if (ids) ids->clear();
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Eigen::Vector3d p = T_cam_world * points_[i];
      if (p.z() <= 0.1) continue;
      const Eigen::Vector2d uv = setup_->camera.project(p);
      if (!setup_->camera.in_image(uv) || uv.x() < hide_left_of) continue;
      kps.emplace_back(static_cast<float>(uv.x()), static_cast<float>(uv.y()), 31.f, 0.f, 1.f, 0);
      depth.push_back(static_cast<float>(p.z()));
      u_right.push_back(static_cast<float>(uv.x() - setup_->camera.bf() / p.z()));
      desc.push_back(cv::Mat(1, 32, CV_8U, const_cast<std::uint8_t*>(descriptors_[i].data())).clone());
      if (ids) ids->push_back(i);
    }
    return Frame(id, 0.1 * static_cast<double>(id), setup_, kps, kps, desc, u_right, depth);
  }

  const Eigen::Vector3d& point(std::size_t i) const { return points_[i]; }

 private:
  static Descriptor random_descriptor(std::mt19937& rng) {
    std::uniform_int_distribution<int> byte(0, 255);
    Descriptor d{};
    for (auto& b : d) b = static_cast<std::uint8_t>(byte(rng));
    return d;
  }
  void add(const Eigen::Vector3d& p, const Descriptor& d) {
    points_.push_back(p);
    descriptors_.push_back(d);
  }

  std::shared_ptr<CameraSetup> setup_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<Descriptor> descriptors_;
};

// Camera at (x, y, 0) looking along +z, turned by yaw about the vertical.
Eigen::Isometry3d camera_at(double x, double y = 0, double yaw_deg = 0) {
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  T_world_cam.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T_world_cam.translation() = Eigen::Vector3d(x, y, 0);
  return T_world_cam.inverse();
}

double position_error(const Eigen::Isometry3d& T_cam_world, const Eigen::Isometry3d& truth) {
  return (T_cam_world.inverse().translation() - truth.inverse().translation()).norm();
}

class RelocalizationVerificationTest : public ::testing::Test {
 protected:
  RelocalizationVerificationTest() {
    std::vector<cv::Mat> training;
    for (double x : {-0.3, 0.3, kPlaceB - 0.3, kPlaceB + 0.3}) training.push_back(scene_.make_frame(900, camera_at(x)).descriptors());
    VocabularyOptions vo;
    vo.branching = 8;
    vo.levels = 3;
    vo.seed = 3;
    vocabulary_ = Vocabulary::train(training, vo);
  }

  // Keyframes along x around `place`, one map point per scene point seen.
  std::vector<RelocalizationCandidate> map_place(double place) {
    std::vector<RelocalizationCandidate> out;
    for (double dx : {-0.3, 0.0, 0.3}) {
      const Eigen::Isometry3d T = camera_at(place + dx, 0.0, dx * 10);
      std::vector<std::size_t> ids;
      Frame frame = scene_.make_frame(next_id_++, T, &ids);
      frame.set_pose(T);
      KeyFramePtr kf = map_.create_keyframe(frame);
      for (std::size_t i = 0; i < ids.size(); ++i) {
        MapPointPtr& mp = points_[ids[i]];
        if (!mp) mp = map_.create_map_point(scene_.point(ids[i]), kf.get());
        mp->add_observation(kf.get(), i);
        kf->set_map_point(i, mp);
      }
      for (const auto& mp : kf->map_points()) {
        if (!mp) continue;
        mp->compute_distinctive_descriptor();
        mp->update_normal_and_depth(frame.setup().pyramid);
      }
      kf->update_connections();
      out.push_back({kf, features_of(frame)});
    }
    for (auto& c : out) c.keyframe->update_connections();
    return out;
  }

  FeatureVector features_of(const Frame& f) const {
    BowVector bow;
    FeatureVector fv;
    vocabulary_.transform(f.descriptors(), bow, fv, kDirectIndexLevel);
    return fv;
  }

  static RelocalizerOptions unverified() {
    RelocalizerOptions o;
    o.min_found_ratio = 0;
    o.min_supported_cells = 0;
    return o;
  }

  RepeatedPosterScene scene_;
  Vocabulary vocabulary_;
  Map map_;
  std::map<std::size_t, MapPointPtr> points_;
  std::uint64_t next_id_ = 0;
};

TEST_F(RelocalizationVerificationTest, WithoutVerificationTheRepeatedPosterGivesAConfidentWrongPose) {
  const std::vector<RelocalizationCandidate> candidates = map_place(0.0);  // only A is mapped
  const Eigen::Isometry3d truth = camera_at(kPlaceB + 0.1, 0.05, 3.0);
  Frame frame = scene_.make_frame(100, truth);
  const RelocalizationResult r = Relocalizer(unverified()).relocalize(frame, features_of(frame), candidates);
  ASSERT_TRUE(r.success);  // the failure mode the verification exists for
  EXPECT_GE(r.inliers, 150);
  EXPECT_GT(position_error(r.T_cam_world, truth), 19.0);
}

TEST_F(RelocalizationVerificationTest, UnmappedPlaceWithTheSamePosterIsRejected) {
  const std::vector<RelocalizationCandidate> candidates = map_place(0.0);
  const Eigen::Isometry3d truth = camera_at(kPlaceB + 0.1, 0.05, 3.0);
  Frame frame = scene_.make_frame(101, truth);
  const RelocalizationResult r = Relocalizer().relocalize(frame, features_of(frame), candidates);
  EXPECT_FALSE(r.success);
  EXPECT_FALSE(frame.has_pose());
  EXPECT_EQ(frame.num_matches(), 0);
  EXPECT_EQ(r.rejected_by_verification, 3);  // every keyframe of A had the inliers, none the support
  EXPECT_GE(r.inliers, 150);
  // Inliers only on the poster: 4 of 16 judged cells.
  EXPECT_GE(r.checked_points, 300);
  EXPECT_GE(r.judged_cells, 12);
  EXPECT_LE(r.supported_cells, 5);
}

TEST_F(RelocalizationVerificationTest, WrongCandidateFirstThenTheTruePlace) {
  std::vector<RelocalizationCandidate> candidates = map_place(0.0);
  const std::vector<RelocalizationCandidate> at_b = map_place(kPlaceB);
  candidates.insert(candidates.end(), at_b.begin(), at_b.end());  // A's keyframes come first
  const Eigen::Isometry3d truth = camera_at(kPlaceB + 0.1, 0.05, 3.0);

  Frame unchecked = scene_.make_frame(102, truth);
  const RelocalizationResult wrong = Relocalizer(unverified()).relocalize(unchecked, features_of(unchecked), candidates);
  ASSERT_TRUE(wrong.success);
  EXPECT_GT(position_error(wrong.T_cam_world, truth), 19.0);

  Frame frame = scene_.make_frame(103, truth);
  const RelocalizationResult r = Relocalizer().relocalize(frame, features_of(frame), candidates);
  ASSERT_TRUE(r.success);
  EXPECT_EQ(r.candidates_tried, 4);  // the three of A rejected, the first of B accepted
  EXPECT_EQ(r.rejected_by_verification, 3);
  EXPECT_EQ(r.keyframe, at_b.front().keyframe);
  EXPECT_LT(position_error(r.T_cam_world, truth), 0.01);
  EXPECT_GE(r.found_points, 0.9 * r.checked_points);
  EXPECT_GE(r.judged_cells, 12);
  EXPECT_EQ(r.supported_cells, r.judged_cells);
  EXPECT_EQ(frame.reference_keyframe(), at_b.front().keyframe);
}

TEST_F(RelocalizationVerificationTest, TruePlaceWithHalfTheImageMaskedIsAccepted) {
  const std::vector<RelocalizationCandidate> candidates = map_place(0.0);
  const Eigen::Isometry3d truth = camera_at(0.15, -0.05, -4.0);
  Frame frame = scene_.make_frame(104, truth, nullptr, 320.0);  // no keypoints on the left half
  const RelocalizationResult r = Relocalizer().relocalize(frame, features_of(frame), candidates);
  ASSERT_TRUE(r.success);
  EXPECT_LT(position_error(r.T_cam_world, truth), 0.01);
  // The left half's predictions are not checkable: they count neither way.
  EXPECT_GE(r.found_points, 0.9 * r.checked_points);
  EXPECT_GE(r.checked_points, 200);
  EXPECT_LE(r.judged_cells, 8);  // the right half only
  EXPECT_EQ(r.supported_cells, r.judged_cells);
}

}  // namespace
}  // namespace stillslam
