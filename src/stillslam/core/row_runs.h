#pragma once
// The runs of non-zero bytes in a row of an 8-bit mask, for mask operations
// whose cost should follow the mask's outline rather than its pixel count.
// Zero bytes are skipped eight at a time.
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

namespace stillslam {

// Replaces `runs` with the [first, last) column ranges of non-zero bytes of
// row[begin, end), in order.
inline void row_runs(const unsigned char* row, int begin, int end, std::vector<std::pair<int, int>>& runs) {
  runs.clear();
  int x = begin;
  while (x < end) {
    while (x + 8 <= end) {
      std::uint64_t word;
      std::memcpy(&word, row + x, sizeof word);
      if (word != 0) break;
      x += 8;
    }
    while (x < end && !row[x]) ++x;
    if (x >= end) break;
    const int first = x;
    while (x < end && row[x]) ++x;
    runs.emplace_back(first, x);
  }
}

}  // namespace stillslam
