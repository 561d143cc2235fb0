#pragma once
// A bag split over several files (rosbag2 --max-bag-size): the files' topics
// merged by name and their messages concatenated in the order given.
#include <memory>

#include "stillslam/io/bag_reader.h"

namespace stillslam {

class BagFileSet : public BagReader {
 public:
  BagFileSet(const std::filesystem::path& folder, std::vector<std::unique_ptr<BagReader>> files);
  std::string storage() const override { return files_.front()->storage(); }
  std::vector<std::uint8_t> read(std::size_t i) const override;

 private:
  std::vector<std::unique_ptr<BagReader>> files_;
  std::vector<std::pair<std::size_t, std::size_t>> source_;  // (file, message in it) per message
};

}  // namespace stillslam
