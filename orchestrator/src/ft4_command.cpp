#include "ft4_command.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <ostream>

#include "cosim/analysis/files.h"
#include "cosim/analysis/ft4_calibration.h"
#include "cosim/analysis/ft4_energy.h"
#include "cosim/analysis/report.h"

namespace cosim::orchestrator {

CLI::App* addFt4Command(CLI::App& app, Ft4Options& o) {
  auto* ft4 = app.add_subcommand(
      "ft4",
      "FT4 rheometer (scenarios/ft4-rheometer): flow energy of a run, calibration of the "
      "friction coefficient against a measurement");
  ft4->require_subcommand(1);
  auto* energy = ft4->add_subcommand(
      "energy",
      "Flow energy W = integral of (M / (R tan alpha) + F) dH of a run (the paper's Eq. 11), "
      "total and as a profile against the blade's height");
  energy->add_option("run", o.run, "run folder of scenarios/ft4-rheometer")->required();
  energy->add_option("-o,--output", o.output,
                     "profile CSV (height_m, force_N, torque_Nm, gradient_J_per_m, energy_J; "
                     "default RUN/ft4_energy.csv, rewritten from the run's rows each time); "
                     "its plot has the same name ending .png");
  energy->add_flag("--no-plots{false}", o.plots, "the CSV only, no PNG (matplotlib)");
  auto* cal = ft4->add_subcommand(
      "calibrate",
      "The value of a parameter (default mu_fric) that reproduces a measured flow energy: a "
      "line fitted to the runs' energies, inverted, with its uncertainty from the runs' spread "
      "and the measurement's replicates");
  cal->add_option("measured", o.measured,
                  "measured CSV: energy_mJ (or energy_J) per replicate, or height_mm (height_m) "
                  "with one cumulative energy_mJ... column per replicate")
      ->required();
  cal->add_option("runs", o.runs, "study folders (cosim study -o) or run folders")->required();
  cal->add_option("--parameter", o.parameter,
                  "the scene parameter varied by the study (default mu_fric)");
  cal->add_option("-o,--output", o.calibration_output,
                  "folder (created if missing) for ft4_calibration.json and its plot "
                  "ft4_calibration.png: the runs' energies, the line, the measurement and the "
                  "answer (default: print only)");
  cal->add_flag("--no-plots{false}", o.plots, "with -o: the JSON only, no PNG");
  return ft4;
}

int runFt4Command(const CLI::App& ft4, const Ft4Options& o, std::ostream& out, std::ostream& err) {
  namespace a = cosim::analysis;
  try {
    if (ft4.got_subcommand("energy")) {
      const auto profile = a::runFlowEnergy(o.run);
      const auto file = o.output.empty() ? std::filesystem::path(o.run) / "ft4_energy.csv"
                                         : std::filesystem::path(o.output);
      const std::string csv = a::energyProfileCsv(profile);
      const auto [_, png, log] = a::claimCsvWithPlot(file, csv, "-o");
      a::writeFileAtomically(file, csv);
      out << fmt::format(
          "flow energy {:.6g} mJ over the blade's descent from {:.4g} to {:.4g} mm (R = {:.4g} "
          "mm, helix {:.4g} deg)\n  of which the torque term M / (R tan alpha) {:.6g} mJ, the "
          "vertical force F {:.6g} mJ\nprofile: {}\n",
          profile.total_J() * 1e3, profile.highest_m() * 1e3, profile.lowest_m() * 1e3,
          profile.blade_radius_m * 1e3, profile.helix_deg, profile.torque_J() * 1e3,
          (profile.total_J() - profile.torque_J()) * 1e3, file.string());
      if (o.plots) {
        out << a::drawFigure("plot_ft4.py", {"energy", file.string(), png.string()}, png, log)
            << "\n";
      }
      if (!profile.cut_windows_s.empty()) {
        std::string times;
        for (const double t : profile.cut_windows_s) times += fmt::format(" {:g}", t);
        out << fmt::format(
            "left out {} row(s) without a mean (the output interval in which the run resumed; "
            "the profile joins the rows on either side): t ={} s\n",
            profile.cut_windows_s.size(), times);
      }
      return 0;
    }
    const auto measured = a::readMeasuredEnergy(o.measured);
    std::vector<std::filesystem::path> folders(o.runs.begin(), o.runs.end());
    const auto runs = a::ft4Runs(folders);
    const auto points = a::calibrationPoints(runs, o.parameter, measured);
    const auto c = a::calibrate(points, measured.mean_J(), measured.standard_error_J());
    if (measured.height_low_m)
      out << fmt::format("energies over the measured heights {:.4g} .. {:.4g} mm\n",
                         *measured.height_low_m * 1e3, *measured.height_high_m * 1e3);
    out << a::calibrationText(c, o.parameter);
    if (!o.calibration_output.empty()) {
      const std::filesystem::path folder(o.calibration_output);
      const auto json = folder / "ft4_calibration.json";
      a::claimOutputFiles({json, folder / "ft4_calibration.png", folder / "plot_ft4.log"},
                          "\"parameter_name\"", "-o");
      std::filesystem::create_directories(folder);
      a::writeJsonFile(json, a::calibrationJson(c, o.parameter), 2);
      out << "written " << json.string() << "\n";
      if (o.plots)
        out << a::drawFigure(
                   "plot_ft4.py",
                   {"calibration", json.string(), (folder / "ft4_calibration.png").string()},
                   folder / "ft4_calibration.png", folder / "plot_ft4.log")
            << "\n";
    }
    return 0;
  } catch (const std::exception& e) {
    err << "cosim ft4: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace cosim::orchestrator
