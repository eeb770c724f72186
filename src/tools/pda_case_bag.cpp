// pda_case_bag: turns a case folder (target.pcd|ply, source.pcd|ply, T_target_source.txt; e.g.
// ../shared/data/campus_hdl32) into a rosbag for replay through the nodelet, in the same layout
// pda_simulate writes: /dense_map, /sparse_map, /tf (a seed dense_map -> sparse_map perturbed from
// the ground truth) and /ground_truth. Prints one JSON line; exit 2 on bad usage or input.

#include <iostream>

#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/simulation/map_bag_writer.hpp"
#include "pda_registration/tools/case_folder.hpp"
#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/json_line.hpp"

using namespace pda_registration;

namespace {

const char* kUsage =
    "usage: pda_case_bag --case DIR --bag FILE [options]\n"
    "  --seed-error-deg D    rotation error of the tf seed (3)\n"
    "  --seed-error-m M      translation error of the tf seed (0.15)\n"
    "  --seed N              perturbation seed (1)\n"
    "  --sparse-messages N   sparse maps in the bag, at 1 Hz (5)\n"
    "  --help\n";

int fail(const std::string& message) { return reportError("pda_case_bag", message); }

}  // namespace

int main(int argc, char** argv) {
  CommandLine cl({"case", "bag", "seed-error-deg", "seed-error-m", "seed", "sparse-messages"},
                 {"help"});
  if (!cl.parse(argc, argv)) return fail(cl.error());
  if (cl.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  if (!cl.has("case") || !cl.has("bag")) return fail("--case and --bag are required");
  double degrees = 3.0, metres = 0.15;
  int seed = 1;
  simulation::MapBagOptions options;
  if (!cl.number("seed-error-deg", &degrees, 0.0, 180.0) ||
      !cl.number("seed-error-m", &metres, 0.0, 1e3) || !cl.integer("seed", &seed, 0, 1 << 30) ||
      !cl.integer("sparse-messages", &options.sparse_messages, 1, 100)) {
    return fail(cl.error());
  }
  CaseFolder loaded;
  std::string error;
  if (!loadCaseFolder(cl.text("case"), &loaded, &error)) return fail(error);
  const PointList& target = loaded.target;
  const PointList& source = loaded.source;
  const Eigen::Isometry3d truth = loaded.T_target_source;
  const Eigen::Isometry3d seed_transform = truth * randomPerturbation(degrees, metres, seed);
  simulation::MapBagSummary summary;
  if (!simulation::writeMapBag(cl.text("bag"), target, source, truth, seed_transform, options,
                               &summary, &error)) {
    return fail(error);
  }
  JsonLine json;
  json.add("case", cl.text("case")).add("bag", cl.text("bag"));
  json.add("dense_points", target.size()).add("sparse_points", source.size());
  json.add("sparse_messages", summary.sparse_messages).add("duration_s", summary.duration);
  json.add("seed_error_deg", degrees).add("seed_error_m", metres);
  std::cout << json.str() << std::endl;
  return 0;
}
