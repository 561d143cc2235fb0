// Vocabulary files (place/vocabulary_io): the input is a whole file but its
// last 8 bytes, the checksum, which the target appends as the writer does. A
// vocabulary that loads turns fixed descriptors into words and a BoW vector.
#include <opencv2/core.hpp>

#include "fuzz/fuzz_support.h"
#include "stillslam/core/fnv1a.h"
#include "stillslam/place/vocabulary.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stillslam;
  std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::uint64_t checksum = fnv1a(bytes.data(), bytes.size());
  bytes.append(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
  const auto path = fuzz::temp_folder() / "vocabulary.bin";
  fuzz::write_file(path, bytes);
  fuzz::expect_error_or_result([&] {
    const Vocabulary vocabulary = Vocabulary::load(path);
    cv::Mat descriptors(16, 32, CV_8U);
    cv::randu(descriptors, 0, 256);  // OpenCV's fixed default seed: the same rows every time
    BowVector bow;
    FeatureVector features;
    vocabulary.transform(descriptors, bow, features, 2);
    for (int i = 0; i < descriptors.rows; ++i) (void)vocabulary.node_depth(vocabulary.word_node(vocabulary.word_of(descriptors.ptr(i))));
  });
  return 0;
}
