// The index that is updated, not rebuilt: queries answer exactly the k nearest points within the
// radius (checked against brute force, ties included, with or without hints), an index extended
// by appended points gives the same candidate sets, normal map and registration result as one
// rebuilt from scratch, and a 1M-point map that grows by 5 % is updated in about the cost of its
// new points; an index folded into one tree while it is queried answers the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <thread>

#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/surface_normals.hpp"
#include "pda_registration/core/target_index.hpp"
#include "pda_registration/core/target_map.hpp"
#include "pda_registration/tools/tiled_map.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// A cloud with many exact ties: points on a 5 cm grid (plus duplicates) and random points.
PointList cloudWithTies(size_t random_points, unsigned seed) {
  PointList points;
  for (int x = 0; x < 40; ++x)
    for (int y = 0; y < 40; ++y) points.emplace_back(0.05 * x, 0.05 * y, 0.0);
  for (int i = 0; i < 200; ++i) points.push_back(points[static_cast<size_t>(i * 7)]);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(-0.5, 2.5);
  for (size_t i = 0; i < random_points; ++i)
    points.emplace_back(coordinate(random), coordinate(random), 0.1 * coordinate(random));
  return points;
}

// `count` source points over the grid's area; with `ties`, every third exactly on a grid point or
// half-way between two.
PointList sourceOverTheGrid(int count, unsigned seed, bool ties) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(-0.2, 2.2), height(-0.05, 0.05);
  PointList source;
  for (int i = 0; i < count; ++i) {
    if (ties && i % 3 == 0) {
      source.emplace_back(0.05 * (i % 40) + 0.025 * (i % 2), 0.05 * ((i / 40) % 40), 0.0);
    } else {
      source.emplace_back(coordinate(random), coordinate(random), height(random));
    }
  }
  return source;
}

void expectSameCandidates(const CandidateSets& a, const CandidateSets& b) {
  ASSERT_EQ(a.offsets, b.offsets);
  ASSERT_EQ(a.target_indices, b.target_indices);
  for (size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << i;
}

TEST(TargetIndex, AnswersExactlyTheKNearestWithinRadiusTiesByIndex) {
  const PointList points = cloudWithTies(20000, 1);
  const std::shared_ptr<const TargetIndex> base =
      std::make_shared<const TargetIndex>(PointList(points.begin(), points.begin() + 9000));
  // Extended twice: three trees (or merged ones), the same answers.
  const auto extended = TargetIndex::extended(
      TargetIndex::extended(base, PointList(points.begin(), points.begin() + 15000)), points);
  EXPECT_TRUE(extended->extends(*base));
  const TargetIndex rebuilt(points);
  std::mt19937 random(2);
  std::uniform_real_distribution<double> coordinate(-0.6, 2.6);
  const int k = 7;
  for (int q = 0; q < 3000; ++q) {
    // Half the queries on grid points and half-way between them: exact ties in distance.
    const Point query =
        q % 2 ? Point(0.05 * (q % 40) + 0.025 * (q % 3), 0.05 * ((q / 40) % 40), 0.0)
              : Point(coordinate(random), coordinate(random), 0.0);
    const double radius = q % 3 == 0 ? 0.05 : 0.3;
    std::vector<std::pair<double, size_t>> brute;
    for (size_t i = 0; i < points.size(); ++i) {
      const double d = (points[i] - query).squaredNorm();
      if (d < radius * radius) brute.emplace_back(d, i);
    }
    std::sort(brute.begin(), brute.end());
    brute.resize(std::min<size_t>(brute.size(), k));
    // Hints (the last run's answers) change nothing: the right ones, wrong ones, duplicates and
    // indices beyond the cloud.
    std::vector<size_t> hints = {points.size() + 3, static_cast<size_t>(q) % points.size()};
    for (auto it = brute.rbegin(); it != brute.rend(); ++it) hints.push_back(it->second);
    if (!brute.empty()) hints.push_back(brute.front().second);
    for (const TargetIndex* index : {extended.get(), &rebuilt}) {
      for (const bool hinted : {false, true}) {
        size_t indices[k];
        double distances[k];
        const size_t found = index->nearestWithinRadius(query, k, radius, indices, distances,
                                                        hinted ? hints.data() : nullptr,
                                                        hinted ? hints.size() : 0);
        ASSERT_EQ(found, brute.size()) << "query " << q;
        for (size_t i = 0; i < found; ++i) {
          EXPECT_EQ(indices[i], brute[i].second) << "query " << q;
          EXPECT_EQ(distances[i], brute[i].first) << "query " << q;
        }
      }
    }
  }
}

// Run after run, the search answers a point that moved little from the target points it kept
// (candidate_sets.cpp): the candidates must be exactly a fresh search's, through moves from
// centimetres to micrometres, a radius that shrinks and grows again, exact ties in distance, and
// new source values in the same memory after forget().
TEST(CandidateSets, AnswersFromKeptPointsEqualAFreshSearch) {
  const TargetIndex target(cloudWithTies(20000, 3));
  PointList source = sourceOverTheGrid(3000, 4, /*ties=*/true);
  CandidateSearchBuffers buffers;
  CandidateSets reused;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  size_t from_kept = 0;
  const double radii[] = {0.3, 0.3, 0.1, 0.1, 0.05, 0.05, 0.3, 0.02, 0.3, 0.3};
  int call = 0;
  for (const bool renew_source : {false, true}) {
    if (renew_source) {  // the same memory, other values: only forget() makes this safe
      for (Point& p : source) p += Point(0.013, -0.007, 0.001);
      buffers.forget();
    }
    for (double move = 1e-2; move > 1e-7; move *= 0.3, ++call) {
      T = T * randomPerturbation(move * 20.0, move, static_cast<uint64_t>(call + 1));
      const double radius = radii[call % 10];
      findCandidateSets(target, source, T, 5, radius, 2, &buffers, &reused);
      const CandidateSets fresh = findCandidateSets(target, source, T, 5, radius, 1);
      expectSameCandidates(reused, fresh);
      if (call == 0 || (renew_source && move == 1e-2)) {
        EXPECT_EQ(buffers.answered_from_kept, 0u);
      }
      from_kept += buffers.answered_from_kept;
    }
  }
  // Not vacuous: most answers of the small moves came from the kept points.
  EXPECT_GT(from_kept, 3000u * 10);
}

// The approach's answers for its subset carry over to the whole source (the settle stage's first
// run): the subset's points are answered from their kept target points, exactly as a fresh search,
// and the others are searched; answers for other points, or a "subset" out of order, carry nothing.
TEST(CandidateSets, SubsetAnswersCarryOverToTheWholeSourceExactly) {
  const TargetIndex target(cloudWithTies(20000, 5));
  PointList source = sourceOverTheGrid(2000, 6, /*ties=*/false);
  source.push_back(source[10]);  // an exact duplicate, in the subset only as its last point
  PointList subset;
  for (size_t i = 0; i < source.size(); i += 4) subset.push_back(source[i]);
  const Eigen::Isometry3d T_subset = randomPerturbation(1.0, 0.02, 7);
  const Eigen::Isometry3d T_whole = T_subset * randomPerturbation(0.01, 0.0005, 8);

  CandidateSearchBuffers buffers;
  CandidateSets sets;
  findCandidateSets(target, subset, T_subset, 5, 0.3, 1, &buffers, &sets);
  buffers.carryToSuperset(subset, source);
  findCandidateSets(target, source, T_whole, 5, 0.3, 2, &buffers, &sets);
  expectSameCandidates(sets, findCandidateSets(target, source, T_whole, 5, 0.3, 1));
  // Most of the subset's points, and nothing else, were answered without a search.
  EXPECT_GT(buffers.answered_from_kept, subset.size() * 9 / 10);
  EXPECT_LE(buffers.answered_from_kept, subset.size());

  // Answers for other points than the subset: nothing carries, every point is searched.
  findCandidateSets(target, subset, T_subset, 5, 0.3, 1, &buffers, &sets);
  buffers.carryToSuperset(source, source);
  findCandidateSets(target, source, T_whole, 5, 0.3, 1, &buffers, &sets);
  EXPECT_EQ(buffers.answered_from_kept, 0u);
  // A subset out of the whole's order: nothing carries either.
  PointList shuffled = subset;
  std::reverse(shuffled.begin(), shuffled.end());
  findCandidateSets(target, shuffled, T_subset, 5, 0.3, 1, &buffers, &sets);
  buffers.carryToSuperset(shuffled, source);
  findCandidateSets(target, source, T_whole, 5, 0.3, 1, &buffers, &sets);
  EXPECT_EQ(buffers.answered_from_kept, 0u);
  expectSameCandidates(sets, findCandidateSets(target, source, T_whole, 5, 0.3, 1));
}

TEST(TargetIndex, ExtendedEqualsRebuiltOnARealGrowingMap) {
  testing_support::SharedCase factory;
  std::string error;
  ASSERT_TRUE(testing_support::loadSharedCase("factory_p64", &factory, &error)) << error;
  const PointList map = factory.target;
  // The map "grows" in 10 steps (the binary-counter merges happen along the way).
  std::shared_ptr<const TargetIndex> index;
  SurfaceNormalMap normals;
  for (int step = 1; step <= 10; ++step) {
    PointList prefix(map.begin(), map.begin() + static_cast<long>(map.size() * step / 10));
    if (!index) {
      normals = SurfaceNormalMap(prefix, 0.15);
      index = std::make_shared<const TargetIndex>(std::move(prefix));
    } else {
      const size_t from = index->size();
      ASSERT_TRUE(index->sharesPrefix(prefix));
      index = TargetIndex::extended(index, std::move(prefix));
      normals.add(index->points(), from);
    }
  }
  EXPECT_GT(index->trees(), 1u);
  const TargetIndex rebuilt(map);
  const SurfaceNormalMap rebuilt_normals(map, 0.15);
  const Eigen::Isometry3d T = factory.T_target_source * randomPerturbation(3.0, 0.15, 5);
  for (const double radius : {1.0, 0.25}) {
    expectSameCandidates(findCandidateSets(*index, factory.source, T, 5, radius, 2),
                         findCandidateSets(rebuilt, factory.source, T, 5, radius, 1));
  }
  EXPECT_EQ(normals.voxelsWithNormal(), rebuilt_normals.voxelsWithNormal());
  // Normals set, replaced and removed as points arrive: the extended map answers as the rebuilt
  // one, on the map and off it.
  for (size_t i = 0; i < map.size(); i += 7) {
    ASSERT_EQ(normals.normalAt(map[i]), rebuilt_normals.normalAt(map[i])) << i;
  }
  for (const Point& p : factory.source) {
    ASSERT_EQ(normals.normalAt(T * p), rebuilt_normals.normalAt(T * p));
  }
}

TEST(TargetIndex, FoldedWhileQueriedAnswersTheSameAndIsExtendedFromOneTree) {
  testing_support::SharedCase factory;
  std::string error;
  ASSERT_TRUE(testing_support::loadSharedCase("factory_p64", &factory, &error)) << error;
  const PointList& map = factory.target;
  std::shared_ptr<const TargetIndex> index;
  for (int step = 1; step <= 7; ++step) {
    index = TargetIndex::extended(
        index, PointList(map.begin(), map.begin() + static_cast<long>(map.size() * step / 10)));
  }
  ASSERT_EQ(index->trees(), 3u);  // 7 steps: trees of 4, 2 and 1 steps (binary counter)
  const Eigen::Isometry3d T = factory.T_target_source * randomPerturbation(3.0, 0.15, 5);
  const CandidateSets before = findCandidateSets(*index, factory.source, T, 5, 1.0, 1);
  // A cancelled fold changes nothing.
  const std::atomic<bool> cancel{true};
  EXPECT_FALSE(index->fold(&cancel));
  EXPECT_EQ(index->trees(), 3u);
  // Queries go on while another thread folds: the same answers before, during and after.
  std::thread folder([&] { EXPECT_TRUE(index->fold()); });
  for (int i = 0; i < 3; ++i) {
    expectSameCandidates(findCandidateSets(*index, factory.source, T, 5, 1.0, 2), before);
  }
  folder.join();
  EXPECT_EQ(index->trees(), 1u);
  EXPECT_FALSE(index->fold());  // once
  expectSameCandidates(findCandidateSets(*index, factory.source, T, 5, 1.0, 2), before);
  // Extended from the fold: its one tree plus the new points' tree, answering like a rebuild.
  const auto grown = TargetIndex::extended(index, map);
  EXPECT_EQ(grown->trees(), 2u);
  EXPECT_EQ(grown->pointsLastIndexed(), map.size() - index->size());
  EXPECT_TRUE(grown->extends(*index));
  const TargetIndex rebuilt(map);
  for (const double radius : {1.0, 0.25}) {
    expectSameCandidates(findCandidateSets(*grown, factory.source, T, 5, radius, 2),
                         findCandidateSets(rebuilt, factory.source, T, 5, radius, 1));
  }
}

TEST(TargetMap, GrowingMapIsExtendedAndRegistersExactlyLikeARebuild) {
  testing_support::SharedCase room;
  std::string error;
  ASSERT_TRUE(testing_support::loadSharedCase("room_scan", &room, &error)) << error;
  const size_t half = room.target.size() / 2;
  // Indexed by setTarget, as the nodelet's keeper does (it thins a map itself, so that its index
  // can be extended; target_subset would index voxel means afresh).
  RegistrationParameters p;
  p.target_subset = false;
  PdaRegistration growing(p);
  ASSERT_TRUE(growing.setTarget(PointList(room.target.begin(), room.target.begin() + half)));
  const auto first = growing.target();
  ASSERT_TRUE(growing.setTarget(room.target));
  ASSERT_TRUE(growing.target()->extends(*first));
  PdaRegistration rebuilt(p);
  ASSERT_TRUE(rebuilt.setTarget(room.target));
  const Eigen::Isometry3d seed = room.T_target_source * randomPerturbation(3.0, 0.15, 9);
  const RegistrationResult a = growing.align(room.source, seed);
  const RegistrationResult b = rebuilt.align(room.source, seed);
  ASSERT_TRUE(a.converged) << a.reason;
  EXPECT_TRUE(a.T_target_source.isApprox(b.T_target_source, 0.0));
  EXPECT_EQ(a.runs, b.runs);
  EXPECT_EQ(a.sigma, b.sigma);
  // A different map (not a continuation) is indexed afresh, the same way.
  PointList moved = room.target;
  for (Point& p : moved) p.x() += 0.01;
  ASSERT_TRUE(growing.setTarget(moved));
  EXPECT_FALSE(growing.target()->extends(*first));
}

TEST(TargetMap, OneMillionPointsPlusFivePercentInAFifthOfTheBuild) {
  testing_support::SharedCase factory;
  std::string error;
  ASSERT_TRUE(testing_support::loadSharedCase("factory_p64", &factory, &error)) << error;
  const PointList tiles =
      tileCloud(factory.target, 3, 1, separatedTileSpacing(factory.target)).points;
  ASSERT_GE(tiles.size(), 1050000u);
  // The update's cost relative to building the map (a ratio, not milliseconds: a shared or slow
  // machine moved the update from 37 to 75 ms, with the build moving alike; the benchmark
  // measures times). A rebuild would be about 1. The best of up to three trials, each on a
  // freshly built map.
  double best_ratio = 1e9;
  for (int trial = 0; trial < 3 && best_ratio >= 0.2; ++trial) {
    TargetMap map;
    TargetIndexing indexing;  // whole-map index (no cropping)
    auto start = std::chrono::steady_clock::now();
    ASSERT_TRUE(map.setCloud(PointList(tiles.begin(), tiles.begin() + 1000000)));
    ASSERT_TRUE(map.prepare(indexing, AlignedBox()));
    const double build_ms = msSince(start);
    PointList grown(tiles.begin(), tiles.begin() + 1050000);
    start = std::chrono::steady_clock::now();
    ASSERT_TRUE(map.setCloud(std::move(grown)));
    const double update_ms = msSince(start);
    EXPECT_EQ(map.lastUpdate(), TargetUpdate::kExtended);
    EXPECT_EQ(map.lastAppended(), 50000u);
    EXPECT_EQ(map.index()->size(), 1050000u);
    EXPECT_EQ(map.index()->pointsLastIndexed(), 50000u);
    std::cout << "1M-point map: built in " << build_ms << " ms; +5 % (50k points) in "
              << update_ms << " ms (setCloud: filtering, prefix check, index and normals)"
              << std::endl;
    best_ratio = std::min(best_ratio, update_ms / build_ms);
  }
  EXPECT_LT(best_ratio, 0.2);
}

}  // namespace
}  // namespace pda_registration
