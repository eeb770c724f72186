// pda_covariance_check: does the reported covariance match the error PDA actually makes? For every
// case of a data directory, from fixed-seed perturbations of the ground truth, it aligns with PDA
// and compares the error with the reported standard deviation, sigma = sqrt(trace) of the
// covariance's translation and rotation blocks. Prints a markdown table of the medians of
// |error| / sigma over the converged trials (1 is a calibrated covariance; above 1 it is
// over-confident) and can write every trial as CSV. Exit 2 on bad arguments or unreadable data.
//
// The perturbations of one pair converge to nearly the same pose, so one pair's row is one draw of
// the error. --pool-draws pools folders NAME_draw1, NAME_draw2, ... (one simulated scene with
// independent draws of its sensor noise: pda_simulate --noise-seed) into one row NAME, whose
// median is then over independent errors.
//
// Even a calibrated covariance puts one error outside a range of |error| / sigma now and then, the
// more often the more one direction holds its variance (calibration_odds.hpp). Each row says how
// often ("outside by chance": if the row were one error, and, for pooled draws, if their errors
// were independent; a scene's draws share most of theirs), and a line under the table how many
// rows a calibrated covariance would put outside and how likely as many as found are.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/tools/calibration_odds.hpp"
#include "pda_registration/tools/case_folder.hpp"
#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/method_runner.hpp"
#include "pda_registration/tools/perturbation_levels.hpp"
#include "pda_registration/tools/settings_flags.hpp"
#include "pda_registration/tools/statistics.hpp"

using namespace pda_registration;

namespace {

const char* kUsage =
    "usage: pda_covariance_check --data DIR [options]\n"
    "  DIR holds one folder per case with target.pcd|ply, source.pcd|ply, T_target_source.txt.\n"
    "  --cases A,B            only these cases (all folders in DIR)\n"
    "  --levels D:M,...       perturbation levels, degrees:metres (5:0.25)\n"
    "  --trials N             perturbations per level (5)\n"
    "  --seed N               first perturbation seed (1)\n"
    "  --bounds LO:HI         the accepted range of median |error| / sigma (0.5:2)\n"
    "  --csv FILE             write every trial\n"
    "  --pool-draws           one row for the folders NAME_draw1, NAME_draw2, ... (independent\n"
    "                         noise draws of one scene): the median over all their trials\n"
    "  The error is taken in the covariance's own convention: translation t_est - t_true,\n"
    "  rotation the angle of R_est R_true^T; sigma is sqrt(trace) of the matching 3x3 block.\n";

struct Trial {
  std::string case_name;
  std::string row;  // the table row it counts in: the case, or its scene with --pool-draws
  PerturbationLevel level;
  int seed = 0;
  bool converged = false;
  double translation_error = 0.0, translation_sigma = 0.0;  // [m]
  double rotation_error = 0.0, rotation_sigma = 0.0;        // [rad]
  double covariance_share = 0.0;  // the covariance's time / the alignment's
  // The eigenvalues of the covariance's translation and rotation blocks, each over their sum:
  // how the variance is shared between directions.
  Eigen::Vector3d translation_shares = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation_shares = Eigen::Vector3d::Zero();
};

int fail(const std::string& message) { return reportError("pda_covariance_check", message); }

// The median of |error| / sigma over trials with a sigma; NaN when there is none.
double medianRatio(const std::vector<double>& errors, const std::vector<double>& sigmas) {
  std::vector<double> ratios;
  for (size_t i = 0; i < errors.size(); ++i) {
    if (sigmas[i] > 0.0) ratios.push_back(errors[i] / sigmas[i]);
  }
  return ratios.empty() ? std::nan("") : median(ratios);
}

// The eigenvalues of a 3x3 covariance block over their sum (zero for a zero block).
Eigen::Vector3d varianceShares(const Eigen::Matrix3d& block) {
  const Eigen::Vector3d values =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(block, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .cwiseMax(0.0);
  return values.sum() > 0.0 ? Eigen::Vector3d(values / values.sum()) : Eigen::Vector3d::Zero();
}

// How often a calibrated covariance would miss the rows: per row the odds as one error and as
// the median of its draws' independent errors, and how many rows are out.
struct MissOdds {
  std::vector<double> as_one_error, as_independent_draws;
  size_t rows_outside = 0;
};

// A row's odds of a miss on either block (the variance shared between directions as in its
// trials: `t_shares`, `r_shares` summed over them), recorded in `odds`; the table's cell.
std::string rowMissOdds(const Eigen::Vector3d& t_shares, const Eigen::Vector3d& r_shares,
                        size_t draws, double low, double high, bool outside, MissOdds* odds) {
  const OutsideOdds t = calibratedOutsideOdds(t_shares, low, high);
  const OutsideOdds r = calibratedOutsideOdds(r_shares, low, high);
  const double one = 1.0 - (1.0 - t.either()) * (1.0 - r.either());
  const double independent = 1.0 - (1.0 - t.medianOf(draws)) * (1.0 - r.medianOf(draws));
  odds->as_one_error.push_back(one);
  odds->as_independent_draws.push_back(independent);
  if (outside) ++odds->rows_outside;
  std::ostringstream text;
  text << std::fixed << std::setprecision(0) << 100.0 * one << " %";
  if (draws > 1) text << " / " << 100.0 * independent << " %";
  return text.str();
}

// The line under the table: rows out, and how many a calibrated covariance would put out on
// average. A row outside the range is evidence against the covariance only where that is
// unlikely.
void printMissCount(const MissOdds& odds, double low, double high) {
  if (odds.as_one_error.empty()) return;
  double one = 0.0, independent = 0.0;
  for (size_t i = 0; i < odds.as_one_error.size(); ++i) {
    one += odds.as_one_error[i];
    independent += odds.as_independent_draws[i];
  }
  const auto asMany = [&](const std::vector<double>& probabilities) {
    std::ostringstream text;
    if (odds.rows_outside > 0) {
      text << " (" << odds.rows_outside << " or more with probability " << std::fixed
           << std::setprecision(2) << chanceOfAtLeast(probabilities, odds.rows_outside) << ")";
    }
    return text.str();
  };
  std::cout << "\nRows outside [" << low << ", " << high << "]: " << odds.rows_outside << " of "
            << odds.as_one_error.size() << ". A calibrated covariance would put " << std::fixed
            << std::setprecision(1) << one << " outside on average if each row were one error"
            << asMany(odds.as_one_error);
  if (independent != one) {
    std::cout << ", " << std::setprecision(1) << independent << " if its draws erred independently"
              << asMany(odds.as_independent_draws);
  }
  std::cout << ".\n";
}

std::string ratioText(double ratio) {
  if (std::isnan(ratio)) return "-";
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << ratio;
  return text.str();
}

// "NAME_drawK" -> "NAME" (K digits); any other name is its own row.
std::string pooledName(const std::string& name) {
  const size_t at = name.rfind("_draw");
  if (at == std::string::npos || at == 0 || at + 5 == name.size()) return name;
  for (size_t i = at + 5; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return name;
  }
  return name.substr(0, at);
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cl = commandLineWithSettings(
      {"data", "cases", "levels", "trials", "seed", "bounds", "csv"}, {"pool-draws"});
  MethodSettings settings;
  const int exit_code =
      startRegistrationTool("pda_covariance_check", kUsage, argc, argv, &cl, &settings);
  if (exit_code >= 0) return exit_code;
  if (!cl.has("data")) return fail("--data is required");
  int trials = 5, first_seed = 1;
  if (!cl.integer("trials", &trials, 1, 100000) || !cl.integer("seed", &first_seed, 0, 1 << 30)) {
    return fail(cl.error());
  }
  std::vector<PerturbationLevel> levels;
  std::string bad;
  if (!parsePerturbationLevels(cl.text("levels", "5:0.25"), &levels, &bad)) {
    return fail("--levels: '" + bad + "' is not DEGREES:METRES");
  }
  const std::vector<std::string> bounds_text = splitList(cl.text("bounds", "0.5:2"), ':');
  double low = 0.0, high = 0.0;
  if (bounds_text.size() != 2 || !parseNumber(bounds_text[0], &low, false) ||
      !parseNumber(bounds_text[1], &high, false) || !(low > 0.0) || !(high >= low)) {
    return fail("--bounds: '" + cl.text("bounds") + "' is not LO:HI with 0 < LO <= HI");
  }
  const std::string data = cl.text("data");
  std::vector<std::string> cases = splitList(cl.text("cases"), ',');
  if (cases.empty()) cases = listCaseFolders(data);
  if (cases.empty()) return fail("no cases found in '" + data + "'");
  const bool pool = cl.has("pool-draws");
  std::vector<std::string> rows;  // in the order of their first case
  for (const std::string& name : cases) {
    const std::string row = pool ? pooledName(name) : name;
    if (std::find(rows.begin(), rows.end(), row) == rows.end()) rows.push_back(row);
  }

  std::vector<Trial> all;
  for (const std::string& name : cases) {
    CaseFolder loaded;
    std::string error;
    if (!loadCaseFolder(data + "/" + name, &loaded, &error)) {
      return fail("case '" + name + "': " + error);
    }
    const Eigen::Isometry3d truth = loaded.T_target_source;
    for (const PerturbationLevel& level : levels) {
      for (int t = 0; t < trials; ++t) {
        Trial trial{name, pool ? pooledName(name) : name, level, first_seed + t};
        const Eigen::Isometry3d initial =
            truth *
            randomPerturbation(level.degrees, level.metres, static_cast<uint64_t>(trial.seed));
        const RegistrationResult r =
            runMethod("pda", loaded.target, loaded.source, initial, settings).result;
        trial.converged = r.converged;
        trial.covariance_share = r.time_ms > 0.0 ? r.covariance_ms / r.time_ms : 0.0;
        trial.translation_error = (r.T_target_source.translation() - truth.translation()).norm();
        trial.rotation_error =
            Eigen::AngleAxisd(r.T_target_source.linear() * truth.linear().transpose()).angle();
        const ExpectedError expected = expectedError(r.covariance);
        trial.translation_sigma = expected.translation;
        trial.rotation_sigma = expected.rotation;
        trial.translation_shares = varianceShares(r.covariance.topLeftCorner<3, 3>());
        trial.rotation_shares = varianceShares(r.covariance.bottomRightCorner<3, 3>());
        all.push_back(trial);
        std::cerr << "\r" << name << " " << level.degrees << "deg/" << level.metres << "m trial "
                  << t + 1 << "/" << trials << "          " << std::flush;
      }
    }
  }
  std::cerr << "\n";

  if (cl.has("csv")) {
    std::ofstream csv(cl.text("csv"));
    csv << "case,level_deg,level_m,seed,converged,translation_error_m,translation_sigma_m,"
           "rotation_error_rad,rotation_sigma_rad,covariance_time_share\n";
    for (const Trial& t : all) {
      csv << t.case_name << ',' << t.level.degrees << ',' << t.level.metres << ',' << t.seed << ','
          << t.converged << ',' << t.translation_error << ',' << t.translation_sigma << ','
          << t.rotation_error << ',' << t.rotation_sigma << ',' << t.covariance_share << '\n';
    }
    if (!csv) return fail("--csv: cannot write '" + cl.text("csv") + "'");
  }

  std::cout << "| case | level | converged | |t err| [cm] | sigma_t [cm] | t err / sigma_t | "
               "|r err| [deg] | sigma_r [deg] | r err / sigma_r | within ["
            << low << ", " << high << "] | outside by chance | covariance time |\n"
            << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  MissOdds miss_odds;
  const double kDeg = 180.0 / M_PI;
  for (const std::string& name : rows) {
    for (const PerturbationLevel& level : levels) {
      std::vector<double> te, ts, re, rs, share;
      Eigen::Vector3d t_shares = Eigen::Vector3d::Zero(), r_shares = Eigen::Vector3d::Zero();
      size_t tried = 0;
      std::vector<std::string> draws;  // the case folders its converged trials come from
      for (const Trial& t : all) {
        if (t.row != name || t.level.degrees != level.degrees || t.level.metres != level.metres)
          continue;
        ++tried;
        if (!t.converged) continue;
        te.push_back(t.translation_error);
        ts.push_back(t.translation_sigma);
        re.push_back(t.rotation_error);
        rs.push_back(t.rotation_sigma);
        share.push_back(t.covariance_share);
        if (std::find(draws.begin(), draws.end(), t.case_name) == draws.end())
          draws.push_back(t.case_name);
        t_shares += t.translation_shares;
        r_shares += t.rotation_shares;
      }
      const double t_ratio = medianRatio(te, ts), r_ratio = medianRatio(re, rs);
      // NaN (no sigma) is never within.
      auto within = [&](double ratio) { return ratio >= low && ratio <= high; };
      std::string chance = "-";
      if (!std::isnan(t_ratio) && !std::isnan(r_ratio) && t_shares.sum() > 0.0 &&
          r_shares.sum() > 0.0) {
        chance = rowMissOdds(t_shares, r_shares, draws.size(), low, high,
                             !(within(t_ratio) && within(r_ratio)), &miss_odds);
      }
      std::ostringstream row;
      row << std::fixed << "| " << name << " | " << std::setprecision(0) << level.degrees << "°/"
          << std::setprecision(2) << level.metres << " m | " << te.size() << "/" << tried << " | "
          << std::setprecision(3) << 100.0 * median(te) << " | " << 100.0 * median(ts) << " | "
          << ratioText(t_ratio) << " | " << std::setprecision(4) << kDeg * median(re) << " | "
          << kDeg * median(rs) << " | " << ratioText(r_ratio) << " | "
          << (within(t_ratio) && within(r_ratio) ? "yes" : "**no**") << " | " << chance << " | "
          << std::setprecision(1) << 100.0 * median(share) << " % |\n";
      std::cout << row.str();
    }
  }
  // Every converged trial of the run at once: the calibration of the whole set, which one row
  // (a handful of draws) can only hint at.
  std::vector<double> t_ratios, r_ratios;
  for (const Trial& t : all) {
    if (!t.converged || !(t.translation_sigma > 0.0) || !(t.rotation_sigma > 0.0)) continue;
    t_ratios.push_back(t.translation_error / t.translation_sigma);
    r_ratios.push_back(t.rotation_error / t.rotation_sigma);
  }
  if (!t_ratios.empty()) {
    auto rms = [](const std::vector<double>& v) {
      double sum = 0.0;
      for (double x : v) sum += x * x;
      return std::sqrt(sum / static_cast<double>(v.size()));
    };
    std::cout << "\nPooled over " << t_ratios.size() << " converged trials: root mean square of "
              << "|error| / sigma " << ratioText(rms(t_ratios)) << " (translation), "
              << ratioText(rms(r_ratios)) << " (rotation); medians " << ratioText(median(t_ratios))
              << ", " << ratioText(median(r_ratios)) << ".\n";
  }
  printMissCount(miss_odds, low, high);
  return 0;
}
