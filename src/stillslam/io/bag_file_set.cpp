#include "stillslam/io/bag_file_set.h"

#include <spdlog/spdlog.h>

namespace stillslam {

BagFileSet::BagFileSet(const std::filesystem::path& folder, std::vector<std::unique_ptr<BagReader>> files)
    : BagReader(folder), files_(std::move(files)) {
  for (std::size_t f = 0; f < files_.size(); ++f) {
    const BagReader& file = *files_[f];
    std::vector<std::uint32_t> topic_map;
    for (const BagTopic& t : file.topics()) {
      const auto found = find_topic(t.name);
      topic_map.push_back(found ? *found : add_topic(t));
    }
    for (std::size_t i = 0; i < file.messages().size(); ++i) {
      BagMessageInfo m = file.messages()[i];
      m.topic = topic_map[m.topic];
      ++topics_[m.topic].message_count;
      messages_.push_back(m);
      source_.emplace_back(f, i);
    }
    if (!file.damage().empty()) {
      damage_ = file.damage();
      if (f + 1 < files_.size()) spdlog::warn("{}: the files after the damaged one are not read", folder.string());
      break;
    }
  }
}

std::vector<std::uint8_t> BagFileSet::read(std::size_t i) const {
  const auto& [f, k] = source_.at(i);
  return files_[f]->read(k);
}

}  // namespace stillslam
