// MaskPropagator on synthetic scenes with known motion: a textured blob moving
// over a textured background (the instance's own motion, found by flow), and a
// static object in front of a wall seen by a translating RGB-D camera (camera
// motion with depth). Holding the old mask (mode 0) must score far lower.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/segmentation/mask_grow.h"
#include "stillslam/segmentation/mask_propagation.h"

namespace stillslam {
namespace {

const cv::Size kSize(320, 240);
const MaskPropagationCamera kCamera{.fx = 250, .fy = 250, .cx = 160, .cy = 120};

// Noise blurred at three scales (fine detail and blobs, as in real images, so
// that the coarse LK pyramid levels see structure too).
cv::Mat1b texture(cv::Size size, int seed) {
  cv::RNG rng(seed);
  cv::Mat1f sum(size, 0.f);
  for (double sigma : {1.5, 4.0, 10.0}) {
    cv::Mat1f noise(size);
    rng.fill(noise, cv::RNG::UNIFORM, 0.f, 1.f);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), sigma);
    cv::normalize(noise, noise, 0, 1, cv::NORM_MINMAX);
    sum += noise;
  }
  cv::Mat1b t;
  cv::normalize(sum, t, 0, 255, cv::NORM_MINMAX, CV_8U);
  return t;
}

double iou(const cv::Mat1b& a, const cv::Mat1b& b) {
  cv::Mat1b i, u;
  cv::bitwise_and(a, b, i);
  cv::bitwise_or(a, b, u);
  const int nu = cv::countNonZero(u);
  return nu == 0 ? 1.0 : static_cast<double>(cv::countNonZero(i)) / nu;
}

// A textured ellipse moving by `velocity` px per frame over a static textured background.
struct MovingBlob {
  cv::Mat1b background = texture(kSize, 1);
  cv::Mat1b object = texture(kSize + cv::Size(200, 200), 2);
  cv::Point start{110, 120};
  cv::Point velocity{6, -2};

  cv::Point centre(int k) const { return start + k * velocity; }
  cv::Mat1b mask(int k) const {
    cv::Mat1b m(kSize, uchar{0});
    cv::ellipse(m, centre(k), cv::Size(35, 55), 0, 0, 360, 255, cv::FILLED);
    return m;
  }
  cv::Mat1b image(int k) const {
    cv::Mat1b img = background.clone();
    const cv::Point shift = k * velocity;
    const cv::Mat1b m = mask(k);
    for (int y = 0; y < kSize.height; ++y)
      for (int x = 0; x < kSize.width; ++x)
        if (m(y, x)) img(y, x) = object(y - shift.y + 100, x - shift.x + 100);  // the texture moves with the blob
    return img;
  }
};

// A static disc (radius 0.35 m) 2 m in front of the camera and a wall at 5 m;
// the camera translates along x by `step` metres per frame.
struct TranslatingCamera {
  cv::Mat1b disc_texture = texture(cv::Size(400, 400), 3);
  cv::Mat1b wall_texture = texture(cv::Size(1000, 800), 4);
  double step = 0.05;

  Eigen::Isometry3d T_cam_world(int k) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(-step * k, 0, 0);
    return T;
  }
  // Image, depth and mask of frame k by ray casting.
  void render(int k, cv::Mat1b& gray, cv::Mat1f& depth, cv::Mat1b& mask) const { render_at(step * k, gray, depth, mask); }
  // The same from a camera at x = cx (a stereo pair's right camera: cx + baseline).
  void render_at(double cx, cv::Mat1b& gray, cv::Mat1f& depth, cv::Mat1b& mask) const {
    gray.create(kSize);
    depth.create(kSize);
    mask = cv::Mat1b(kSize, uchar{0});
    for (int v = 0; v < kSize.height; ++v) {
      for (int u = 0; u < kSize.width; ++u) {
        const double dx = (u - kCamera.cx) / kCamera.fx, dy = (v - kCamera.cy) / kCamera.fy;
        const double X = cx + 2.0 * dx, Y = 2.0 * dy;
        if (X * X + Y * Y <= 0.35 * 0.35) {
          gray(v, u) = disc_texture(cvRound(200 + Y * 100), cvRound(200 + X * 100));
          depth(v, u) = 2.0f;
          mask(v, u) = 255;
        } else {
          const double Xw = cx + 5.0 * dx, Yw = 5.0 * dy;
          gray(v, u) = wall_texture(cvRound(400 + Yw * 100), cvRound(500 + Xw * 100));
          depth(v, u) = 5.0f;
        }
      }
    }
  }
};

MaskPropagationOptions with_mode(int mode) {
  MaskPropagationOptions o;
  o.mode = mode;
  return o;
}

TEST(MaskPropagation, MovingBlobFollowedByFlowFrameToFrame) {
  const MovingBlob scene;
  for (int mode : {2, 0}) {
    MaskPropagator propagator(kCamera, with_mode(mode));
    propagator.reset({.frame_id = 10, .gray = scene.image(0), .depth = {}, .right = {}, .instances = {scene.mask(0)}, .T_cam_world = {}});
    for (int k = 1; k <= 6; ++k) {
      const PropagatedMasks p = propagator.propagate(10 + k, scene.image(k), {}, std::nullopt);
      ASSERT_EQ(p.instances.size(), 1u);
      EXPECT_EQ(p.age, k);
      const double score = iou(p.instances[0].mask, scene.mask(k));
      if (mode == 2) {
        EXPECT_EQ(p.instances[0].motion, InstanceMotion::flow) << "frame " << k;
        EXPECT_GE(p.instances[0].tracked_points, 10) << "frame " << k;
        EXPECT_GT(score, 0.93) << "frame " << k;
      } else {
        EXPECT_EQ(p.instances[0].motion, InstanceMotion::none);
        if (k == 6) {
          EXPECT_LT(score, 0.6);  // 38 px away: holding the mask is far off
        }
      }
    }
  }
}

// Two people under one mask (a union of masks, or merged detections) walking
// apart: tracked as two parts each follows its person; one motion fitted to
// both (splitMinPx 0) follows at most one of them.
TEST(MaskPropagation, PartsOfOneInstanceAreFollowedApart) {
  MovingBlob left, right;
  left.start = {100, 120};
  left.velocity = {0, -8};
  right.start = {220, 120};
  right.velocity = {0, 8};
  right.object = texture(kSize + cv::Size(200, 200), 5);
  const auto both_mask = [&](int k) {
    cv::Mat1b m;
    cv::bitwise_or(left.mask(k), right.mask(k), m);
    return m;
  };
  const auto image = [&](int k) {
    cv::Mat1b img = left.image(k);
    right.image(k).copyTo(img, right.mask(k));
    return img;
  };
  std::vector<double> scores;
  for (int split : {400, 0}) {
    MaskPropagationOptions o;
    o.split_min_px = split;
    MaskPropagator propagator(kCamera, o);
    propagator.reset({.frame_id = 0, .gray = image(0), .depth = {}, .right = {}, .instances = {both_mask(0)}, .T_cam_world = {}});
    PropagatedMasks p;
    for (int k = 1; k <= 6; ++k) p = propagator.propagate(k, image(k), {}, std::nullopt);
    ASSERT_EQ(p.instances.size(), split > 0 ? 2u : 1u);
    cv::Mat1b moved(kSize, uchar{0});
    for (const PropagatedInstance& i : p.instances) cv::bitwise_or(moved, i.mask, moved);
    scores.push_back(iou(moved, both_mask(6)));
  }
  EXPECT_GT(scores[0], 0.9);   // each part followed, 48 px up and down
  EXPECT_LT(scores[1], 0.75);  // one motion for both
}

TEST(MaskPropagation, BlobWalkingInFromTheBorderKeepsItsHiddenPart) {
  MovingBlob scene;
  scene.start = {300, 120};  // the right third is outside the frame
  scene.velocity = {-8, 0};
  MaskPropagator propagator(kCamera, {});
  propagator.reset({.frame_id = 0, .gray = scene.image(0), .depth = {}, .right = {}, .instances = {scene.mask(0)}, .T_cam_world = {}});
  for (int k = 1; k <= 5; ++k) {
    const PropagatedMasks p = propagator.propagate(k, scene.image(k), {}, std::nullopt);
    ASSERT_EQ(p.instances.size(), 1u);
    EXPECT_EQ(p.instances[0].motion, InstanceMotion::flow);
    // The border column replicated outwards: all of the blob (recall 0.7 at frame 5
    // without the extension), and a box where the ellipse closes.
    const cv::Mat1b truth = scene.mask(k);
    const double hit = cv::countNonZero(p.instances[0].mask & truth);
    EXPECT_GT(hit / cv::countNonZero(truth), 0.97) << "frame " << k;
    EXPECT_GT(hit / cv::countNonZero(p.instances[0].mask), 0.65) << "frame " << k;
  }
}

TEST(MaskPropagation, FirstCallMaySpanSeveralFrames) {
  const MovingBlob scene;
  MaskPropagator propagator(kCamera, {});
  propagator.reset({.frame_id = 0, .gray = scene.image(0), .depth = {}, .right = {}, .instances = {scene.mask(0)}, .T_cam_world = {}});
  const PropagatedMasks p = propagator.propagate(4, scene.image(4), {}, std::nullopt);  // 25 px
  ASSERT_EQ(p.instances.size(), 1u);
  EXPECT_EQ(p.instances[0].motion, InstanceMotion::flow);
  EXPECT_GE(p.instances[0].tracked_points, 10);
  EXPECT_EQ(p.age, 4);
  EXPECT_GT(iou(p.instances[0].mask, scene.mask(4)), 0.93);
  const PropagatedMasks q = propagator.propagate(5, scene.image(5), {}, std::nullopt);
  EXPECT_GT(iou(q.instances[0].mask, scene.mask(5)), 0.93);
}

TEST(MaskPropagation, StaticObjectFollowsTheCameraMotionWithDepth) {
  const TranslatingCamera scene;
  cv::Mat1b gray0, mask0;
  cv::Mat1f depth0;
  scene.render(0, gray0, depth0, mask0);
  double last_score[3] = {0, 0, 0};
  for (int mode : {0, 1, 2}) {
    MaskPropagator propagator(kCamera, with_mode(mode));
    propagator.reset({.frame_id = 0, .gray = gray0, .depth = depth0, .right = {}, .instances = {mask0}, .T_cam_world = scene.T_cam_world(0)});
    for (int k = 1; k <= 5; ++k) {  // 6.25 px a frame
      cv::Mat1b gray, mask;
      cv::Mat1f depth;
      scene.render(k, gray, depth, mask);
      const PropagatedMasks p = propagator.propagate(k, gray, depth, scene.T_cam_world(k));
      ASSERT_EQ(p.instances.size(), 1u);
      last_score[mode] = iou(p.instances[0].mask, mask);
      if (mode == 1) {
        EXPECT_EQ(p.instances[0].motion, InstanceMotion::camera);
      }
      if (mode == 2) {
        EXPECT_EQ(p.instances[0].motion, InstanceMotion::flow);
      }
    }
  }
  EXPECT_LT(last_score[0], 0.6);   // 31 px off
  EXPECT_GT(last_score[1], 0.95);  // the plane at the median depth is exact here
  EXPECT_GT(last_score[2], 0.93);
}

TEST(MaskPropagation, CameraMotionWithoutDepthOrPoseIsNotUsed) {
  const TranslatingCamera scene;
  cv::Mat1b gray0, mask0, gray1, mask1;
  cv::Mat1f depth0, depth1;
  scene.render(0, gray0, depth0, mask0);
  scene.render(1, gray1, depth1, mask1);
  MaskPropagator propagator(kCamera, with_mode(1));
  propagator.reset({.frame_id = 0, .gray = gray0, .depth = {}, .right = {}, .instances = {mask0}, .T_cam_world = scene.T_cam_world(0)});
  EXPECT_EQ(propagator.propagate(1, gray1, depth1, scene.T_cam_world(1)).instances[0].motion, InstanceMotion::none);
  // Sparse depth (stereo keypoints): a few pixels with depth are enough.
  cv::Mat1f sparse(kSize, 0.f);
  for (int y = 100; y < 140; y += 10) sparse(y, 160) = 2.0f;
  propagator.reset({.frame_id = 0, .gray = gray0, .depth = sparse, .right = {}, .instances = {mask0}, .T_cam_world = scene.T_cam_world(0)});
  const PropagatedMasks p = propagator.propagate(1, gray1, {}, scene.T_cam_world(1));
  EXPECT_EQ(p.instances[0].motion, InstanceMotion::camera);
  EXPECT_GT(iou(p.instances[0].mask, mask1), 0.95);
  // No pose for this frame: nothing to move by.
  propagator.reset({.frame_id = 0, .gray = gray0, .depth = depth0, .right = {}, .instances = {mask0}, .T_cam_world = scene.T_cam_world(0)});
  EXPECT_EQ(propagator.propagate(1, gray1, depth1, std::nullopt).instances[0].motion, InstanceMotion::none);
}

// Stereo: the sparse keypoint depths under the disc are the wall's (the
// disc's own keypoints were removed), as when a carried mask removed a
// person's keypoints at the segmented frame. With stereoBlockDepth the
// instance's depth comes from block matching the pair inside its mask.
TEST(MaskPropagation, StereoBlockDepthGivesTheInstanceItsOwnDepth) {
  const TranslatingCamera scene;
  const double baseline = 0.1;
  MaskPropagationCamera camera = kCamera;
  camera.bf = camera.fx * baseline;  // disc 12.5 px of disparity, wall 5 px
  cv::Mat1b gray0, mask0, right0, unused_mask, gray1, mask1;
  cv::Mat1f depth0, unused_depth, depth1;
  scene.render(0, gray0, depth0, mask0);
  scene.render_at(baseline, right0, unused_depth, unused_mask);
  scene.render(1, gray1, depth1, mask1);
  cv::Mat1f sparse(kSize, 0.f);  // wall depths at a few pixels inside the disc
  for (int y = 100; y < 140; y += 10) sparse(y, 160) = 5.0f;
  double depth[2] = {0, 0}, score[2] = {0, 0};
  for (bool block : {false, true}) {
    MaskPropagationOptions o = with_mode(1);
    o.stereo_block_depth = block;
    MaskPropagator propagator(camera, o);
    propagator.reset({.frame_id = 0, .gray = gray0, .depth = sparse, .right = right0, .instances = {mask0},
                      .T_cam_world = scene.T_cam_world(0)});
    const PropagatedMasks p = propagator.propagate(1, gray1, {}, scene.T_cam_world(1));
    ASSERT_EQ(p.instances.size(), 1u);
    depth[block] = p.instances[0].depth;
    score[block] = iou(p.instances[0].mask, mask1);
  }
  EXPECT_NEAR(depth[0], 5.0, 1e-3);  // the sparse depths' median
  EXPECT_NEAR(depth[1], 2.0, 0.1);   // the disc's own
  EXPECT_GT(score[1], 0.95);         // moved 12.5 px as the disc did, not 5 px as the wall
  EXPECT_LT(score[0], score[1] - 0.05);
  // Without a right image, or for a camera without bf, the option does nothing.
  MaskPropagationOptions o = with_mode(1);
  o.stereo_block_depth = true;
  MaskPropagator no_bf(kCamera, o);
  no_bf.reset({.frame_id = 0, .gray = gray0, .depth = sparse, .right = right0, .instances = {mask0},
               .T_cam_world = scene.T_cam_world(0)});
  EXPECT_NEAR(no_bf.propagate(1, gray1, {}, scene.T_cam_world(1)).instances[0].depth, 5.0, 1e-3);
  MaskPropagator no_right(camera, o);
  no_right.reset({.frame_id = 0, .gray = gray0, .depth = sparse, .right = {}, .instances = {mask0}, .T_cam_world = scene.T_cam_world(0)});
  EXPECT_NEAR(no_right.propagate(1, gray1, {}, scene.T_cam_world(1)).instances[0].depth, 5.0, 1e-3);
  // A right image of another size is an error.
  MaskPropagator bad(camera, o);
  EXPECT_THROW(bad.reset({.frame_id = 0, .gray = gray0, .depth = sparse, .right = cv::Mat1b(10, 10, uchar{0}),
                          .instances = {mask0}, .T_cam_world = scene.T_cam_world(0)}),
               Error);
}

TEST(MaskPropagation, SameInputsGiveTheSameMasks) {  // --deterministic runs rely on it
  const TranslatingCamera scene;
  std::vector<cv::Mat1b> first;
  for (int run = 0; run < 2; ++run) {
    cv::Mat1b gray, mask;
    cv::Mat1f depth;
    scene.render(0, gray, depth, mask);
    MaskPropagator propagator(kCamera, {});
    propagator.reset({.frame_id = 0, .gray = gray, .depth = depth, .right = {}, .instances = {mask}, .T_cam_world = scene.T_cam_world(0)});
    for (int k = 1; k <= 3; ++k) {
      scene.render(k, gray, depth, mask);
      const PropagatedMasks p = propagator.propagate(k, gray, depth, scene.T_cam_world(k));
      if (run == 0) {
        first.push_back(p.union_mask);
      } else {
        EXPECT_EQ(cv::countNonZero(p.union_mask != first[k - 1]), 0) << "frame " << k;
      }
    }
  }
}

TEST(MaskPropagation, MarginGrowsWithAge) {
  const MovingBlob scene;
  MaskPropagationOptions o;
  o.margin_px = 2;
  o.margin_px_per_frame = 1.5;
  o.max_margin_px = 10;
  MaskPropagator propagator(kCamera, o);
  EXPECT_EQ(propagator.margin_px(0), 2);
  EXPECT_EQ(propagator.margin_px(2), 5);
  EXPECT_EQ(propagator.margin_px(10), 10);  // capped
  propagator.reset({.frame_id = 0, .gray = scene.image(0), .depth = {}, .right = {}, .instances = {scene.mask(0)}, .T_cam_world = {}});
  int previous_margin = 0;
  for (int k = 1; k <= 5; ++k) {
    const PropagatedMasks p = propagator.propagate(k, scene.image(k), {}, std::nullopt);
    EXPECT_EQ(p.margin_px, std::lround(2 + 1.5 * k));
    EXPECT_GT(p.margin_px, previous_margin);
    previous_margin = p.margin_px;
    EXPECT_EQ(cv::countNonZero(p.union_mask != dynamic_mask({p.instances[0].mask}, kSize, p.margin_px)), 0);
    EXPECT_GT(cv::countNonZero(p.union_mask), cv::countNonZero(p.instances[0].mask));
  }
}

// OpenCV's dilation with a disc kernel: every pixel (dx, dy) with dx^2 + dy^2 <= r^2 of a set pixel.
cv::Mat1b disc_dilation(const cv::Mat1b& mask, int r) {
  if (r <= 0) return mask.clone();
  cv::Mat1b disc(2 * r + 1, 2 * r + 1, uchar{0});
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      if (dx * dx + dy * dy <= r * r) disc(dy + r, dx + r) = 1;
  cv::Mat1b out;
  cv::dilate(mask, out, disc);
  return out;
}

TEST(MaskPropagation, GrowMaskIsTheDiscDilation) {
  cv::Mat1b m(kSize, uchar{0});
  cv::ellipse(m, cv::Point(40, 60), cv::Size(20, 30), 15, 0, 360, 255, cv::FILLED);
  m(cv::Rect(300, 0, 20, 10)).setTo(255);  // at the border
  for (int r : {0, 1, 4, 13}) {
    EXPECT_EQ(cv::countNonZero(grow_mask(m, r) != disc_dilation(m, r)), 0) << "radius " << r;
    EXPECT_EQ(cv::countNonZero(dynamic_mask({m}, kSize, r) != disc_dilation(m, r)), 0) << "radius " << r;
  }
  EXPECT_EQ(cv::countNonZero(grow_mask(cv::Mat1b(kSize, uchar{0}), 5)), 0);
  // Rows with several runs, lone pixels, holes, all four borders, every radius the propagation uses.
  cv::Mat1b many(kSize, uchar{0});
  cv::RNG rng(7);
  for (int i = 0; i < 40; ++i) many(rng.uniform(0, kSize.height), rng.uniform(0, kSize.width)) = 255;
  cv::rectangle(many, cv::Rect(100, 50, 60, 40), 255, cv::FILLED);
  cv::rectangle(many, cv::Rect(115, 60, 20, 15), 0, cv::FILLED);  // a hole
  many(cv::Rect(0, kSize.height - 3, 5, 3)).setTo(255);
  many(cv::Rect(kSize.width - 2, 20, 2, 30)).setTo(255);
  for (int r = 1; r <= 30; ++r) {
    EXPECT_EQ(cv::countNonZero(grow_mask(many, r) != disc_dilation(many, r)), 0) << "radius " << r;
  }
}

TEST(MaskPropagation, EmptyAndFlatInstances) {
  const MovingBlob scene;
  MaskPropagator propagator(kCamera, {});
  EXPECT_TRUE(propagator.empty());
  propagator.reset({.frame_id = 0, .gray = scene.image(0), .depth = {}, .right = {}, .instances = {cv::Mat1b(kSize, uchar{0})}, .T_cam_world = {}});
  EXPECT_FALSE(propagator.empty());
  PropagatedMasks p = propagator.propagate(1, scene.image(1), {}, std::nullopt);
  EXPECT_TRUE(p.instances.empty());
  ASSERT_EQ(p.union_mask.size(), kSize);
  EXPECT_EQ(cv::countNonZero(p.union_mask), 0);
  // A textureless instance has no points to track: it is held where it was.
  cv::Mat1b flat(kSize, uchar{128});
  propagator.reset({.frame_id = 0, .gray = flat, .depth = {}, .right = {}, .instances = {scene.mask(0)}, .T_cam_world = {}});
  p = propagator.propagate(1, flat, {}, std::nullopt);
  ASSERT_EQ(p.instances.size(), 1u);
  EXPECT_EQ(p.instances[0].motion, InstanceMotion::none);
  EXPECT_EQ(cv::countNonZero(p.instances[0].mask != scene.mask(0)), 0);
}

TEST(MaskPropagation, BadInputsAreClearErrors) {
  const MovingBlob scene;
  MaskPropagator propagator(kCamera, {});
  EXPECT_THROW(propagator.propagate(1, scene.image(1), {}, std::nullopt), Error);  // no reset yet
  EXPECT_THROW(propagator.reset({.frame_id = 0, .gray = {}, .depth = {}, .right = {}, .instances = {}, .T_cam_world = {}}), Error);
  EXPECT_THROW(propagator.reset({.frame_id = 0, .gray = scene.image(0), .depth = {}, .right = {}, .instances = {cv::Mat1b(10, 10, uchar{0})}, .T_cam_world = {}}), Error);
  EXPECT_THROW(propagator.reset({.frame_id = 0, .gray = scene.image(0), .depth = cv::Mat1f(5, 5, 1.f), .right = {}, .instances = {}, .T_cam_world = {}}), Error);
  propagator.reset({.frame_id = 5, .gray = scene.image(0), .depth = {}, .right = {}, .instances = {scene.mask(0)}, .T_cam_world = {}});
  EXPECT_THROW(propagator.propagate(5, scene.image(1), {}, std::nullopt), Error);  // not after the last frame
  EXPECT_THROW(propagator.propagate(6, cv::Mat1b(10, 10, uchar{0}), {}, std::nullopt), Error);
  EXPECT_THROW(propagator.propagate(6, scene.image(1), cv::Mat1f(10, 10, 1.f), std::nullopt), Error);
  EXPECT_NO_THROW(propagator.propagate(6, scene.image(1), {}, std::nullopt));
  EXPECT_THROW(MaskPropagator({.fx = 0, .fy = 250, .cx = 0, .cy = 0}, {}), Error);
  MaskPropagationOptions bad;
  bad.lk_window_px = 20;
  try {
    MaskPropagator p(kCamera, bad);
    FAIL() << "even LK window accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "MaskPropagationOptions.lk_window_px");
  }
  bad = {};
  bad.mode = 3;
  EXPECT_THROW(bad.check(), OptionError);
}

}  // namespace
}  // namespace stillslam
