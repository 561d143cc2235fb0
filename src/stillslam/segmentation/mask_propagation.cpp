#include "stillslam/segmentation/mask_propagation.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/segmentation/mask_grow.h"

namespace stillslam {
namespace {

std::string size_text(cv::Size s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

float valid_depth(const cv::Mat1f& depth, cv::Point2f p, const MaskPropagationOptions& o) {
  if (depth.empty()) return 0.f;
  const int x = cvRound(p.x), y = cvRound(p.y);
  if (x < 0 || y < 0 || x >= depth.cols || y >= depth.rows) return 0.f;
  const float z = depth(y, x);
  return std::isfinite(z) && z >= o.min_depth_m && z <= o.max_depth_m ? z : 0.f;
}

// Median of the valid depths under the mask (0 when none): works for dense
// RGB-D depth and for sparse stereo depths written at keypoint pixels. Every
// 4th pixel (every 2nd row and column) first; all of them when that finds
// fewer than 50 depths (sparse depth).
float median_depth_in(const cv::Mat1b& mask, const cv::Mat1f& depth, const MaskPropagationOptions& o) {
  if (depth.empty()) return 0.f;
  const cv::Rect box = cv::boundingRect(mask);
  std::vector<float> z;
  for (int stride : {2, 1}) {
    z.clear();
    for (int y = box.y; y < box.y + box.height; y += stride) {
      const uchar* m = mask.ptr<uchar>(y);
      const float* d = depth.ptr<float>(y);
      for (int x = box.x; x < box.x + box.width; x += stride) {
        if (m[x] && std::isfinite(d[x]) && d[x] >= o.min_depth_m && d[x] <= o.max_depth_m) z.push_back(d[x]);
      }
    }
    if (z.size() >= 50) break;
  }
  if (z.empty()) return 0.f;
  auto mid = z.begin() + static_cast<std::ptrdiff_t>(z.size() / 2);
  std::nth_element(z.begin(), mid, z.end());
  return *mid;
}

// Depths (metres) from block matching the rectified left and right images
// around the mask (cv::StereoBM, 11 px blocks, disparities 1 to 128 px at
// most: depths from bf / 128 on, and from min_depth_m on): a frame-size
// image, 0 where unknown (outside the mask's bounding box, weak texture, no
// unique match, or the search range cut by the left image border).
cv::Mat1f block_depth(const cv::Mat1b& left, const cv::Mat1b& right, const cv::Mat1b& mask, double bf,
                      const MaskPropagationOptions& o) {
  cv::Mat1f depth(mask.size(), 0.f);
  const cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) return depth;
  const int block = 11;
  const int disparities = std::clamp(16 * static_cast<int>(std::ceil(bf / o.min_depth_m / 16)), 16, 128);
  const int x0 = std::max(0, box.x - disparities);
  const int y0 = std::max(0, box.y - block / 2), y1 = std::min(mask.rows, box.y + box.height + block / 2);
  const cv::Rect roi(x0, y0, box.x + box.width - x0, y1 - y0);
  if (roi.width <= block || roi.height <= block) return depth;
  cv::Mat disparity;  // CV_16S, 16 x the disparity; <= 0: no match
  cv::StereoBM::create(disparities, block)->compute(left(roi), right(roi), disparity);
  for (int y = box.y; y < box.y + box.height; ++y) {
    const short* d = disparity.ptr<short>(y - y0);
    float* z = depth.ptr<float>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (d[x - x0] <= 0) continue;
      const float zz = static_cast<float>(16.0 * bf / d[x - x0]);
      if (zz >= o.min_depth_m && zz <= o.max_depth_m) z[x] = zz;
    }
  }
  return depth;
}

// Good features inside the mask eroded by erode_px (the mask itself when the
// erosion leaves nothing), searched only in the mask's bounding box.
std::vector<cv::Point2f> features_in(const cv::Mat1b& gray, const cv::Mat1b& mask, const MaskPropagationOptions& o) {
  std::vector<cv::Point2f> points;
  const cv::Rect box = cv::boundingRect(mask);
  if (box.width < 3 || box.height < 3) return points;
  cv::Mat1b inner;
  if (o.erode_px > 0) {
    cv::erode(mask(box), inner, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * o.erode_px + 1, 2 * o.erode_px + 1)));
    if (cv::countNonZero(inner) == 0) inner = mask(box);
  } else {
    inner = mask(box);
  }
  cv::goodFeaturesToTrack(gray(box), points, o.points_per_instance, 0.01, o.min_point_distance_px, inner, 3);
  for (cv::Point2f& p : points) p += cv::Point2f(static_cast<float>(box.x), static_cast<float>(box.y));
  return points;
}

// The instance as 0/255 masks: its 8-connected parts of at least min_px
// pixels, then the smaller ones together (the whole instance when min_px is 0).
std::vector<cv::Mat1b> parts_of(const cv::Mat1b& instance, int min_px) {
  cv::Mat1b whole;
  cv::compare(instance, 0, whole, cv::CMP_NE);  // own copy, 0/255
  const cv::Rect box = cv::boundingRect(whole);
  if (min_px <= 0 || box.empty()) return {whole};
  cv::Mat1i labels, stats;
  cv::Mat1d centroids;
  const int n = cv::connectedComponentsWithStats(whole(box), labels, stats, centroids, 8, CV_32S);
  if (n <= 2) return {whole};  // background and one part
  std::vector<cv::Mat1b> parts;
  cv::Mat1b rest(whole.size(), uchar{0});
  for (int label = 1; label < n; ++label) {
    const bool big = stats(label, cv::CC_STAT_AREA) >= min_px;
    cv::Mat1b part(whole.size(), uchar{0});
    cv::Mat1b target = big ? part : rest;
    cv::Mat1b roi = target(box);
    roi.setTo(255, labels == label);
    if (big) parts.push_back(part);
  }
  if (cv::countNonZero(rest) > 0) parts.push_back(rest);
  return parts;
}

bool in_frame(cv::Point2f p, cv::Size s) { return p.x >= 0 && p.y >= 0 && p.x <= s.width - 1 && p.y <= s.height - 1; }

// The mask moved by the 3x3 map H (pixel of the last frame -> pixel of this
// one), warping only the part of the frame the moved mask can cover. A mask
// cut by an image border is taken to go on beyond it (its border pixels
// replicated outwards), so a person walking into the view or brought in by
// the camera motion keeps the part that was outside the last frame.
cv::Mat1b warp_mask(const cv::Mat1b& mask, const cv::Matx33d& H) {
  cv::Mat1b out(mask.size(), uchar{0});
  const cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) return out;
  const auto moved_box = [&](const cv::Rect& r) {
    const std::vector<cv::Point2f> corners{{float(r.x), float(r.y)},
                                           {float(r.x + r.width), float(r.y)},
                                           {float(r.x), float(r.y + r.height)},
                                           {float(r.x + r.width), float(r.y + r.height)}};
    std::vector<cv::Point2f> moved;
    cv::perspectiveTransform(corners, moved, cv::Matx33f(H));
    float shift = 0;
    for (std::size_t i = 0; i < 4; ++i) shift = std::max(shift, static_cast<float>(cv::norm(moved[i] - corners[i])));
    return std::make_pair(cv::boundingRect(moved), shift);
  };
  // Padding beyond a touched border: as far as the map moves the box, at most one frame size.
  const int pad = std::min(std::max(mask.cols, mask.rows), cvCeil(moved_box(box).second) + 2);
  const int left = box.x == 0 ? pad : 0, top = box.y == 0 ? pad : 0;
  const int right = box.x + box.width == mask.cols ? pad : 0, bottom = box.y + box.height == mask.rows ? pad : 0;
  cv::Mat1b src_mask = mask(box);
  if (left + top + right + bottom > 0)
    cv::copyMakeBorder(mask(box), src_mask, top, bottom, left, right, cv::BORDER_REPLICATE);
  const cv::Rect src(box.x - left, box.y - top, src_mask.cols, src_mask.rows);
  cv::Rect dst = moved_box(src).first;
  dst = cv::Rect(dst.x - 1, dst.y - 1, dst.width + 2, dst.height + 2) & cv::Rect(0, 0, mask.cols, mask.rows);
  if (dst.empty()) return out;
  // Local coordinates: p_dst_local = T(-dst) H T(src) p_src_local.
  const cv::Matx33d to_src(1, 0, src.x, 0, 1, src.y, 0, 0, 1);
  const cv::Matx33d from_dst(1, 0, -dst.x, 0, 1, -dst.y, 0, 0, 1);
  const cv::Matx33d L = from_dst * H * to_src;
  cv::Mat1b part = out(dst);
  if (std::abs(L(2, 0)) < 1e-12 && std::abs(L(2, 1)) < 1e-12 && std::abs(L(2, 2) - 1) < 1e-12) {
    const cv::Matx23d A(L(0, 0), L(0, 1), L(0, 2), L(1, 0), L(1, 1), L(1, 2));
    cv::warpAffine(src_mask, part, A, dst.size(), cv::INTER_NEAREST, cv::BORDER_CONSTANT, 0);
  } else {
    cv::warpPerspective(src_mask, part, L, dst.size(), cv::INTER_NEAREST, cv::BORDER_CONSTANT, 0);
  }
  return out;
}

}  // namespace

void MaskPropagationOptions::check() const {
  using namespace option_check;
  in_range("MaskPropagationOptions.mode", mode, 0, 2);
  at_least("MaskPropagationOptions.margin_px", margin_px, 0);
  at_least("MaskPropagationOptions.margin_px_per_frame", margin_px_per_frame, 0);
  at_least("MaskPropagationOptions.max_margin_px", max_margin_px, margin_px);
  in_range("MaskPropagationOptions.points_per_instance", points_per_instance, 1, 10000);
  at_least("MaskPropagationOptions.min_point_distance_px", min_point_distance_px, 1);
  at_least("MaskPropagationOptions.erode_px", erode_px, 0);
  in_range("MaskPropagationOptions.lk_window_px", lk_window_px, 5, 101);
  if (lk_window_px % 2 == 0)
    throw OptionError("MaskPropagationOptions.lk_window_px", option_check::text(lk_window_px), "must be odd");
  in_range("MaskPropagationOptions.lk_levels", lk_levels, 0, 8);
  at_least("MaskPropagationOptions.fb_max_error_px", fb_max_error_px, 0);
  at_least("MaskPropagationOptions.min_tracked_points", min_tracked_points, 1);
  at_least("MaskPropagationOptions.min_points_similarity", min_points_similarity, 2);
  above("MaskPropagationOptions.ransac_threshold_px", ransac_threshold_px, 0);
  above("MaskPropagationOptions.min_depth_m", min_depth_m, 0);
  above("MaskPropagationOptions.max_depth_m", max_depth_m, min_depth_m);
  at_least("MaskPropagationOptions.split_min_px", split_min_px, 0);
}

MaskPropagator::MaskPropagator(const MaskPropagationCamera& camera, MaskPropagationOptions options)
    : camera_(camera), options_(options) {
  options_.check();
  if (!(camera_.fx > 0) || !(camera_.fy > 0))
    throw Error("MaskPropagator: the camera's fx and fy must be > 0 (got " + std::to_string(camera_.fx) + ", " +
                std::to_string(camera_.fy) + ")");
}

int MaskPropagator::margin_px(int age) const {
  const double m = options_.margin_px + options_.margin_px_per_frame * std::max(age, 0);
  return static_cast<int>(std::min<double>(std::lround(m), options_.max_margin_px));
}

void MaskPropagator::reset(SegmentedFrame fresh) {
  if (fresh.gray.empty()) throw Error("MaskPropagator::reset: the segmented frame's gray image is empty");
  const cv::Size size = fresh.gray.size();
  if (!fresh.depth.empty() && fresh.depth.size() != size)
    throw Error("MaskPropagator::reset: depth is " + size_text(fresh.depth.size()) + " but the image is " +
                size_text(size));
  for (const cv::Mat1b& m : fresh.instances) {
    if (m.size() != size)
      throw Error("MaskPropagator::reset: an instance mask is " + size_text(m.size()) + " but the image is " +
                  size_text(size));
  }
  const bool block = options_.stereo_block_depth && options_.mode >= 1 && camera_.bf > 0 && !fresh.right.empty();
  if (block && fresh.right.size() != size)
    throw Error("MaskPropagator::reset: the right image is " + size_text(fresh.right.size()) + " but the image is " +
                size_text(size));
  tracks_.clear();
  std::vector<cv::Mat1b> parts;
  for (const cv::Mat1b& m : fresh.instances) {
    if (cv::countNonZero(m) == 0) continue;
    for (cv::Mat1b& part : parts_of(m, options_.split_min_px)) parts.push_back(std::move(part));
  }
  for (cv::Mat1b& part : parts) {
    Track t;
    t.mask = std::move(part);
    cv::Mat1f dense;  // block matching: the instance's own depths
    if (block) {
      dense = block_depth(fresh.gray, fresh.right, t.mask, camera_.bf, options_);
      t.median_depth = median_depth_in(t.mask, dense, options_);
    }
    if (options_.mode >= 1 && !(t.median_depth > 0)) t.median_depth = median_depth_in(t.mask, fresh.depth, options_);
    if (options_.mode == 2) {
      t.points = features_in(fresh.gray, t.mask, options_);
      t.depth.reserve(t.points.size());
      for (const cv::Point2f& p : t.points) {
        const float z = valid_depth(fresh.depth, p, options_);
        t.depth.push_back(z > 0 || dense.empty() ? z : valid_depth(dense, p, options_));
      }
    }
    tracks_.push_back(std::move(t));
  }
  gray_ = fresh.gray.clone();
  pyramid_.clear();
  frame_id_ = fresh_id_ = fresh.frame_id;
  T_cam_world_ = fresh.T_cam_world;
}

void MaskPropagator::set_last_pose(const Eigen::Isometry3d& T_cam_world) { T_cam_world_ = T_cam_world; }

PropagatedMasks MaskPropagator::propagate(std::uint64_t frame_id, const cv::Mat1b& gray, const cv::Mat1f& depth,
                                          const std::optional<Eigen::Isometry3d>& T_cam_world) {
  if (empty()) throw Error("MaskPropagator::propagate: no fresh segmentation yet (call reset first)");
  if (gray.size() != gray_.size())
    throw Error("MaskPropagator::propagate: the image is " + size_text(gray.size()) + " but the segmented one was " +
                size_text(gray_.size()));
  if (!depth.empty() && depth.size() != gray.size())
    throw Error("MaskPropagator::propagate: depth is " + size_text(depth.size()) + " but the image is " +
                size_text(gray.size()));
  if (frame_id <= frame_id_)
    throw Error("MaskPropagator::propagate: frame " + std::to_string(frame_id) + " is not after frame " +
                std::to_string(frame_id_) + " (the last one propagated to)");
  const cv::Size size = gray.size();
  const MaskPropagationOptions& o = options_;

  // Camera motion from the last frame to this one (points in the last camera -> this camera).
  std::optional<Eigen::Isometry3d> T_rel;
  if (o.mode >= 1 && T_cam_world && T_cam_world_) T_rel = *T_cam_world * T_cam_world_->inverse();
  const Eigen::Matrix3d K = (Eigen::Matrix3d() << camera_.fx, 0, camera_.cx, 0, camera_.fy, camera_.cy, 0, 0, 1).finished();
  const auto move_point = [&](cv::Point2f p, float z, float* z_new) -> std::optional<cv::Point2f> {
    const Eigen::Vector3d X((p.x - camera_.cx) / camera_.fx * z, (p.y - camera_.cy) / camera_.fy * z, z);
    const Eigen::Vector3d Y = *T_rel * X;
    if (Y.z() < o.min_depth_m) return std::nullopt;
    if (z_new) *z_new = static_cast<float>(Y.z());
    return cv::Point2f(static_cast<float>(camera_.fx * Y.x() / Y.z() + camera_.cx),
                       static_cast<float>(camera_.fy * Y.y() / Y.z() + camera_.cy));
  };

  // Pyramids, built once per frame: this frame's is the next call's last one.
  const cv::Size window(o.lk_window_px, o.lk_window_px);
  std::vector<cv::Mat> pyramid;
  const bool want_flow = o.mode == 2 && std::any_of(tracks_.begin(), tracks_.end(), [&](const Track& t) {
                           return static_cast<int>(t.points.size()) >= o.min_tracked_points;
                         });
  if (want_flow) {
    if (pyramid_.empty()) cv::buildOpticalFlowPyramid(gray_, pyramid_, window, o.lk_levels);
    cv::buildOpticalFlowPyramid(gray, pyramid, window, o.lk_levels);
  }
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.03);

  PropagatedMasks out;
  out.age = static_cast<int>(frame_id - fresh_id_);
  out.margin_px = margin_px(out.age);
  for (Track& t : tracks_) {
    PropagatedInstance inst;
    std::optional<cv::Matx33d> H;  // last frame -> this frame
    float median_z_new = t.median_depth;

    // Camera motion: the instance as a fronto-parallel plane at its median depth,
    // H = K (R + t n^T / d) K^-1 with n = (0, 0, 1).
    if (T_rel && t.median_depth > 0) {
      const Eigen::Matrix3d Hc = K * (T_rel->linear() + T_rel->translation() * Eigen::RowVector3d(0, 0, 1) / t.median_depth) * K.inverse();
      cv::Matx33d h;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) h(r, c) = Hc(r, c) / Hc(2, 2);
      H = h;
      inst.motion = InstanceMotion::camera;
      const cv::Rect box = cv::boundingRect(t.mask);
      const cv::Point2f centre(box.x + 0.5f * box.width, box.y + 0.5f * box.height);
      move_point(centre, t.median_depth, &median_z_new);
    }

    // The instance's own motion: LK from the camera-predicted positions.
    std::vector<cv::Point2f> kept;
    std::vector<float> kept_depth;
    if (o.mode == 2 && static_cast<int>(t.points.size()) >= o.min_tracked_points) {
      std::vector<cv::Point2f> next(t.points.size());
      std::vector<float> next_depth(t.points.size(), 0.f);
      int flags = 0;
      if (T_rel) {
        flags = cv::OPTFLOW_USE_INITIAL_FLOW;
        for (std::size_t i = 0; i < t.points.size(); ++i) {
          const float z = t.depth[i] > 0 ? t.depth[i] : t.median_depth;
          std::optional<cv::Point2f> q;
          if (z > 0) q = move_point(t.points[i], z, &next_depth[i]);
          next[i] = q && in_frame(*q, size) ? *q : t.points[i];
        }
      }
      std::vector<uchar> status;
      std::vector<float> error;
      cv::calcOpticalFlowPyrLK(pyramid_, pyramid, t.points, next, status, error, window, o.lk_levels, criteria, flags);
      std::vector<uchar> back_status(status.size(), 1);
      std::vector<cv::Point2f> back;
      if (o.fb_max_error_px > 0) {
        back = t.points;
        cv::calcOpticalFlowPyrLK(pyramid, pyramid_, next, back, back_status, error, window, o.lk_levels, criteria,
                                 cv::OPTFLOW_USE_INITIAL_FLOW);
      }
      std::vector<cv::Point2f> from, to;
      std::vector<float> to_depth;
      for (std::size_t i = 0; i < t.points.size(); ++i) {
        if (!status[i] || !back_status[i] || !in_frame(next[i], size)) continue;
        if (o.fb_max_error_px > 0 && cv::norm(back[i] - t.points[i]) > o.fb_max_error_px) continue;
        from.push_back(t.points[i]);
        to.push_back(next[i]);
        to_depth.push_back(next_depth[i] > 0 ? next_depth[i] : t.depth[i]);
      }
      std::vector<uchar> inlier;
      cv::Matx33d flow_H = cv::Matx33d::eye();
      bool fitted = false;
      if (static_cast<int>(from.size()) >= o.min_points_similarity) {
        const cv::Mat A = cv::estimateAffinePartial2D(from, to, inlier, cv::RANSAC, o.ransac_threshold_px, 200, 0.99, 10);
        if (!A.empty() && cv::countNonZero(inlier) >= o.min_tracked_points) {
          const double scale = std::hypot(A.at<double>(0, 0), A.at<double>(1, 0));
          if (scale > 0.5 && scale < 2.0) {
            flow_H = cv::Matx33d(A.at<double>(0, 0), A.at<double>(0, 1), A.at<double>(0, 2), A.at<double>(1, 0),
                                 A.at<double>(1, 1), A.at<double>(1, 2), 0, 0, 1);
            fitted = true;
          }
        }
      }
      if (!fitted && static_cast<int>(from.size()) >= o.min_tracked_points) {
        std::vector<float> dx, dy;
        for (std::size_t i = 0; i < from.size(); ++i) {
          dx.push_back(to[i].x - from[i].x);
          dy.push_back(to[i].y - from[i].y);
        }
        const auto median = [](std::vector<float> v) {
          auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
          std::nth_element(v.begin(), mid, v.end());
          return *mid;
        };
        const float mx = median(dx), my = median(dy);
        inlier.assign(from.size(), 0);
        for (std::size_t i = 0; i < from.size(); ++i)
          inlier[i] = std::hypot(dx[i] - mx, dy[i] - my) <= 2 * o.ransac_threshold_px;
        if (cv::countNonZero(inlier) >= o.min_tracked_points) {
          flow_H = cv::Matx33d(1, 0, mx, 0, 1, my, 0, 0, 1);
          fitted = true;
        }
      }
      if (fitted) {
        H = flow_H;
        inst.motion = InstanceMotion::flow;
        for (std::size_t i = 0; i < from.size(); ++i) {
          if (!inlier[i]) continue;
          kept.push_back(to[i]);
          kept_depth.push_back(to_depth[i]);
        }
        inst.tracked_points = static_cast<int>(kept.size());
      }
    }

    if (H) t.mask = warp_mask(t.mask, *H);  // a new Mat: masks handed out earlier stay as they were
    // Points for the next step: the inliers still inside the moved mask, or
    // fresh features there when fewer than half of the wanted number remain.
    if (o.mode == 2) {
      std::vector<cv::Point2f> points;
      std::vector<float> point_depth;
      for (std::size_t i = 0; i < kept.size(); ++i) {
        const cv::Point p(cvRound(kept[i].x), cvRound(kept[i].y));
        if (p.x < 0 || p.y < 0 || p.x >= size.width || p.y >= size.height || !t.mask(p)) continue;
        points.push_back(kept[i]);
        const float z = valid_depth(depth, kept[i], o);
        point_depth.push_back(z > 0 ? z : (depth.empty() ? kept_depth[i] : 0.f));
      }
      if (static_cast<int>(points.size()) * 2 < o.points_per_instance) {
        points = features_in(gray, t.mask, o);
        point_depth.clear();
        for (const cv::Point2f& p : points) point_depth.push_back(valid_depth(depth, p, o));
      }
      t.points = std::move(points);
      t.depth = std::move(point_depth);
    }
    if (o.mode >= 1) {
      const float z = median_depth_in(t.mask, depth, o);
      t.median_depth = z > 0 ? z : median_z_new;
    }

    inst.mask = t.mask;
    inst.depth = t.median_depth;
    out.instances.push_back(std::move(inst));
  }

  out.union_mask = cv::Mat1b(size, uchar{0});
  for (const PropagatedInstance& inst : out.instances) cv::bitwise_or(out.union_mask, inst.mask, out.union_mask);
  out.union_mask = grow_mask(out.union_mask, out.margin_px);

  gray_ = gray.clone();
  pyramid_ = std::move(pyramid);
  frame_id_ = frame_id;
  T_cam_world_ = T_cam_world;
  return out;
}

}  // namespace stillslam
