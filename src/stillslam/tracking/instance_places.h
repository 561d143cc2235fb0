#pragma once
// Where (world frame) each judged instance was last seen, so that an
// instance that comes back under a new id takes over the evidence of the one
// seen at the same place: the segmenter's ids change when an instance leaves
// the view and comes back, is hidden for a while, or when its mask changes
// too much between frames (a small person behind a passer-by). A still
// person or a parked object stays where it was, so its place identifies it;
// a walking person is rarely found where another instance of its class was.
// An id can also swap: when a walker passes in front of a seated person, the
// seated person's remaining sliver may take the walker's id by mask overlap
// (segmentation/instance_ids.h) and the walker a new one; assign() hands each
// remembered instance to the nearest of this frame's instances only, and lets
// an older id take one over when it is no longer where that id was.
#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace stillslam {

// One of this frame's instances with a known place (assign()).
struct PlaceClaim {
  std::uint32_t id = 0;  // its id so far (a new id, or the one it had)
  std::string category;
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
  bool is_new = false;   // a new id: may take over any remembered instance
};

struct InstancePlacesOptions {
  double radius_m = 0.5;    // same place: world points of the same class this close; 0: no matching
  int memory_frames = 300;  // judged frames an instance is kept after it was last seen
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

class InstancePlaces {
 public:
  explicit InstancePlaces(InstancePlacesOptions options = {});

  // Instance `id` of `category` is in judged frame `frame`, at `p_world`
  // when its place is known (else only its last frame is kept), seen on
  // `pixels` pixels.
  void seen(std::uint32_t id, const std::string& category, std::int64_t frame, const Eigen::Vector3d* p_world,
            int pixels = 0);
  // Which remembered instance of its class, not in this frame (`present`
  // and the claims' ids), each claim takes over. Each remembered instance is
  // where it was last seen and where it was seen on the most pixels (its most
  // complete view: a part seen at the image border has its centre off the
  // instance's); a claim's distance is to the nearer. Nearest pairs first, within
  // the radius, each remembered instance to one claim at most. A new id may
  // take one over; an older id only when it has jumped: it is more than half
  // the radius and more than twice as far from where its own id was last
  // seen as from the remembered place. A remembered instance nearest to a
  // claim that may not take it over (another instance of its class stands
  // there) is handed to nobody this frame. A claim's id left behind is free
  // for the others to take. Returns claim id -> remembered id.
  std::map<std::uint32_t, std::uint32_t> assign(const std::vector<PlaceClaim>& claims,
                                                 std::set<std::uint32_t> present) const;
  // Drops the instances not seen for memory_frames before `frame`; returns their ids.
  std::vector<std::uint32_t> expire(std::int64_t frame);
  void clear() { places_.clear(); }
  std::size_t size() const { return places_.size(); }

 private:
  struct Place {
    std::string category;
    std::int64_t last_frame = 0;
    bool known = false;
    Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
    int most_pixels = -1;
    Eigen::Vector3d p_most = Eigen::Vector3d::Zero();  // where it was seen on the most pixels
  };
  // Distance from `p_world` to where the place was seen last or on the most pixels.
  static double distance(const Place& place, const Eigen::Vector3d& p_world);
  InstancePlacesOptions options_;
  std::map<std::uint32_t, Place> places_;
};

}  // namespace stillslam
