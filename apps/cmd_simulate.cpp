// `stillslam simulate`: synthetic RGB-D / stereo sequences with exact ground
// truth (poses, depth, dynamic masks) and moving people. See sim/sequence_writer.h.
#include <spdlog/spdlog.h>

#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "stillslam/core/error.h"
#include "stillslam/sim/asset_extraction.h"
#include "stillslam/sim/sequence_writer.h"

namespace stillslam::apps {
namespace {

struct SimulateArgs {
  sim::SimulationOptions options;
  std::string out;
  std::string extract_from;
  int cutouts = 12;
  std::vector<std::string> exclude, sitting;
  std::string occlude, crowd;  // T[:D]
};

// "T[:D]" (--occlude, --crowd) -> at = T, seconds = D (unchanged when absent).
void parse_time_window(const std::string& flag, const std::string& text, std::optional<double>& at,
                       double& seconds) {
  if (text.empty()) return;
  const auto colon = text.find(':');
  try {
    std::size_t used = 0;
    const std::string t = text.substr(0, colon);
    at = std::stod(t, &used);
    if (used != t.size()) throw std::invalid_argument(t);
    if (colon != std::string::npos) {
      const std::string d = text.substr(colon + 1);
      seconds = std::stod(d, &used);
      if (used != d.size()) throw std::invalid_argument(d);
    }
  } catch (const std::exception&) {
    throw Error(flag + " " + text + ": expected T or T:D in seconds, e.g. " + flag + " 12 or " + flag + " 12:1.5");
  }
  if (*at < 0 || seconds <= 0) throw Error(flag + " " + text + ": T must be >= 0 and D > 0 seconds");
}

void run_simulate(const SimulateArgs& args) {
  if (!args.extract_from.empty()) {
    sim::AssetExtractionOptions ex;
    ex.cutouts = args.cutouts;
    ex.exclude = args.exclude;
    ex.sitting = args.sitting;
    const auto data = args.options.data_dir.empty() ? std::filesystem::path("data") : args.options.data_dir;
    const auto r = sim::extract_assets(args.extract_from, data, ex);
    spdlog::info("wrote {} textures and {} cut-outs into {}", r.texture_files.size(),
                 r.cutout_files.size(), data.string());
    return;
  }
  if (args.out.empty()) throw Error("simulate: --out DIR is required");
  sim::SimulationOptions options = args.options;
  parse_time_window("--occlude", args.occlude, options.occlude_at, options.occlude_seconds);
  parse_time_window("--crowd", args.crowd, options.crowd_at, options.crowd_seconds);
  if (options.stereo_gray) options.stereo = true;
  const auto s = sim::write_sequence(args.out, options, [](int done, int total) {
    if (done % 100 == 0 || done == total) spdlog::info("rendered {}/{} frames", done, total);
  });
  spdlog::info("{} frames in {:.1f} s ({:.1f} ms/frame rendering) -> {}", s.frames, s.seconds,
               s.render_ms_mean, args.out);
  std::cout << s.settings.string() << "\n";
  if (!s.settings_stereo.empty()) std::cout << s.settings_stereo.string() << "\n";
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  auto& o = args->options;
  auto* cmd = app.add_subcommand(
      "simulate", "Render a synthetic RGB-D (and stereo) sequence with moving people and exact ground truth");
  cmd->add_option("--out", args->out, "Output folder (TUM RGB-D layout; EuRoC mav0/ with --stereo)");
  cmd->add_option("--trajectory", o.trajectory,
                  "walking_xyz, halfsphere, rpy, static, loop (a turn around the room every 20 s), or a TUM trajectory file")
      ->capture_default_str();
  cmd->add_option("--frames", o.frames, "Number of frames at most (walking_xyz has 865 at 30 Hz)")
      ->capture_default_str();
  cmd->add_option("--fps", o.fps, "Frame rate")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--people", o.people, "Walking people")->capture_default_str();
  cmd->add_option("--still-people", o.still_people, "People who stay (almost) still: seated on a chair behind the desk")->capture_default_str();
  cmd->add_flag("--moved-object", o.moved_object, "A box on the desk is picked up and moved");
  cmd->add_option("--occlude", args->occlude,
                  "T[:D]: at T seconds a person walks right in front of the camera and hides (nearly) the whole "
                  "view for D seconds (default 1; walks in during the 0.5 s before, out during the 0.5 s after); "
                  "in the masks; dropped by --no-people");
  cmd->add_flag("--moved-chair", o.moved_chair,
                "A chair behind the desk is pushed 0.6 m aside over 2 s from 65% of the sequence");
  cmd->add_option("--crowd", args->crowd,
                  "T[:D]: a crowd walks across the view 0.9-1.3 m from the camera and covers most of it from T "
                  "seconds for D seconds (default 3; walks in during the ~2 s before, out during those after); "
                  "dropped by --no-people");
  cmd->add_flag("--no-people", o.no_people, "No moving things: static reference of the same sequence");
  cmd->add_option("--seed", o.seed, "Random seed (scene, people, noise)")->capture_default_str();
  cmd->add_flag("--overwrite", o.overwrite, "Replace a sequence already in --out");
  cmd->add_flag("--stereo", o.stereo, "Also write a rectified stereo pair (EuRoC layout, colour PNGs)");
  cmd->add_flag("--gray-stereo", o.stereo_gray, "Stereo pair in gray, like EuRoC's cameras (implies --stereo)");
  cmd->add_option("--baseline", o.baseline, "Stereo baseline in metres")->capture_default_str();
  cmd->add_option("--noise", o.noise, "0 none, 1 realistic, 2 heavy")->capture_default_str()->check(
      CLI::Range(0, 2));
  cmd->add_option("--width", o.width, "Image width (intrinsics scale with it)")->capture_default_str();
  cmd->add_option("--height", o.height, "Image height")->capture_default_str();
  cmd->add_option("--supersampling", o.supersampling, "Colour rays per pixel per axis")
      ->capture_default_str();
  cmd->add_option("--data-dir", o.data_dir, "The repo's data/ folder (textures/, cutouts/, sim/)");
  cmd->add_option("--model", o.segmentation_model, "Segmentation.model written into settings.yaml");
  cmd->add_option("--extract-assets", args->extract_from,
                  "Rebuild data/textures and data/cutouts from this COCO128 YOLO-seg folder, then exit");
  cmd->add_option("--cutouts", args->cutouts, "With --extract-assets: number of cut-outs")
      ->capture_default_str();
  cmd->add_option("--sitting-cutout", args->sitting,
                  "With --extract-assets: export this instance as a seated person (<image id>_<index>)");
  cmd->add_option("--exclude-cutout", args->exclude,
                  "With --extract-assets: skip this instance (<image id>_<index>)");
  cmd->callback([args] { run_simulate(*args); });
}

}  // namespace stillslam::apps
