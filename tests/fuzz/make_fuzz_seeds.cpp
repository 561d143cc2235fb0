// Writes the binary seeds of tests/fuzz/corpus (scripts/fuzz --seeds runs it):
// a small map file of the synthetic scene (plain and zstd) and a small
// vocabulary, each without its trailing checksum, as fuzz_map_file and
// fuzz_vocabulary expect; tiny MCAP bags (zstd, lz4, none without summary,
// no chunks) and CDR payloads (type byte + message) for fuzz_mcap / fuzz_cdr.
#include <cstdio>
#include <fstream>
#include <random>
#include <tuple>

#include "common/synthetic_camera.h"
#include "fuzz/fuzz_support.h"
#include "map/map_builder.h"
#include "map/synthetic_scene.h"
#include "stillslam/map/map_file.h"
#include "stillslam/io/bag_writer.h"
#include "stillslam/io/ros2_image_convert.h"
#include "stillslam/io/ros2_message_codec.h"
#include "stillslam/place/vocabulary.h"

namespace {

std::string read_without_checksum(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), {}};
  bytes.resize(bytes.size() - 8);
  return bytes;
}

// One message of each type the readers decode, small.
std::vector<std::pair<std::string, stillslam::ros2::Bytes>> sample_messages() {
  using namespace stillslam;
  ros2::Header h;
  h.set_stamp_ns(1'700'000'000'000'000'000);
  h.frame_id = "f";
  cv::Mat image(2, 4, CV_8UC1, cv::Scalar(7));
  ros2::CameraInfo info;
  info.header = h;
  info.width = 4;
  info.height = 2;
  info.distortion_model = "plumb_bob";
  info.d = {0.1, 0, 0, 0, 0};
  info.k = {3, 0, 2, 0, 3, 1, 0, 0, 1};
  ros2::Odometry odom;
  odom.header = h;
  odom.child_frame_id = "b";
  ros2::TfMessage tf;
  tf.transforms.resize(1);
  tf.transforms[0].header = h;
  tf.transforms[0].child_frame_id = "b";
  ros2::PoseStamped pose;
  pose.header = h;
  return {{ros2::kImageType, ros2::encode(ros2::mat_to_image(image, h))},
          {ros2::kCompressedImageType, ros2::encode(ros2::mat_to_png(image, h))},
          {ros2::kCameraInfoType, ros2::encode(info)},
          {ros2::kPoseStampedType, ros2::encode(pose)},
          {ros2::kOdometryType, ros2::encode(odom)},
          {ros2::kTfMessageType, ros2::encode(tf)}};
}

}  // namespace

int main(int argc, char** argv) {
  using namespace stillslam;
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_fuzz_seeds CORPUS_FOLDER (tests/fuzz/corpus)\n");
    return 2;
  }
  const std::filesystem::path corpus = argv[1];
  const auto tmp = fuzz::temp_folder();

  // Three keyframes over 40 points, one culled point's worth of edits: a file of a few KB.
  test::SyntheticScene scene(40, 11);
  test::MapBuilder builder(scene);
  for (int i = 0; i < 3; ++i) builder.add_keyframe(test::pose_at(0.1 * i, 0.01 * i, 3.0 * i));
  const MapFileContext context{"rgbd", test::synthetic_camera_setup(), 0};
  for (const bool compress : {false, true}) {
    const auto file = tmp / "map.bin";
    save_map_file(file, context, builder.map(), {{0, 2}, {2, 0}}, MapFileSaveOptions{compress, 3});
    fuzz::write_file(corpus / "map_file" / (compress ? "zstd.map" : "plain.map"), read_without_checksum(file));
  }

  // k = 3, L = 3 over 300 random descriptors in 6 images.
  std::mt19937 rng(5);
  std::vector<cv::Mat> images;
  for (int i = 0; i < 6; ++i) {
    cv::Mat d(0, 32, CV_8U);
    for (int k = 0; k < 50; ++k) d.push_back(test::descriptor_row(test::random_descriptor(rng)));
    images.push_back(d);
  }
  for (const WordWeighting w : {WordWeighting::kTfIdf, WordWeighting::kBinary}) {
    VocabularyOptions options;
    options.branching = 3;
    options.levels = 3;
    options.weighting = w;
    const auto file = tmp / "vocabulary.bin";
    Vocabulary::train(images, options).save(file);
    fuzz::write_file(corpus / "vocabulary" / (w == WordWeighting::kTfIdf ? "k3l3_tfidf.voc" : "k3l3_binary.voc"),
                     read_without_checksum(file));
  }

  // MCAP bags and CDR payloads.
  const auto messages = sample_messages();
  for (const auto& [name, compression, chunked, summary] :
       {std::tuple{"zstd.mcap", "zstd", true, true}, std::tuple{"lz4.mcap", "lz4", true, true},
        std::tuple{"none_no_summary.mcap", "none", true, false}, std::tuple{"no_chunks.mcap", "none", false, true}}) {
    BagWriterOptions o;
    o.compression = compression;
    o.chunked = chunked;
    o.summary = summary;
    const auto file = tmp / name;
    std::filesystem::remove(file);
    auto bag = open_bag_writer(file, o);
    for (std::size_t t = 0; t < messages.size(); ++t) {
      bag->add_topic("/t" + std::to_string(t), messages[t].first);
      bag->write(static_cast<std::uint32_t>(t), 1000 + static_cast<std::int64_t>(t), messages[t].second);
    }
    bag->close();
    std::ifstream in(file, std::ios::binary);
    fuzz::write_file(corpus / "mcap" / name, std::string{std::istreambuf_iterator<char>(in), {}});
  }
  const char* cdr_names[] = {"image", "compressed_image", "camera_info", "pose_stamped", "odometry", "tf"};
  // fuzz_cdr's type byte: 0 Image, 1 CompressedImage, 2 CameraInfo, 3 PoseStamped, 4 Odometry, 5 TFMessage.
  for (std::size_t t = 0; t < messages.size(); ++t) {
    std::string bytes(1, static_cast<char>(t));
    bytes.append(messages[t].second.begin(), messages[t].second.end());
    fuzz::write_file(corpus / "cdr" / (std::string(cdr_names[t]) + ".cdr"), bytes);
  }
  return 0;
}
