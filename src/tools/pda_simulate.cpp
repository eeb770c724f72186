// pda_simulate: simulate an office, a hand-held Kinect 2 scan (the dense map, target) and a few
// Velodyne VLP-16 revolutions (the sparse map, source) with a known T_target_source, and write
// them as a case folder (target.pcd, source.pcd, T_target_source.txt, as in ../shared/data) and/or
// a rosbag. With --distortion the ground truth is the best rigid fit of the warp over the overlap
// (warp_rigid_fit.hpp); the warp's fixed point goes to T_target_source_unwarped.txt beside it.
// Prints one JSON line. Exit codes: 0 written, 2 bad usage or a file not written.

#include <chrono>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <vector>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/transform_io.hpp"
#include "pda_registration/simulation/map_bag_writer.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "pda_registration/tools/cloud_io.hpp"
#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/json_line.hpp"

using namespace pda_registration;
using namespace pda_registration::simulation;

namespace {

const char* kUsage =
    "usage: pda_simulate --output DIR [--bag FILE] [options]\n"
    "  Simulates an office scanned by a Kinect 2 (dense map, target) and a Velodyne VLP-16\n"
    "  (sparse map, source), p_dense = T * p_sparse. Prints one JSON line.\n"
    "  --output DIR              write DIR/target.pcd, DIR/source.pcd, DIR/T_target_source.txt\n"
    "                            (the ground truth) and DIR/T_target_source_unwarped.txt (the\n"
    "                            chosen transform before --distortion; the same without it)\n"
    "  --bag FILE                write a rosbag: /dense_map, /sparse_map, /tf (perturbed seed\n"
    "                            dense_map -> sparse_map), /ground_truth\n"
    "  --seed N                  scene layout and sensor noise (1)\n"
    "  --noise-seed N            another draw of the sensor noise alone: the same scene,\n"
    "                            poses and ground truth (default: from --seed)\n"
    "  --scene office|outdoor    office (default), or a ground-dominated car park with a few\n"
    "                            buildings, parked cars, poles and trees (ranges to 80 m+)\n"
    "  --dense-sensor S          kinect (office default), vlp16 or lidar64 (outdoor default):\n"
    "                            what builds the dense map\n"
    "  --dense-revolutions N     lidar dense sensors: revolutions in the dense map (4)\n"
    "  --sparse-sensor S         vlp16 (default) or kinect: the source is a second hand-held\n"
    "                            Kinect fragment (the dense map scans the first 60 % of the\n"
    "                            office's walkway, the source the last 60 %: RGB-D fragments\n"
    "                            overlapping on two fifths of the loop)\n"
    "  --same-pose               lidar dense sensors: the dense revolutions are taken at the\n"
    "                            sparse scan's own pose by the same sensor (same azimuth grid),\n"
    "                            and the sparse map is one more revolution cut to the rings\n"
    "                            within +-15 deg: the same-sensor lattice case\n"
    "  --dense-offset X,Y,YAW    lidar dense sensors: the dense revolutions are taken at the\n"
    "                            sparse scan's pose moved by X, Y metres and turned by YAW\n"
    "                            degrees: a scan pair (e.g. 3,0,31)\n"
    "  --scan-frame              the sparse map (one VLP-16 revolution) in its sensor's own\n"
    "                            frame, as a real scan: the ground truth is the sensor's pose\n"
    "                            (--yaw-deg, --translation etc. are then not used)\n"
    "  --kinect-frames N         depth frames around the walkway (24)\n"
    "  --fragment-length L       with --sparse-sensor kinect: the share of the walkway loop\n"
    "                            each fragment scans, the dense map the first, the source\n"
    "                            the last (0.6); shorter ones share less of the scene\n"
    "  --velodyne-revolutions N  lidar stops around the walkway, one revolution each (3)\n"
    "  --dense-voxel M           voxel grid of the dense map in metres, 0 keeps every point "
    "(0.03\n"
    "                            for the Kinect, 0 for lidar dense sensors)\n"
    "  --yaw-deg D               yaw of T_target_source (25)\n"
    "  --pitch-deg D             pitch of T_target_source (0)\n"
    "  --roll-deg D              roll of T_target_source (0)\n"
    "  --translation X,Y,Z       translation of T_target_source in metres (1.5,-0.8,0.1)\n"
    "                            (the ground truth; with --distortion, before the warp)\n"
    "  --distortion A            non-rigid drift of the dense map: relative scale error 5 m from\n"
    "                            the centre, with as much upward bend (0 = rigid; 0.01 = 5 cm).\n"
    "                            The ground truth is then the best rigid fit of the warp over\n"
    "                            the sparse points that have a dense point within 0.1 m\n"
    "  --scene-changes F         the sparse map is scanned on another day, with a share F of\n"
    "                            the car park's places (cars gone, come or parked otherwise)\n"
    "                            or of the office's chairs (gone or moved) drawn again;\n"
    "                            0 = the same day (0)\n"
    "  --no-noise                exact sensors (no depth or range noise)\n"
    "  --seed-error-deg D        rotation error of the bag's tf seed (3)\n"
    "  --seed-error-m M          translation error of the bag's tf seed (0.15)\n"
    "  --dense-messages N        dense maps in the bag, latched (2)\n"
    "  --sparse-messages N       sparse maps in the bag, at 1 Hz (5)\n"
    "  --tf-rate HZ              rate of the seed on /tf (10)\n"
    "  --help\n";

int usageError(const std::string& message) { return reportError("pda_simulate", message); }

}  // namespace

int main(int argc, char** argv) {
  // clang-format off
  CommandLine cl({"output",          "bag",
                  "seed",            "noise-seed",
                  "scene",           "dense-sensor",
                  "sparse-sensor",   "dense-revolutions",
                  "kinect-frames",   "fragment-length",
                  "velodyne-revolutions",
                  "dense-voxel",     "yaw-deg",
                  "pitch-deg",       "roll-deg",
                  "translation",     "distortion",
                  "seed-error-deg",  "seed-error-m",
                  "dense-messages",  "sparse-messages",
                  "tf-rate",         "dense-offset",
                  "scene-changes"},
                 {"no-noise", "same-pose", "scan-frame", "help"});
  // clang-format on
  if (!cl.parse(argc, argv)) return usageError(cl.error());
  if (cl.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  if (!cl.has("output") && !cl.has("bag")) return usageError("--output or --bag is required");

  MapSimulationOptions options;
  MapBagOptions bag_options;
  int seed = 1, noise_seed = 0;
  double seed_error_deg = 3.0, seed_error_m = 0.15;
  std::vector<double> translation = {options.translation.x(), options.translation.y(),
                                     options.translation.z()};
  std::vector<double> dense_offset = {0.0, 0.0, 0.0};
  const bool flags_ok = cl.integer("seed", &seed, 0, 2147483647) &&
                        cl.integer("noise-seed", &noise_seed, 1, 2147483647) &&
                        cl.integer("kinect-frames", &options.kinect_frames, 1, 1000) &&
                        cl.number("fragment-length", &options.fragment_length, 0.2, 1.0) &&
                        cl.integer("velodyne-revolutions", &options.velodyne_revolutions, 1, 100) &&
                        cl.number("dense-voxel", &options.dense_voxel_size, 0.0, 1.0) &&
                        cl.number("yaw-deg", &options.yaw_deg, -360.0, 360.0) &&
                        cl.number("pitch-deg", &options.pitch_deg, -90.0, 90.0) &&
                        cl.number("roll-deg", &options.roll_deg, -180.0, 180.0) &&
                        cl.numberList("translation", &translation, -1e4, 1e4) &&
                        cl.numberList("dense-offset", &dense_offset, -1e3, 1e3) &&
                        cl.number("distortion", &options.distortion, 0.0, 0.2) &&
                        cl.number("scene-changes", &options.scene_change_share, 0.0, 1.0) &&
                        cl.number("seed-error-deg", &seed_error_deg, 0.0, 180.0) &&
                        cl.number("seed-error-m", &seed_error_m, 0.0, 1e3) &&
                        cl.integer("dense-messages", &bag_options.dense_messages, 1, 100) &&
                        cl.integer("sparse-messages", &bag_options.sparse_messages, 1, 100) &&
                        cl.number("tf-rate", &bag_options.tf_rate, 0.1, 1000.0);
  if (!flags_ok) return usageError(cl.error());
  const std::string scene = cl.text("scene", "office");
  if (scene != "office" && scene != "outdoor")
    return usageError("--scene: expected office or outdoor (got '" + scene + "')");
  options.scene = scene == "office" ? SceneKind::kOffice : SceneKind::kOutdoor;
  const std::string dense_sensor =
      cl.text("dense-sensor", options.scene == SceneKind::kOffice ? "kinect" : "lidar64");
  if (dense_sensor == "kinect")
    options.dense_sensor = DenseSensor::kKinect;
  else if (dense_sensor == "vlp16")
    options.dense_sensor = DenseSensor::kVlp16;
  else if (dense_sensor == "lidar64")
    options.dense_sensor = DenseSensor::kLidar64;
  else
    return usageError("--dense-sensor: expected kinect, vlp16 or lidar64 (got '" + dense_sensor +
                      "')");
  const std::string sparse_sensor = cl.text("sparse-sensor", "vlp16");
  if (sparse_sensor == "kinect")
    options.sparse_sensor = SparseSensor::kKinectFragment;
  else if (sparse_sensor != "vlp16")
    return usageError("--sparse-sensor: expected vlp16 or kinect (got '" + sparse_sensor + "')");
  if (!cl.integer("dense-revolutions", &options.dense_revolutions, 1, 100))
    return usageError(cl.error());
  options.same_pose = cl.has("same-pose");
  if (dense_offset.size() != 3) return usageError("--dense-offset: expected X,Y,YAW (e.g. 3,0,31)");
  options.dense_offset_set = cl.has("dense-offset");
  options.scan_frame = cl.has("scan-frame");
  if (options.scan_frame &&
      (cl.has("yaw-deg") || cl.has("pitch-deg") || cl.has("roll-deg") || cl.has("translation")))
    return usageError(
        "--scan-frame sets the ground truth to the sensor's pose: drop --yaw-deg, "
        "--pitch-deg, --roll-deg and --translation");
  options.dense_offset = Eigen::Vector3d(dense_offset[0], dense_offset[1], dense_offset[2]);
  // A lidar map is kept whole: a voxel grid would average away its scan lattice.
  if (!cl.has("dense-voxel") && options.dense_sensor != DenseSensor::kKinect)
    options.dense_voxel_size = 0.0;
  const std::string invalid = validateSimulationOptions(options);
  if (!invalid.empty()) return usageError(invalid);
  if (translation.size() != 3)
    return usageError("--translation: expected X,Y,Z (e.g. 1.5,-0.8,0.1)");
  options.seed = static_cast<uint64_t>(seed);
  options.noise_seed = static_cast<uint64_t>(noise_seed);
  options.translation = Eigen::Vector3d(translation[0], translation[1], translation[2]);
  options.kinect.noise = options.velodyne.noise = !cl.has("no-noise");

  // Unusable destinations fail before the simulation, not after it.
  const std::filesystem::path folder(cl.text("output"));
  if (cl.has("output")) {
    std::error_code failure;
    std::filesystem::create_directories(folder, failure);
    if (failure) return usageError("--output: cannot create '" + folder.string() + "'");
  }
  if (cl.has("bag")) {
    const std::filesystem::path bag_folder =
        std::filesystem::absolute(cl.text("bag")).parent_path();
    if (!std::filesystem::is_directory(bag_folder)) {
      return usageError("--bag: no directory '" + bag_folder.string() + "'");
    }
  }

  const auto start = std::chrono::steady_clock::now();
  const SimulatedMaps maps = simulateMaps(options);
  const double simulation_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  JsonLine files;
  std::string error;
  if (cl.has("output")) {
    const std::string target = (folder / "target.pcd").string();
    const std::string source = (folder / "source.pcd").string();
    const std::string transform = (folder / "T_target_source.txt").string();
    const std::string unwarped = (folder / "T_target_source_unwarped.txt").string();
    if (!savePointCloudFile(target, maps.dense, &error) ||
        !savePointCloudFile(source, maps.sparse, &error) ||
        !writeTransformFile(transform, maps.T_target_source, &error) ||
        !writeTransformFile(unwarped, maps.T_target_source_unwarped, &error)) {
      return usageError("--output: " + error);
    }
    files.add("target", target).add("source", source).add("ground_truth", transform);
    files.add("ground_truth_unwarped", unwarped);
  }

  JsonLine bag_json;
  if (cl.has("bag")) {
    const Eigen::Isometry3d T_seed =
        maps.T_target_source * randomPerturbation(seed_error_deg, seed_error_m, options.seed);
    MapBagSummary summary;
    if (!writeMapBag(cl.text("bag"), maps.dense, maps.sparse, maps.T_target_source, T_seed,
                     bag_options, &summary, &error)) {
      return usageError("--bag: " + error);
    }
    files.add("bag", cl.text("bag"));
    bag_json.add("duration_s", summary.duration).add("dense_messages", summary.dense_messages);
    bag_json.add("sparse_messages", summary.sparse_messages)
        .add("tf_messages", summary.tf_messages);
    bag_json.add("ground_truth_messages", summary.ground_truth_messages);
    bag_json.add("seed_error_deg", seed_error_deg).add("seed_error_m", seed_error_m);
    bag_json.add("T_seed", T_seed);
  }

  JsonLine json;
  json.add("seed", seed)
      .add("noise_seed", static_cast<int>(noiseSeed(options)))
      .add("scene_primitives", maps.scene.primitiveCount());
  json.add("scene", scene).add("dense_sensor", dense_sensor).add("same_pose", options.same_pose);
  json.add("dense_raw_points", maps.dense_raw_points);
  json.add("dense_points", maps.dense.size());
  json.add("velodyne_revolutions", options.velodyne_revolutions);
  json.add("sparse_points", maps.sparse.size()).add("distortion", options.distortion);
  json.add("noise", options.kinect.noise).add("simulation_ms", simulation_ms);
  if (options.scene_change_share > 0.0) {
    json.add("scene_changes", options.scene_change_share)
        .add("changed_places", maps.changed_places);
  }
  json.add("T_target_source", maps.T_target_source);
  json.add("T_target_source_unwarped", maps.T_target_source_unwarped);
  if (options.distortion != 0.0) {
    // How far the ground truth moved from the fixed point, measured as pda_benchmark measures
    // errors (eq. 22 over the sparse map, rotation, translation), and how well a rigid fit can do.
    const PoseError moved =
        poseError(maps.sparse, maps.T_target_source, maps.T_target_source_unwarped);
    JsonLine fit;
    fit.add("overlap_points", maps.warp_fit.overlap_points);
    fit.add("mean_distance_m", moved.mean_distance).add("rotation_deg", moved.rotation_deg);
    fit.add("translation_m", moved.translation);
    fit.add("rms_residual_fixed_m", maps.warp_fit.rms_residual_fixed);
    fit.add("rms_residual_fit_m", maps.warp_fit.rms_residual_fit);
    fit.add("mean_residual_fixed_m", maps.warp_fit.mean_residual_fixed);
    fit.add("mean_residual_fit_m", maps.warp_fit.mean_residual_fit);
    json.addRaw("warp_fit", fit.str());
  }
  json.addRaw("files", files.str());
  if (cl.has("bag")) json.addRaw("bag", bag_json.str());
  std::cout << json.str() << std::endl;
  return 0;
}
