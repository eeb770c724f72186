#pragma once
// Simulated cases shared by the tests: a small office, the lidar car park and its same-sensor
// lattice, and one alignment from a perturbed ground truth.

#include <cstdint>

#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/simulation/map_simulation.hpp"

namespace pda_registration {
namespace testing_support {

/// The office from 3 Kinect frames and one VLP-16 revolution: small but complete maps, quick to
/// simulate (pda_simulate --seed N --kinect-frames 3 --velodyne-revolutions 1).
simulation::MapSimulationOptions smallOfficeOptions(uint64_t seed);

/// Two hand-held RGB-D fragments of the office (pda_simulate --seed N --sparse-sensor kinect
/// [--distortion D]): the dense one warped by `distortion` (its ground truth then the warp's
/// least-squares rigid fit over the overlap).
simulation::MapSimulationOptions rgbdFragmentOptions(uint64_t seed, double distortion = 0.0);

/// rgbdFragmentOptions(seed) with fragments that each scan 40 % of the walkway, so that they
/// share about a third of the scene (pda_simulate ... --fragment-length 0.4; docs/benchmark.md,
/// "RGB-D fragments that share less").
simulation::MapSimulationOptions lowOverlapFragmentOptions(uint64_t seed);

/// The car park scanned by lidars only (maps kept whole, as pda_simulate keeps lidar maps).
simulation::MapSimulationOptions carParkOptions(simulation::DenseSensor dense_sensor,
                                                bool same_pose);

/// Single revolutions in the car park of `seed` (scripts/benchmark_scan_pairs): one of
/// `dense_sensor` as the map, `dense_offset` (x, y [m], yaw [deg]) from one VLP-16 revolution, the
/// scan in its sensor's frame, as a real scan is.
simulation::MapSimulationOptions scanPairOptions(simulation::DenseSensor dense_sensor,
                                                 uint64_t seed,
                                                 const Eigen::Vector3d& dense_offset);

/// A static 64-beam lidar in a car park: the dense map is four revolutions of it, the sparse map
/// one more revolution cut to 11 rings: every sparse return lies on the dense map's lattice.
/// Simulated once per test program.
const simulation::SimulatedMaps& latticeMaps();

/// Aligns maps.sparse to maps.dense from the ground truth perturbed by `degrees` / `metres`
/// (seeded); returns eq. 22's error against the ground truth and the result in *out.
double alignedError(const simulation::SimulatedMaps& maps, const RegistrationParameters& parameters,
                    double degrees, double metres, uint64_t seed, RegistrationResult* out);

}  // namespace testing_support
}  // namespace pda_registration
