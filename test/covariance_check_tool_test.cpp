// pda_covariance_check as a user runs it: the table's row for factory_p64 (exact ground truth)
// within the range for real cases, noise draws pooled into one row, and a bad flag is one
// line and exit code 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "test_support/command_run.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::CommandRun;
using testing_support::lineCount;
using testing_support::runCommand;
using testing_support::temporaryPath;

std::vector<std::string> tableCells(const std::string& row) {
  std::vector<std::string> cells;
  std::istringstream in(row);
  std::string cell;
  while (std::getline(in, cell, '|')) {
    const size_t first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
    if (first != std::string::npos) cells.push_back(cell.substr(first, last - first + 1));
  }
  return cells;
}

// The cells of `name`'s row in pda_covariance_check's table; empty when there is no such row.
std::vector<std::string> tableRow(const std::string& out, const std::string& name) {
  const size_t start = out.find("| " + name + " |");
  if (start == std::string::npos) return {};
  return tableCells(out.substr(start, out.find('\n', start) - start));
}

TEST(PdaCovarianceCheck, FactoryErrorIsWithinAThirdToThreeTimesSigma) {
  const CommandRun run =
      runCommand(PDA_COVARIANCE_CHECK_BINARY, "--data " + testing_support::sharedDataDirectory() +
                                                  " --cases factory_p64 --trials 5 --bounds 0.3:3");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<std::string> cells = tableRow(run.out, "factory_p64");
  ASSERT_EQ(cells.size(), 12u) << run.out;
  EXPECT_EQ(cells[2], "5/5");
  for (int column : {5, 8}) {  // translation and rotation |error| / sigma
    const double ratio = std::stod(cells[column]);
    EXPECT_GE(ratio, 0.3) << run.out;
    EXPECT_LE(ratio, 3.0) << run.out;
  }
  EXPECT_EQ(cells[9], "yes");
  // How often a calibrated covariance would miss [0.3, 3] on this row: one error, one figure.
  ASSERT_NE(cells[10].find(" %"), std::string::npos) << cells[10];
  EXPECT_EQ(cells[10].find('/'), std::string::npos) << cells[10];
  const double chance = std::stod(cells[10]);
  EXPECT_GT(chance, 0.0);
  EXPECT_LT(chance, 50.0);
  EXPECT_NE(run.out.find("Rows outside [0.3, 3]: 0 of 1. A calibrated covariance would put "),
            std::string::npos)
      << run.out;
}

// Folders NAME_draw1, NAME_draw2 (noise draws of one scene) are one row NAME over all their
// trials, and the last line pools every trial; here two links to factory_p64, 2 perturbations
// each.
TEST(PdaCovarianceCheck, PoolDrawsMakesOneRowOfAllDraws) {
  const std::string data = temporaryPath("covariance_draws");
  std::filesystem::remove_all(data);
  std::filesystem::create_directories(data);
  const std::string factory = testing_support::sharedDataDirectory() + "/factory_p64";
  std::filesystem::create_directory_symlink(factory, data + "/factory_draw1");
  std::filesystem::create_directory_symlink(factory, data + "/factory_draw2");
  const CommandRun run =
      runCommand(PDA_COVARIANCE_CHECK_BINARY, "--data " + data + " --pool-draws --trials 2");
  std::filesystem::remove_all(data);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out.find("factory_draw"), std::string::npos) << run.out;
  const std::vector<std::string> cells = tableRow(run.out, "factory");
  ASSERT_EQ(cells.size(), 12u) << run.out;
  EXPECT_EQ(cells[2], "4/4");
  // The pooled line counts the same trials.
  EXPECT_NE(run.out.find("Pooled over 4 converged trials"), std::string::npos) << run.out;
  // Two draws: the odds of a miss as one error and as the median of two independent ones, which
  // must both be out (less likely).
  const size_t slash = cells[10].find(" / ");
  ASSERT_NE(slash, std::string::npos) << cells[10];
  EXPECT_LT(std::stod(cells[10].substr(slash + 3)), std::stod(cells[10])) << cells[10];
  EXPECT_NE(run.out.find("if its draws erred independently"), std::string::npos) << run.out;
}

TEST(PdaCovarianceCheck, BadBoundsAreOneLineAndExitCodeTwo) {
  const CommandRun run =
      runCommand(PDA_COVARIANCE_CHECK_BINARY,
                 "--data " + testing_support::sharedDataDirectory() + " --bounds 2:1");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(lineCount(run.err), 1u);
  EXPECT_NE(run.err.find("pda_covariance_check: error: --bounds"), std::string::npos) << run.err;
  EXPECT_TRUE(run.out.empty());
}

}  // namespace
}  // namespace pda_registration
