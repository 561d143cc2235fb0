#include "stillslam/tracking/start_votes.h"

namespace stillslam {

void StartVotes::reset(std::size_t keypoints) {
  confirmed_.assign(keypoints, 0);
  rejected_.assign(keypoints, 0);
}

void StartVotes::add(const InitialViewCheck& check) {
  for (std::size_t i = 0; i < confirmed_.size(); ++i) {
    if (i < check.confirmed.size() && check.confirmed[i]) ++confirmed_[i];
    if (i < check.keep.size() && !check.keep[i]) ++rejected_[i];
  }
}

std::vector<bool> StartVotes::keep(bool unmasked) const {
  std::vector<bool> out(confirmed_.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = unmasked ? confirmed_[i] > rejected_[i] : rejected_[i] == 0;
  }
  return out;
}

}  // namespace stillslam
