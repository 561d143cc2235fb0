// Writes the binary seeds of tests/fuzz/corpus (scripts/fuzz --seeds runs it):
// a small map file of the synthetic scene (plain and zstd) and a small
// vocabulary, each without its trailing checksum, as fuzz_map_file and
// fuzz_vocabulary expect.
#include <cstdio>
#include <fstream>
#include <random>

#include "common/synthetic_camera.h"
#include "fuzz/fuzz_support.h"
#include "map/map_builder.h"
#include "map/synthetic_scene.h"
#include "stillslam/map/map_file.h"
#include "stillslam/place/vocabulary.h"

namespace {

std::string read_without_checksum(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), {}};
  bytes.resize(bytes.size() - 8);
  return bytes;
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
  return 0;
}
