#include "stillslam/segmentation/yolo_segmenter.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <filesystem>

#include "stillslam/core/error.h"
#include "stillslam/segmentation/nms.h"
#include "stillslam/segmentation/coco_classes.h"
#include "stillslam/segmentation/onnx_input_shape.h"

namespace stillslam {
namespace {

constexpr int kMaskCoefficients = 32;
constexpr int kProtoStride = 4;  // prototype masks are at 1/4 of the input resolution

std::string shape_string(const cv::Mat& m) {
  std::string s;
  for (int i = 0; i < m.dims; ++i) s += (i ? "x" : "") + std::to_string(m.size[i]);
  return s;
}

}  // namespace

YoloSegmenter::YoloSegmenter(const SegmentationOptions& options) : options_(options) {
  options_.check();
  const std::vector<int> wanted = resolve_class_ids(options_.classes);  // unknown names fail here, early
  const std::string& path = options_.model_path;
  if (path.empty()) throw Error("no segmentation model given: set Segmentation.model or --model to a YOLO-seg .onnx file");
  if (!std::filesystem::is_regular_file(path))
    throw Error("segmentation model '" + path + "' does not exist: check Segmentation.model / --model");

  const auto shape = onnx_input_shape(path);
  if (shape.size() != 4 || shape[1] != 3 || shape[2] <= 0 || shape[3] <= 0 || shape[2] % 32 || shape[3] % 32)
    throw Error("segmentation model '" + path +
                "' needs a fixed 1x3xHxW image input (H, W multiples of 32); export it with a fixed imgsz");
  input_size_ = cv::Size(static_cast<int>(shape[3]), static_cast<int>(shape[2]));

  try {
    net_ = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& e) {
    throw Error("OpenCV DNN cannot load segmentation model '" + path + "': " + e.what() +
                "\nUse an fp32 YOLOv8/YOLO11-seg export converted for OpenCV 4.6 (see models/README.md)");
  }
  if (net_.empty()) throw Error("OpenCV DNN loaded an empty network from '" + path + "'");
  net_.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net_.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  output_names_ = net_.getUnconnectedOutLayersNames();

  // A dummy forward validates the output layout (and sets num_classes_) now rather
  // than on the first frame; it also takes OpenCV's one-time allocations out of frame 0.
  forward(cv::Mat(input_size_, CV_8UC3, cv::Scalar::all(114)));

  mask_class_.assign(static_cast<std::size_t>(num_classes_), !options_.masks_for_classes_only);
  for (int id : wanted)
    if (id < num_classes_) mask_class_[static_cast<std::size_t>(id)] = true;
}

YoloSegmenter::Outputs YoloSegmenter::forward(const cv::Mat& bgr_input) {
  const cv::Mat blob = cv::dnn::blobFromImage(bgr_input, 1.0 / 255.0, input_size_, cv::Scalar(), /*swapRB=*/true,
                                              /*crop=*/false, CV_32F);
  std::vector<cv::Mat> outs;
  try {
    net_.setInput(blob);
    net_.forward(outs, output_names_);
  } catch (const cv::Exception& e) {
    throw Error("segmentation model '" + options_.model_path + "' failed to run on a " +
                std::to_string(input_size_.width) + "x" + std::to_string(input_size_.height) + " input: " + e.what());
  }
  return check_outputs(outs);
}

YoloSegmenter::Outputs YoloSegmenter::check_outputs(std::vector<cv::Mat>& outs) {
  const std::string expected = "expected YOLO-seg outputs (1, 4+classes+32, N) and (1, 32, " +
                               std::to_string(input_size_.height / kProtoStride) + ", " +
                               std::to_string(input_size_.width / kProtoStride) + ")";
  std::string got;
  for (const auto& m : outs) got += (got.empty() ? "" : ", ") + shape_string(m);
  const auto fail = [&]() {
    return Error("segmentation model '" + options_.model_path + "' is not a YOLOv8/YOLO11-seg model: " + expected +
                 ", got (" + got + ")");
  };
  if (outs.size() != 2) throw fail();
  const auto pred_it = std::find_if(outs.begin(), outs.end(), [](const cv::Mat& m) { return m.dims == 3; });
  const auto proto_it = std::find_if(outs.begin(), outs.end(), [](const cv::Mat& m) { return m.dims == 4; });
  if (pred_it == outs.end() || proto_it == outs.end()) throw fail();
  const cv::Mat& pred = *pred_it;
  const cv::Mat& proto = *proto_it;
  const int rows = pred.size[1];
  const int anchors = pred.size[2];
  const cv::Size proto_size(proto.size[3], proto.size[2]);
  if (pred.size[0] != 1 || pred.type() != CV_32F || rows <= 4 + kMaskCoefficients || anchors <= 0 ||
      proto.size[0] != 1 || proto.size[1] != kMaskCoefficients || proto.type() != CV_32F ||
      proto_size.width * kProtoStride != input_size_.width || proto_size.height * kProtoStride != input_size_.height)
    throw fail();
  const int classes = rows - 4 - kMaskCoefficients;
  if (num_classes_ != 0 && classes != num_classes_) throw fail();
  num_classes_ = classes;  // first set by the constructor's dummy forward

  Outputs o;
  cv::transpose(pred.reshape(1, rows), o.predictions);  // N x rows: one anchor per row
  o.protos = proto.reshape(1, kMaskCoefficients);       // 32 x (H/4 * W/4), shares the data
  o.proto_size = proto_size;
  return o;
}

std::vector<Detection> YoloSegmenter::segment(const cv::Mat& image) {
  if (image.empty()) throw Error("segment(): the image is empty (unreadable file?)");
  cv::Mat bgr;
  switch (image.type()) {
    case CV_8UC3: bgr = image; break;
    case CV_8UC1: cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR); break;
    case CV_8UC4: cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR); break;
    default:
      throw Error("segment(): image type " + cv::typeToString(image.type()) +
                  " is not supported; pass an 8-bit BGR (8UC3) or gray (8UC1) image");
  }
  const Letterbox lb = Letterbox::fit(bgr.size(), input_size_);
  const Outputs outs = forward(lb.apply(bgr));

  // Candidates: best class per anchor above the score threshold.
  std::vector<cv::Rect2d> boxes;
  std::vector<float> scores;
  std::vector<int> class_ids;
  std::vector<int> rows;
  for (int r = 0; r < outs.predictions.rows; ++r) {
    const float* p = outs.predictions.ptr<float>(r);
    const float* best = std::max_element(p + 4, p + 4 + num_classes_);
    if (*best < options_.score_threshold) continue;
    boxes.emplace_back(p[0] - 0.5 * p[2], p[1] - 0.5 * p[3], p[2], p[3]);
    scores.push_back(*best);
    class_ids.push_back(static_cast<int>(best - (p + 4)));
    rows.push_back(r);
  }
  const std::vector<int> keep =
      options_.agnostic_nms
          ? agnostic_nms(boxes, scores, options_.score_threshold, options_.nms_iou_threshold)
          : class_aware_nms(boxes, scores, class_ids, options_.score_threshold, options_.nms_iou_threshold);

  std::vector<Detection> detections;
  detections.reserve(keep.size());
  const cv::Point2f frame_max(static_cast<float>(bgr.cols), static_cast<float>(bgr.rows));
  for (int k : keep) {
    const auto i = static_cast<std::size_t>(k);
    const cv::Rect2d& b = boxes[i];
    cv::Point2f tl = lb.to_frame(cv::Point2f(static_cast<float>(b.x), static_cast<float>(b.y)));
    cv::Point2f br = lb.to_frame(cv::Point2f(static_cast<float>(b.x + b.width), static_cast<float>(b.y + b.height)));
    tl = cv::Point2f(std::clamp(tl.x, 0.0f, frame_max.x), std::clamp(tl.y, 0.0f, frame_max.y));
    br = cv::Point2f(std::clamp(br.x, 0.0f, frame_max.x), std::clamp(br.y, 0.0f, frame_max.y));
    Detection d;
    d.class_id = class_ids[i];
    d.class_name = coco_class_name(d.class_id);
    d.score = scores[i];
    d.box = cv::Rect2f(tl, br);
    if (mask_class_[static_cast<std::size_t>(d.class_id)]) d.mask = instance_mask(outs, rows[i], lb, d.box, bgr.size());
    detections.push_back(std::move(d));
  }
  return detections;
}

cv::Mat1b YoloSegmenter::instance_mask(const Outputs& outs, int row, const Letterbox& lb, const cv::Rect2f& box,
                                       cv::Size frame_size) const {
  // Mask probabilities at prototype resolution: sigmoid(coefficients . prototypes).
  const cv::Mat coeffs = outs.predictions.row(row).colRange(4 + num_classes_, 4 + num_classes_ + kMaskCoefficients);
  cv::Mat logits = coeffs * outs.protos;  // 1 x (H/4 * W/4)
  cv::Mat prob;
  cv::exp(-logits, prob);
  prob = 1.0 / (1.0 + prob);
  prob = prob.reshape(1, outs.proto_size.height);

  cv::Mat1b mask(frame_size, uchar{0});
  // Pixels whose centre lies inside the box (the box crop).
  const cv::Rect roi = cv::Rect(cv::Point(cvRound(box.x), cvRound(box.y)),
                                cv::Point(cvRound(box.x + box.width), cvRound(box.y + box.height))) &
                       cv::Rect(cv::Point(0, 0), frame_size);
  if (roi.empty()) return mask;
  // One bilinear warp from prototype pixels straight to the frame ROI; the same
  // sampling positions as upsampling to the input, removing the letterbox
  // padding and resizing to the frame, without building the full-size images.
  // Frame pixel u -> prototype coordinate ((u + 0.5) * scale + pad) / 4 - 0.5.
  const double a = lb.scale / kProtoStride;
  const cv::Matx23d frame_to_proto(a, 0, ((roi.x + 0.5) * lb.scale + lb.pad_x) / kProtoStride - 0.5,  //
                                   0, a, ((roi.y + 0.5) * lb.scale + lb.pad_y) / kProtoStride - 0.5);
  cv::Mat prob_roi;
  cv::warpAffine(prob, prob_roi, frame_to_proto, roi.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);
  cv::Mat1b roi_mask = mask(roi);
  cv::compare(prob_roi, options_.mask_threshold, roi_mask, cv::CMP_GT);
  return mask;
}

}  // namespace stillslam
