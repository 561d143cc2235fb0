#pragma once
// The atlas: every map of a run. Tracking works in the active map; when it
// stays lost (relocalization keeps failing) the System starts a new map and
// keeps the old ones; a place recognized across maps merges the active map
// into the old one (loop/map_merger.h). All maps share one set of id
// counters, so keyframe and map-point ids are unique across maps and one
// place-recognition database indexes all of them (its results are grouped
// by map with map_of_keyframe / Map::keyframe).
//
// Locking: the atlas' own mutex guards the list of maps (which maps exist,
// which is active); each map's content is guarded by its update_mutex(). Map
// references stay valid until the map is removed (only after a merge has
// emptied it, by the thread that runs the merge).
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "stillslam/map/map.h"

namespace stillslam {

class Atlas {
 public:
  // Starts with one empty active map (id 0).
  Atlas();
  Atlas(const Atlas&) = delete;
  Atlas& operator=(const Atlas&) = delete;

  // Creates an empty map with the next map id and makes it active.
  Map& create_map();
  Map& active_map() const;
  std::uint64_t active_map_id() const;
  void set_active_map(std::uint64_t id);  // Error for an unknown id

  // Every map, by id (the active one included), and one by id (nullptr when unknown).
  std::vector<Map*> maps() const;
  Map* map(std::uint64_t id) const;
  std::size_t num_maps() const;
  // Maps ever created (merged ones are gone from maps()).
  std::uint64_t maps_created() const;

  // Removes a map emptied by a merge (Map::absorb). Error when it is the
  // active map or not empty.
  void remove_map(std::uint64_t id);

  // Adds a map built elsewhere (loading a saved atlas): it keeps its id, which
  // must be new; later maps get larger ids.
  Map& add_map(std::unique_ptr<Map> map);

  // Loading a saved atlas (map/map_file.h): `maps` (unique ids, built with
  // id_counters()) replace the current maps, which must all be empty; map
  // `active` becomes active; later maps get ids >= next_map_id. Error when
  // `maps` is empty, a current map is not, or `active` is not among them.
  void replace_maps(std::vector<std::unique_ptr<Map>> maps, std::uint64_t active, std::uint64_t next_map_id);

  const std::shared_ptr<MapIdCounters>& id_counters() const { return ids_; }

  // The map holding keyframe `id` (also a culled one), or nullopt. Takes each
  // map's update mutex in turn: call it without holding any.
  std::optional<std::uint64_t> map_of_keyframe(std::uint64_t keyframe_id) const;

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<MapIdCounters> ids_;
  std::vector<std::unique_ptr<Map>> maps_;  // by id
  std::uint64_t active_ = 0;
  std::uint64_t next_map_id_ = 0;
};

}  // namespace stillslam
