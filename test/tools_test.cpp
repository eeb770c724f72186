// The command-line layer: matrix and flag parsing, PCD/PLY reading, and pda_align run as a user
// runs it (exit codes, one-line errors, the JSON fields, PLY input, a real shared case).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

#include "pda_registration/core/transform_io.hpp"
#include "pda_registration/tools/cloud_io.hpp"
#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/pcd_header.hpp"
#include "test_support/command_run.hpp"
#include "test_support/shared_data.hpp"
#include "test_support/synthetic_scene.hpp"

namespace pda_registration {
namespace {

using testing_support::CommandRun;
using testing_support::jsonNumber;
using testing_support::lineCount;
using testing_support::runCommand;
using testing_support::temporaryPath;

CommandRun runPdaAlign(const std::string& arguments) {
  return runCommand(PDA_ALIGN_BINARY, arguments);
}

void writeAsciiPly(const std::string& path, const PointList& points) {
  std::ofstream ply(path);
  ply << "ply\nformat ascii 1.0\nelement vertex " << points.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (const Point& p : points) ply << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
}

TEST(TransformIo, ParsesRoundTripsAndRejectsMalformedMatrices) {
  Eigen::Isometry3d T;
  std::string error;
  Eigen::Isometry3d original = Eigen::Isometry3d::Identity();
  original.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  original.translation() = Eigen::Vector3d(1, 2, 3);
  ASSERT_TRUE(parseTransform(formatTransform(original), &T, &error)) << error;
  EXPECT_TRUE(T.isApprox(original, 1e-15));
  EXPECT_TRUE(parseTransform("# comment\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1 # last\n", &T, &error));
  EXPECT_FALSE(parseTransform("1 0 0 0 0 1 0 0 0 0 1 0", &T, &error));
  EXPECT_NE(error.find("expected 16 numbers"), std::string::npos);
  EXPECT_FALSE(parseTransform("1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 x", &T, &error));
  EXPECT_NE(error.find("not a number"), std::string::npos);
  EXPECT_FALSE(parseTransform("2 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1", &T, &error));
  EXPECT_NE(error.find("not a rotation"), std::string::npos);
  EXPECT_FALSE(parseTransform("1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1", &T, &error));
  EXPECT_NE(error.find("last row"), std::string::npos);
  EXPECT_FALSE(parseTransform("1 0 0 nan 0 1 0 0 0 0 1 0 0 0 0 1", &T, &error));
  // Found by the initial_transform fuzzer, the same check here: huge finite entries made the
  // orthonormality error Inf - Inf = NaN, which passed "> 1e-3" (regressions/transform_matrix/).
  EXPECT_FALSE(
      parseTransform("2.7e154 -3.4e221 0 0  -3.4e221 -1.7e308 -1.2e217 0 "
                     "-3.4e221 0 -1.7e308 0  0 0 0 1",
                     &T, &error));
  EXPECT_NE(error.find("not a rotation"), std::string::npos) << error;
  EXPECT_FALSE(readTransformFile("/nonexistent/T.txt", &T, &error));
  EXPECT_NE(error.find("cannot open"), std::string::npos);
}

TEST(CommandLine, ParsesAndReportsBadFlags) {
  const char* good[] = {"tool", "--k", "7", "--nu=inf", "--help"};
  CommandLine cl({"k", "nu"}, {"help"});
  ASSERT_TRUE(cl.parse(5, good)) << cl.error();
  int k = 0;
  double nu = 0;
  EXPECT_TRUE(cl.integer("k", &k, 1, 100));
  EXPECT_EQ(k, 7);
  EXPECT_TRUE(cl.number("nu", &nu, 0.0, std::numeric_limits<double>::infinity()));
  EXPECT_TRUE(std::isinf(nu));
  EXPECT_TRUE(cl.has("help"));

  const char* unknown[] = {"tool", "--bogus", "1"};
  CommandLine cl2({"k"}, {});
  EXPECT_FALSE(cl2.parse(3, unknown));
  EXPECT_NE(cl2.error().find("unknown flag '--bogus'"), std::string::npos);

  const char* missing[] = {"tool", "--k"};
  CommandLine cl3({"k"}, {});
  EXPECT_FALSE(cl3.parse(2, missing));

  const char* bad_value[] = {"tool", "--k", "ten"};
  CommandLine cl4({"k"}, {});
  ASSERT_TRUE(cl4.parse(3, bad_value));
  EXPECT_FALSE(cl4.integer("k", &k, 1, 100));
  EXPECT_NE(cl4.error().find("--k: 'ten'"), std::string::npos);

  std::vector<double> list;
  const char* lists[] = {"tool", "--nu", "3,5,inf"};
  CommandLine cl5({"nu"}, {});
  ASSERT_TRUE(cl5.parse(3, lists));
  EXPECT_TRUE(cl5.numberList("nu", &list, 0.0, 1e6, true));
  ASSERT_EQ(list.size(), 3u);
  EXPECT_TRUE(std::isinf(list[2]));
}

// Found by the command_line fuzzer (test/fuzz/regressions/command_line/): a carriage return or
// newline inside an argument was echoed raw, so the "one-line" error spanned or overwrote lines.
TEST(CommandLine, ErrorsEscapeControlCharactersAndStayOneLine) {
  const char* stray[] = {"tool", "-\rtranslation-epsilon"};
  CommandLine cl({"k"}, {});
  EXPECT_FALSE(cl.parse(2, stray));
  EXPECT_EQ(cl.error(), "unexpected argument '-\\rtranslation-epsilon'");

  const char* bad_value[] = {"tool", "--k", "1\n2", "--nu", "3,\x1b[2J"};
  CommandLine cl2({"k", "nu"}, {});
  ASSERT_TRUE(cl2.parse(5, bad_value));
  int k = 0;
  EXPECT_FALSE(cl2.integer("k", &k, 1, 100));
  EXPECT_EQ(cl2.error(), "--k: '1\\n2' is not an integer in [1, 100]");
  std::vector<double> nu;
  EXPECT_FALSE(cl2.numberList("nu", &nu, 0.0, 10.0));
  EXPECT_EQ(cl2.error(), "--nu: '\\x1b[2J' is not a number in [0, 10]");
}

TEST(CloudIo, ReadsPlyAndPcdAndRejectsGarbage) {
  const PointList points = testing_support::makePlane(1.0, 0.1);
  const std::string ply = temporaryPath("plane.ply"), pcd = temporaryPath("plane.pcd");
  writeAsciiPly(ply, points);
  std::string error;
  ASSERT_TRUE(savePointCloudFile(pcd, points, &error)) << error;
  for (const std::string& path : {ply, pcd}) {
    PointList loaded;
    ASSERT_TRUE(loadPointCloudFile(path, &loaded, &error)) << path << ": " << error;
    ASSERT_EQ(loaded.size(), points.size());
    EXPECT_LT((loaded[5] - points[5]).norm(), 1e-6);
  }
  const std::string garbage = temporaryPath("garbage.pcd");
  std::ofstream(garbage) << "this is not a point cloud\n";
  PointList loaded;
  EXPECT_FALSE(loadPointCloudFile(garbage, &loaded, &error));
  EXPECT_NE(error.find("not a readable pcd"), std::string::npos) << error;
  EXPECT_FALSE(loadPointCloudFile(temporaryPath("cloud.xyz"), &loaded, &error));
  EXPECT_FALSE(loadPointCloudFile("/nonexistent.pcd", &loaded, &error));
  EXPECT_NE(error.find("cannot open"), std::string::npos);
}

// Found by review while writing the pcd_header fuzzer, confirmed by its unsigned-overflow check
// (test/fuzz/regressions/pcd_header/): WIDTH x HEIGHT and POINTS x point size wrapped around
// 2^64, so these headers passed as consistent. (PCL 1.13 happens to refuse both itself.)
TEST(PcdHeader, CountsWhoseProductsOverflowAreRefused) {
  std::string error;
  std::istringstream cells_wrap(
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4294967296\nHEIGHT 4294967296\nPOINTS 0\n"
      "DATA binary\n");
  EXPECT_FALSE(checkPcdHeader(cells_wrap, &error));
  EXPECT_EQ(error, "PCD header: WIDTH x HEIGHT does not equal POINTS");
  std::istringstream bytes_wrap(
      "FIELDS x y\nSIZE 8 8\nTYPE F F\nCOUNT 536870912 536870912\nWIDTH 2147483648\nHEIGHT 1\n"
      "POINTS 2147483648\nDATA binary\n");
  EXPECT_FALSE(checkPcdHeader(bytes_wrap, &error));
  EXPECT_EQ(error, "PCD data is shorter than POINTS x point size");
  std::istringstream good(
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n"
      "DATA binary\n" +
      std::string(24, '\0'));
  EXPECT_TRUE(checkPcdHeader(good, &error)) << error;
}

TEST(PdaAlign, UsageErrorsExitWithCodeTwoAndOneLine) {
  const std::string data = testing_support::sharedDataDirectory() + "/room_scan/";
  const std::string clouds = "--target " + data + "target.pcd --source " + data + "source.pcd";
  const std::string bad_matrix = temporaryPath("bad_matrix.txt");
  std::ofstream(bad_matrix) << "1 0 0\n";
  const std::string garbage = temporaryPath("garbage2.pcd");
  std::ofstream(garbage) << "garbage\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--source " + data + "source.pcd", "--target and --source are required"},
      {clouds + " --bogus 3", "unknown flag '--bogus'"},
      {clouds + " --k ten", "--k: 'ten'"},
      {clouds + " --radius -1", "--radius"},
      {clouds + " --method foo", "--method: 'foo'"},
      {clouds + " --method 'a\nb'", "--method: 'a\\nb'"},  // a newline, quoted by the shell
      {clouds + " --solver fast", "--solver: 'fast'"},
      {clouds + " --spread-budget 2", "--spread-budget"},
      {clouds + " --solver closed_form", "closed_form needs surface_anisotropy = 1"},
      {clouds + " --initial " + bad_matrix, "expected 16 numbers"},
      {"--target /nonexistent.pcd --source " + data + "source.pcd", "cannot open"},
      // A path holding a newline is echoed escaped, so the error stays one line.
      {"--target '/nonexistent\n.pcd' --source " + data + "source.pcd",
       "cannot open '/nonexistent\\n.pcd'"},
      {"--target " + garbage + " --source " + data + "source.pcd", "not a readable pcd"},
      {clouds + " --trace --compare icp", "--trace: traces one alignment"},
      {clouds + " --trace --method gicp", "--trace: only PDA's runs"},
  };
  for (const auto& c : cases) {
    const CommandRun run = runPdaAlign(c.first);
    EXPECT_EQ(run.exit_code, 2) << c.first;
    EXPECT_EQ(lineCount(run.err), 1u) << run.err;
    EXPECT_NE(run.err.find(c.second), std::string::npos) << c.first << " -> " << run.err;
    EXPECT_TRUE(run.out.empty());
  }
}

TEST(PdaAlign, AlignsARealCaseAndReportsErrorsAgainstGroundTruth) {
  const std::string data = testing_support::sharedDataDirectory() + "/room_scan/";
  const std::string output = temporaryPath("estimate.txt");
  const CommandRun run =
      runPdaAlign("--target " + data + "target.pcd --source " + data + "source.pcd --initial " +
                  data + "T_target_source.txt" + " --perturb 5,0.25 --seed 3 --ground-truth " +
                  data + "T_target_source.txt --output " + output);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_EQ(lineCount(run.out), 1u);
  EXPECT_NE(run.out.find("\"method\":\"pda\""), std::string::npos);
  EXPECT_NE(run.out.find("\"converged\":true"), std::string::npos);
  for (const char* key :
       {"time_ms", "runs", "sigma", "inlier_fraction", "support_fraction", "mean_distance",
        "rot_err_deg", "trans_err_m", "peak_rss_mb", "expected_error_m", "expected_error_deg",
        "competing_prominence"}) {
    EXPECT_FALSE(std::isnan(jsonNumber(run.out, key))) << key << " missing in " << run.out;
  }
  // No second pose half as prominent as the estimate's in the room (0.5: a competing pose).
  EXPECT_LT(jsonNumber(run.out, "competing_prominence"), 0.5);
  // The covariance's expected error: positive, and of the size of the errors made (room_scan's
  // ground truth is good to ~1 cm / 0.5 deg).
  EXPECT_GT(jsonNumber(run.out, "expected_error_m"), 1e-4);
  EXPECT_LT(jsonNumber(run.out, "expected_error_m"), 0.05);
  EXPECT_GT(jsonNumber(run.out, "expected_error_deg"), 1e-3);
  EXPECT_LT(jsonNumber(run.out, "expected_error_deg"), 1.0);
  EXPECT_LT(jsonNumber(run.out, "mean_distance"), 0.03);
  EXPECT_GT(jsonNumber(run.out, "initial_mean_distance"), 0.2);
  Eigen::Isometry3d written, truth;
  std::string error;
  ASSERT_TRUE(readTransformFile(output, &written, &error)) << error;
  ASSERT_TRUE(readTransformFile(data + "T_target_source.txt", &truth, &error));
  EXPECT_LT((written.translation() - truth.translation()).norm(), 0.03);
}

// --trace: one JSON line per run and per attempt on stderr; stdout keeps its one line. The
// attempt's line carries its estimate and, with a ground truth, its eq. 22 error: the answer's.
TEST(PdaAlign, TracesEveryRunAndAttemptOnStderr) {
  const std::string data = testing_support::sharedDataDirectory() + "/room_scan/";
  const CommandRun run = runPdaAlign(
      "--target " + data + "target.pcd --source " + data + "source.pcd --initial " + data +
      "T_target_source.txt --perturb 5,0.25 --seed 3 --trace --ground-truth " + data +
      "T_target_source.txt");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(lineCount(run.out), 1u);
  const double runs = jsonNumber(run.out, "runs");
  ASSERT_GT(runs, 1.0);
  std::istringstream lines(run.err);
  std::string line;
  int run_lines = 0, attempt_lines = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("{\"trace\":\"run\",\"attempt\":\"first\"", 0) == 0) {
      ++run_lines;
      EXPECT_EQ(jsonNumber(line, "run"), run_lines) << line;
      EXPECT_GT(jsonNumber(line, "sigma"), 0.0) << line;
    } else if (line.rfind("{\"trace\":\"attempt\"", 0) == 0) {
      ++attempt_lines;
      EXPECT_NE(line.find("\"adopted\":true"), std::string::npos) << line;
      EXPECT_EQ(jsonNumber(line, "runs"), runs) << line;
      EXPECT_DOUBLE_EQ(jsonNumber(line, "mean_distance"), jsonNumber(run.out, "mean_distance"));
      EXPECT_LT(jsonNumber(line, "mean_distance"), 0.03) << line;
      EXPECT_NE(line.find("\"T\":["), std::string::npos) << line;
    } else {
      ADD_FAILURE() << "not a trace line: " << line;
    }
  }
  EXPECT_EQ(run_lines, static_cast<int>(runs));
  EXPECT_EQ(attempt_lines, 1);
}

TEST(PdaAlign, ComparesWithPclIcpInOneRun) {
  const std::string data = testing_support::sharedDataDirectory() + "/room_scan/";
  const CommandRun run =
      runPdaAlign("--target " + data + "target.pcd --source " + data + "source.pcd --initial " +
                  data + "T_target_source.txt --ground-truth " + data +
                  "T_target_source.txt --compare icp --repeat 1");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_GT(jsonNumber(run.out, "icp_ms"), 0.0);
  EXPECT_GT(jsonNumber(run.out, "pda_over_icp"), 0.0);
  EXPECT_FALSE(std::isnan(jsonNumber(run.out, "icp_mean_distance")));
}

TEST(PdaAlign, ReadsPlyAndRecoversTheSyntheticTransform) {
  const testing_support::SyntheticCase room =
      testing_support::makeSyntheticRoom(testing_support::SyntheticOptions());
  const std::string target = temporaryPath("room_target.ply");
  const std::string source = temporaryPath("room_source.ply");
  const std::string truth = temporaryPath("room_truth.txt");
  writeAsciiPly(target, room.target);
  writeAsciiPly(source, room.source);
  std::string error;
  ASSERT_TRUE(writeTransformFile(truth, room.T_target_source, &error));
  const CommandRun run =
      runPdaAlign("--target " + target + " --source " + source + " --initial " + truth +
                  " --perturb 3,0.15 --radius 0.5 --ground-truth " + truth);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_LT(jsonNumber(run.out, "mean_distance"), 0.015);  // measured 1.005 cm
}

TEST(PdaAlign, RunsPclMethodsOnTheSameInputs) {
  const std::string data = testing_support::sharedDataDirectory() + "/room_scan/";
  const CommandRun run =
      runPdaAlign("--target " + data + "target.pcd --source " + data + "source.pcd --initial " +
                  data + "T_target_source.txt --method icp");
  EXPECT_NE(run.out.find("\"method\":\"icp\""), std::string::npos) << run.out << run.err;
  EXPECT_TRUE(run.exit_code == 0 || run.exit_code == 1);
}

}  // namespace
}  // namespace pda_registration
