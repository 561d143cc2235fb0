// Timing of the per-frame pose optimization and of local bundle adjustment on
// synthetic scenes (1 px noise, 30% outliers for the pose, 5% for BA). The
// "CPU" column is the benchmark thread's CPU time (what a shared machine
// does not distort).
//   build/bench/bench_optimize [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/geometry/se3.h"
#include "stillslam/optimize/bundle_adjustment.h"
#include "stillslam/optimize/pose_optimizer.h"

namespace stillslam {
namespace {

CameraCalibration calibration() {
  return pinhole_calibration(517.3, 516.5, 318.6, 255.3, 640, 480);
}

Eigen::Isometry3d pose(const Eigen::Vector3d& center, const Eigen::Vector3d& omega) {
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  T_world_cam.linear() = so3_exp(omega);
  T_world_cam.translation() = center;
  return T_world_cam.inverse();
}

std::vector<PoseObservation> pose_scene(const PinholeCamera& cam, const Eigen::Isometry3d& T, int n) {
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> xy(-2, 2), z(2, 6), ux(0, 640), uy(0, 480), coin(0, 1);
  std::vector<PoseObservation> obs;
  while (static_cast<int>(obs.size()) < n) {
    const Eigen::Vector3d p(xy(rng), xy(rng), z(rng));
    const Eigen::Vector3d pc = T * p;
    const Eigen::Vector2d uv = cam.project(pc);
    if (pc.z() < 0.1 || !cam.in_image(uv)) continue;
    PoseObservation o;
    o.point_world = p;
    const bool out = coin(rng) < 0.3;
    o.pixel = out ? Eigen::Vector2d(ux(rng), uy(rng)) : Eigen::Vector2d(uv + Eigen::Vector2d(noise(rng), noise(rng)));
    if (obs.size() % 2 == 0) o.u_right = out ? o.pixel.x() - 10 : cam.project_right_u(pc) + noise(rng);
    obs.push_back(o);
  }
  return obs;
}

void BM_OptimizePose(benchmark::State& state) {
  const PinholeCamera cam(calibration(), 40.0);
  const Eigen::Isometry3d T = pose({0.1, 0.2, -0.3}, {0.02, -0.05, 0.1});
  const auto obs = pose_scene(cam, T, static_cast<int>(state.range(0)));
  Eigen::Isometry3d T0 = T;
  T0.translation() += Eigen::Vector3d(0.03, -0.02, 0.04);  // a motion-model-sized error
  int inliers = 0;
  for (auto _ : state) {
    const PoseOptimizationResult r = optimize_pose(cam, T0, obs);
    inliers = r.num_inliers;
    benchmark::DoNotOptimize(r.T_cam_world);
  }
  state.counters["inliers"] = inliers;
}
BENCHMARK(BM_OptimizePose)->Arg(300)->Arg(600)->Arg(1000)->Unit(benchmark::kMillisecond);

struct BaScene {
  std::vector<Eigen::Isometry3d> truth;  // T_cam_world per keyframe
  std::vector<BaKeyframe> keyframes;
  std::vector<BaPoint> points;
  std::vector<BaObservation> observations;
};

// Which observations carry a right-image coordinate (RGB-D: those with depth).
enum class Depth { None = 0, All = 1, TwoThirds = 2 };

// num_kf keyframes on a 1.5 m arc looking at num_points points; the first
// num_fixed keyframes fixed; keyframes/points perturbed, every obs noisy.
BaScene ba_scene(const PinholeCamera& cam, int num_kf, int num_points, Depth depth, int num_fixed = 2) {
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 1.0), small(0.0, 1.0);
  std::uniform_real_distribution<double> xy(-3, 3), z(3, 8), coin(0, 1);
  BaScene s;
  std::vector<Eigen::Isometry3d>& truth = s.truth;
  for (int k = 0; k < num_kf; ++k) {
    const double a = 1.5 * k / std::max(1, num_kf - 1);
    truth.push_back(pose({a - 0.75, 0.1 * std::sin(3 * a), 0.2 * a}, {0.12 * a, -0.18 * a, 0.01}));
    Eigen::Isometry3d noisy = truth.back();
    if (k >= num_fixed) {
      noisy.translation() += 0.03 * Eigen::Vector3d(small(rng), small(rng), small(rng));
      noisy.linear() = so3_exp(0.01 * Eigen::Vector3d(small(rng), small(rng), small(rng))) * noisy.linear();
    }
    s.keyframes.push_back({static_cast<std::uint64_t>(k), noisy, k < num_fixed});
  }
  for (int i = 0; i < num_points; ++i) {
    const Eigen::Vector3d p(xy(rng), xy(rng), z(rng));
    std::vector<BaObservation> obs;
    for (int k = 0; k < num_kf; ++k) {
      const Eigen::Vector3d pc = truth[static_cast<std::size_t>(k)] * p;
      const Eigen::Vector2d uv = cam.project(pc);
      if (pc.z() < 0.1 || !cam.in_image(uv)) continue;
      BaObservation o;
      o.keyframe = static_cast<std::size_t>(k);
      o.point = s.points.size();
      const bool out = coin(rng) < 0.05;
      o.pixel = uv + Eigen::Vector2d(noise(rng), noise(rng)) + (out ? Eigen::Vector2d(30, -20) : Eigen::Vector2d::Zero());
      const bool stereo = depth == Depth::All || (depth == Depth::TwoThirds && (s.observations.size() + obs.size()) % 3 != 0);
      if (stereo) o.u_right = cam.project_right_u(pc) + noise(rng) + (out ? 30.0 : 0.0);
      obs.push_back(o);
    }
    if (obs.size() < 2) continue;
    s.points.push_back({static_cast<std::uint64_t>(i), p + 0.05 * Eigen::Vector3d(small(rng), small(rng), small(rng))});
    s.observations.insert(s.observations.end(), obs.begin(), obs.end());
  }
  return s;
}

void BM_LocalBundleAdjustment(benchmark::State& state) {
  const PinholeCamera cam(calibration(), 40.0);
  const BaScene s = ba_scene(cam, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                            static_cast<Depth>(state.range(2)));
  BundleAdjustmentOptions options;
  options.iterations = 5;
  options.iterations_after_outliers = 10;
  options.split_stereo = state.range(4) != 0;
  options.linear_solver = state.range(3) == 0   ? BaLinearSolver::DenseSchur
                          : state.range(3) == 1 ? BaLinearSolver::SparseSchur
                                                : BaLinearSolver::IterativeSchur;
  options.function_tolerance = state.range(5) == 0 ? 1e-6 : std::pow(10.0, -static_cast<double>(state.range(5)));
  double final_cost = 0, position_error = 0;
  int iterations = 0;
  for (auto _ : state) {
    const BundleAdjustmentResult r = bundle_adjust(cam, s.keyframes, s.points, s.observations, options);
    final_cost = r.final_cost;
    iterations = r.iterations;
    position_error = 0;
    for (std::size_t k = 0; k < r.T_cam_world.size(); ++k) {
      position_error += (r.T_cam_world[k].inverse().translation() - s.truth[k].inverse().translation()).norm();
    }
    benchmark::DoNotOptimize(r.points);
  }
  state.counters["observations"] = static_cast<double>(s.observations.size());
  state.counters["final_cost_per_obs"] = final_cost / static_cast<double>(s.observations.size());
  state.counters["iterations"] = iterations;
  state.counters["mean_kf_err_mm"] = 1000 * position_error / static_cast<double>(s.keyframes.size());
}
// Args: keyframes, points, depth (0 none, 1 all, 2 two thirds), solver (0 dense,
// 1 sparse, 2 iterative Schur), split stereo (0 one 3-row block, 1 two 2-row
// blocks), function tolerance (0: 1e-6, n: 1e-n).
BENCHMARK(BM_LocalBundleAdjustment)
    ->Args({10, 1000, 1, 0, 0, 0})
    ->Args({10, 1000, 1, 0, 1, 0})
    ->Args({10, 1000, 2, 0, 0, 0})
    ->Args({10, 1000, 2, 0, 1, 0})
    ->Args({10, 1000, 2, 1, 1, 0})
    ->Args({10, 1000, 2, 2, 1, 0})
    ->Args({10, 1000, 0, 0, 1, 0})
    ->Args({20, 2000, 2, 0, 0, 0})
    ->Args({20, 2000, 2, 0, 1, 0})
    ->Args({20, 2000, 2, 1, 1, 0})
    ->Args({20, 2000, 2, 0, 1, 4})
    ->Args({20, 2000, 2, 0, 1, 3})
    // The median local BA window of the halfsphere run before (42 free
    // keyframes, 3500 points) and after (12 + 8 fixed, 1400 points) the budget.
    ->Args({42, 3500, 2, 1, 0, 0})
    ->Args({42, 3500, 2, 1, 1, 3})
    ->Args({20, 1400, 2, 0, 0, 3})
    ->Args({20, 1400, 2, 0, 1, 3})
    ->Args({20, 1400, 1, 0, 0, 3})
    ->Args({20, 1400, 1, 0, 1, 3})
->Unit(benchmark::kMillisecond);

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Ceres against the hand-written Schur solver (BaSolver) on the same problem,
// one after the other in every benchmark iteration, with the local mapper's
// options (5 robust + 10 iterations, function tolerance 1e-4). Counters:
// median thread-CPU ms per BA of each, their ratio, and the final costs.
// Args: free keyframes, fixed keyframes, points, depth (as above), split stereo.
void BM_LocalBaSolvers(benchmark::State& state) {
  const PinholeCamera cam(calibration(), 40.0);
  const int num_fixed = static_cast<int>(state.range(1));
  const BaScene s = ba_scene(cam, static_cast<int>(state.range(0)) + num_fixed, static_cast<int>(state.range(2)),
                            static_cast<Depth>(state.range(3)), num_fixed);
  BundleAdjustmentOptions options;
  options.iterations = 5;
  options.iterations_after_outliers = 10;
  options.function_tolerance = 1e-4;
  options.split_stereo = state.range(4) != 0;
  std::vector<double> ceres_ms, schur_ms;
  double ceres_cost = 0, schur_cost = 0;
  int ceres_iterations = 0, schur_iterations = 0;
  for (auto _ : state) {
    for (const BaSolver solver : {BaSolver::Ceres, BaSolver::Schur}) {
      options.solver = solver;
      const ThreadCpuStopwatch cpu;
      const BundleAdjustmentResult r = bundle_adjust(cam, s.keyframes, s.points, s.observations, options);
      const double ms = cpu.elapsed_ms();
      benchmark::DoNotOptimize(r.points);
      (solver == BaSolver::Ceres ? ceres_ms : schur_ms).push_back(ms);
      (solver == BaSolver::Ceres ? ceres_cost : schur_cost) = r.final_cost;
      (solver == BaSolver::Ceres ? ceres_iterations : schur_iterations) = r.iterations;
    }
  }
  state.counters["observations"] = static_cast<double>(s.observations.size());
  state.counters["ceres_ms"] = median(ceres_ms);
  state.counters["schur_ms"] = median(schur_ms);
  state.counters["ratio"] = median(ceres_ms) / median(schur_ms);
  state.counters["ceres_cost"] = ceres_cost;
  state.counters["schur_cost"] = schur_cost;
  state.counters["ceres_it"] = ceres_iterations;
  state.counters["schur_it"] = schur_iterations;
}
BENCHMARK(BM_LocalBaSolvers)
    // The local mapper's median window on the walking_xyz render (19 free +
    // 10 fixed keyframes, ~1600 points, ~11300 observations), RGB-D and mixed.
    ->Args({19, 10, 1600, 1, 1})
    ->Args({19, 10, 1600, 1, 0})
    ->Args({19, 10, 1600, 2, 1})
    ->Args({19, 10, 1600, 0, 1})
    ->Args({10, 2, 1000, 2, 1})
    ->Args({40, 10, 3500, 2, 1})
    ->Iterations(7)
    ->Unit(benchmark::kMillisecond);

// Global BA as loop closing runs it (LoopCloserOptions::
// default_global_bundle_adjustment: 10 robust iterations, no outlier pass,
// function tolerance 1e-6, sparse Schur above 40 free keyframes) on a larger
// scene. Args: keyframes, points, depth (as above), split stereo (0/1).
void BM_GlobalBundleAdjustment(benchmark::State& state) {
  const PinholeCamera cam(calibration(), 40.0);
  const BaScene s = ba_scene(cam, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                            static_cast<Depth>(state.range(2)));
  BundleAdjustmentOptions options;
  options.iterations = 10;
  options.outlier_rounds = 0;
  options.split_stereo = state.range(3) != 0;
  double position_error = 0;
  int iterations = 0;
  for (auto _ : state) {
    const BundleAdjustmentResult r = bundle_adjust(cam, s.keyframes, s.points, s.observations, options);
    iterations = r.iterations;
    position_error = 0;
    for (std::size_t k = 0; k < r.T_cam_world.size(); ++k) {
      position_error += (r.T_cam_world[k].inverse().translation() - s.truth[k].inverse().translation()).norm();
    }
    benchmark::DoNotOptimize(r.points);
  }
  state.counters["observations"] = static_cast<double>(s.observations.size());
  state.counters["iterations"] = iterations;
  state.counters["mean_kf_err_mm"] = 1000 * position_error / static_cast<double>(s.keyframes.size());
}
BENCHMARK(BM_GlobalBundleAdjustment)
    ->Args({60, 2500, 2, 0})
    ->Args({60, 2500, 2, 1})
    ->Args({60, 2500, 1, 0})
    ->Args({60, 2500, 1, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stillslam

BENCHMARK_MAIN();
