// Map files (map/map_file): the input is a whole file but its last 8 bytes,
// the checksum, which the target appends as the writer does, so mutations
// reach the payload's structural checks instead of stopping at the checksum.
// A map that loads is used the way tracking starts on it (point normals and
// distances from their observations, covisibility, the spanning tree).
#include "common/synthetic_camera.h"
#include "fuzz/fuzz_support.h"
#include "stillslam/core/fnv1a.h"
#include "stillslam/map/map_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stillslam;
  static const MapFileContext context{"rgbd", test::synthetic_camera_setup(), 0};
  std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::uint64_t checksum = fnv1a(bytes.data(), bytes.size());
  bytes.append(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
  const auto path = fuzz::temp_folder() / "map.bin";
  fuzz::write_file(path, bytes);
  fuzz::expect_error_or_result([&] {
    const MapFileContents contents = load_map_file(path, context);
    for (const LoadedMap& loaded : contents.maps) {
      for (const MapPointPtr& mp : loaded.map->map_points()) {
        mp->compute_distinctive_descriptor();
        mp->update_normal_and_depth(context.setup->pyramid);
      }
      for (const KeyFramePtr& kf : loaded.map->keyframes()) {
        for (KeyFrame* c : kf->best_covisibles(10)) (void)c->camera_center();
        for (const KeyFrame* p = kf->parent(); p != nullptr; p = p->parent()) (void)p->id();
      }
    }
  });
  return 0;
}
