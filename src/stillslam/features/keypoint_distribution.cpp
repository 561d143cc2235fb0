#include "stillslam/features/keypoint_distribution.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>

namespace stillslam {
namespace {

struct Node {
  cv::Rect2f box;
  int depth = 0;
  std::vector<std::size_t> members;
};

// Heap order: shallow nodes first, then more members, then creation order.
struct SplitKey {
  int depth;
  std::size_t count;
  std::size_t id;
  bool operator<(const SplitKey& o) const {  // "lower priority than"
    return std::tie(o.depth, count, o.id) < std::tie(depth, o.count, id);
  }
};

constexpr int kMaxDepth = 24;  // guards against identical coordinates

}  // namespace

std::vector<std::size_t> distribute_quadtree(const std::vector<cv::KeyPoint>& keypoints,
                                             const cv::Rect2f& region, int target) {
  std::vector<std::size_t> result;
  if (target <= 0 || keypoints.empty() || region.width <= 0 || region.height <= 0) return result;

  // Initial nodes: a row of roughly square nodes across the region.
  const int n_initial = std::max(1, static_cast<int>(std::lround(region.width / region.height)));
  const float initial_w = region.width / static_cast<float>(n_initial);
  std::vector<Node> nodes;
  nodes.reserve(static_cast<std::size_t>(4 * target + n_initial + 8));
  for (int i = 0; i < n_initial; ++i) {
    nodes.push_back({cv::Rect2f(region.x + initial_w * static_cast<float>(i), region.y, initial_w,
                                region.height),
                     0,
                     {}});
  }
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    const cv::Point2f& p = keypoints[k].pt;
    if (p.x < region.x || p.y < region.y || p.x >= region.x + region.width ||
        p.y >= region.y + region.height) {
      continue;
    }
    const int i = std::min(n_initial - 1, static_cast<int>((p.x - region.x) / initial_w));
    nodes[static_cast<std::size_t>(i)].members.push_back(k);
  }

  std::vector<bool> alive(nodes.size(), false);
  std::priority_queue<SplitKey> queue;
  std::size_t n_alive = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].members.empty()) continue;
    alive[i] = true;
    ++n_alive;
    if (nodes[i].members.size() > 1) queue.push({0, nodes[i].members.size(), i});
  }

  while (n_alive < static_cast<std::size_t>(target) && !queue.empty()) {
    const SplitKey key = queue.top();
    queue.pop();
    Node parent = std::move(nodes[key.id]);
    alive[key.id] = false;
    --n_alive;
    const float hw = parent.box.width * 0.5f, hh = parent.box.height * 0.5f;
    const float mx = parent.box.x + hw, my = parent.box.y + hh;
    std::vector<std::size_t> quadrants[4];
    for (std::size_t k : parent.members) {
      const cv::Point2f& p = keypoints[k].pt;
      quadrants[(p.x >= mx ? 1 : 0) + (p.y >= my ? 2 : 0)].push_back(k);
    }
    for (int q = 0; q < 4; ++q) {
      if (quadrants[q].empty()) continue;
      const cv::Rect2f box(q % 2 ? mx : parent.box.x, q / 2 ? my : parent.box.y, hw, hh);
      const std::size_t id = nodes.size();
      const std::size_t count = quadrants[q].size();
      nodes.push_back({box, parent.depth + 1, std::move(quadrants[q])});
      alive.push_back(true);
      ++n_alive;
      if (count > 1 && parent.depth + 1 < kMaxDepth) queue.push({parent.depth + 1, count, id});
    }
  }

  // Strongest keypoint of every node (ties: lower index).
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!alive[i]) continue;
    std::size_t best = nodes[i].members.front();
    for (std::size_t k : nodes[i].members) {
      if (keypoints[k].response > keypoints[best].response) best = k;
    }
    result.push_back(best);
  }
  if (result.size() > static_cast<std::size_t>(target)) {
    std::stable_sort(result.begin(), result.end(), [&](std::size_t a, std::size_t b) {
      return keypoints[a].response > keypoints[b].response;
    });
    result.resize(static_cast<std::size_t>(target));
  }
  std::sort(result.begin(), result.end());
  return result;
}

}  // namespace stillslam
