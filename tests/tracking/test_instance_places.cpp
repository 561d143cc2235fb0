// InstancePlaces: an instance's last place (world frame) and last frame;
// a new instance matches the nearest remembered one of its class within the
// radius that is not in the frame; places not seen for memory_frames expire.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "stillslam/core/error.h"
#include "stillslam/tracking/instance_places.h"

namespace stillslam {
namespace {

// The remembered instance a new instance of `category` at `p_world` takes
// over (0: none), with `present` the ids already in the frame.
std::uint32_t new_instance_takes(const InstancePlaces& places, const std::string& category,
                                 const Eigen::Vector3d& p_world, const std::set<std::uint32_t>& present) {
  constexpr std::uint32_t kNewId = 1000;
  const std::map<std::uint32_t, std::uint32_t> taken =
      places.assign({PlaceClaim{.id = kNewId, .category = category, .p_world = p_world, .is_new = true}}, present);
  const auto it = taken.find(kNewId);
  return it == taken.end() ? 0 : it->second;
}

TEST(InstancePlaces, MatchesTheNearestOfItsClassWithinTheRadius) {
  InstancePlaces places(InstancePlacesOptions{.radius_m = 0.5, .memory_frames = 10});
  const Eigen::Vector3d sitter(1, 2, 0.6), box(1.3, 2, 0.8), far(4, 0, 0);
  places.seen(3, "person", 0, &sitter);
  places.seen(4, "box", 0, &box);
  places.seen(5, "person", 0, &far);
  places.seen(6, "person", 0, nullptr);  // no place known
  EXPECT_EQ(new_instance_takes(places, "person", Eigen::Vector3d(1.2, 2.1, 0.5), {}), 3u);
  EXPECT_EQ(new_instance_takes(places, "box", Eigen::Vector3d(1.2, 2.1, 0.5), {}), 4u);
  EXPECT_EQ(new_instance_takes(places, "person", Eigen::Vector3d(1.2, 2.1, 0.5), {3}), 0u);  // 3 is in the frame
  EXPECT_EQ(new_instance_takes(places, "person", Eigen::Vector3d(1.0, 2.6, 0.6), {}), 0u);   // 0.6 m away
  EXPECT_EQ(new_instance_takes(places, "chair", sitter, {}), 0u);
  EXPECT_EQ(new_instance_takes(places, "person", Eigen::Vector3d(3.8, 0, 0), {}), 5u);
}

// A person seen whole, then only its head at the image border: a new id
// seen later by its feet matches the whole view's place, not the head's.
TEST(InstancePlaces, MatchesWhereItWasSeenMostCompletely) {
  InstancePlaces places(InstancePlacesOptions{.radius_m = 0.5, .memory_frames = 10});
  const Eigen::Vector3d whole(0, 0, 0.6), head(0, 0, 1.1), feet(0.1, 0, 0.2);
  places.seen(3, "person", 0, &whole, 9000);
  places.seen(3, "person", 1, &head, 800);
  EXPECT_EQ(new_instance_takes(places, "person", feet, {}), 3u);  // 0.41 m from the whole view, 0.9 m from the head
  EXPECT_EQ(new_instance_takes(places, "person", head, {}), 3u);
  InstancePlaces last_only(InstancePlacesOptions{.radius_m = 0.5, .memory_frames = 10});
  last_only.seen(3, "person", 1, &head, 800);
  EXPECT_EQ(new_instance_takes(last_only, "person", feet, {}), 0u);
}

// A walker passes in front of a seated person (id 2): the seated person's
// sliver has taken the walker's id 1 by mask overlap, the walker a new id 7
// near the seated person's place. The sliver, far from where id 1 was, takes
// id 2 back; the walker then takes id 1 (left free). Judged alone, the new
// id would take id 2.
TEST(InstancePlaces, SwappedIdsGoBackToTheirPlaces) {
  InstancePlaces places(InstancePlacesOptions{.radius_m = 0.5, .memory_frames = 10});
  const Eigen::Vector3d seated(0, 0, 2), walker(0.6, 0, 1.6);
  places.seen(2, "person", 0, &seated);
  places.seen(1, "person", 0, &walker);
  const std::vector<PlaceClaim> claims{{1, "person", Eigen::Vector3d(0.05, 0, 2), false},
                                       {7, "person", Eigen::Vector3d(0.4, 0, 1.8), true}};
  EXPECT_EQ(new_instance_takes(places, "person", claims[1].p_world, {1, 7}), 2u);
  const std::map<std::uint32_t, std::uint32_t> expected{{1, 2}, {7, 1}};
  EXPECT_EQ(places.assign(claims, {}), expected);
}

// A new id near a remembered person while another person (an older id,
// where its id was) stands nearer to that place: nobody takes it over. With
// that person out of the radius, the new id does.
TEST(InstancePlaces, ARememberedPlaceAnotherInstanceStandsAtIsNotHandedOver) {
  InstancePlaces places(InstancePlacesOptions{.radius_m = 0.5, .memory_frames = 10});
  const Eigen::Vector3d seated(0, 0, 2), walker(0.3, 0, 2);
  places.seen(2, "person", 0, &seated);
  places.seen(1, "person", 0, &walker);
  const PlaceClaim fragment{7, "person", Eigen::Vector3d(-0.4, 0, 2), true};
  EXPECT_TRUE(places.assign({{1, "person", Eigen::Vector3d(0.32, 0, 2), false}, fragment}, {}).empty());
  const Eigen::Vector3d gone(0.9, 0, 2);
  places.seen(1, "person", 1, &gone);
  const std::map<std::uint32_t, std::uint32_t> expected{{7, 2}};
  EXPECT_EQ(places.assign({{1, "person", Eigen::Vector3d(0.92, 0, 2), false}, fragment}, {}), expected);
  // Other classes, instances in the frame (`present`) and radius 0 take nothing over.
  EXPECT_TRUE(places.assign({{7, "chair", Eigen::Vector3d(0, 0, 2), true}}, {}).empty());
  EXPECT_TRUE(places.assign({fragment}, {2}).empty());
  InstancePlaces off(InstancePlacesOptions{.radius_m = 0, .memory_frames = 10});
  off.seen(2, "person", 0, &seated);
  EXPECT_TRUE(off.assign({fragment}, {}).empty());
}

TEST(InstancePlaces, ForgetsPlacesNotSeenForMemoryFrames) {
  InstancePlaces places(InstancePlacesOptions{.radius_m = 0.5, .memory_frames = 10});
  const Eigen::Vector3d p(0, 0, 1);
  places.seen(1, "person", 0, &p);
  places.seen(2, "person", 5, &p);
  EXPECT_TRUE(places.expire(10).empty());
  EXPECT_EQ(places.expire(11), std::vector<std::uint32_t>{1});
  EXPECT_EQ(new_instance_takes(places, "person", p, {}), 2u);
  places.seen(2, "person", 20, nullptr);  // seen again without a place: keeps the last one
  EXPECT_EQ(new_instance_takes(places, "person", p, {}), 2u);
  EXPECT_TRUE(places.expire(30).empty());
  EXPECT_EQ(places.size(), 1u);
}

TEST(InstancePlaces, OptionsOutOfRangeNameTheField) {
  EXPECT_THROW(InstancePlaces(InstancePlacesOptions{.radius_m = -1, .memory_frames = 10}), Error);
  try {
    InstancePlacesOptions{.radius_m = 0.5, .memory_frames = -1}.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("InstancePlacesOptions.memory_frames"), std::string::npos);
  }
}

}  // namespace
}  // namespace stillslam
