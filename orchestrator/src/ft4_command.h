// `cosim ft4`: the FT4 rheometer scene's analyses (scenarios/ft4-rheometer).
//   cosim ft4 energy RUN [-o CSV]                          flow energy of Eq. 11, total and profile
//   cosim ft4 calibrate MEASURED.csv STUDY_OR_RUNS... [--parameter mu_fric] [-o FOLDER]
//                                                          the parameter value the measurement
//                                                          matches
#pragma once

#include <CLI/CLI.hpp>
#include <iosfwd>
#include <string>
#include <vector>

namespace cosim::orchestrator {

struct Ft4Options {
  std::string run;                // energy
  std::string output;             // energy: profile CSV (default RUN/ft4_energy.csv)
  std::string measured;           // calibrate
  std::vector<std::string> runs;  // calibrate: study folders or run folders
  std::string parameter = "mu_fric";
  std::string
      calibration_output;  // calibrate: folder for ft4_calibration.json / .png (none: print only)
  bool plots = true;       // energy: the profile as a PNG; calibrate: the fit as a PNG
};

// Adds `ft4` with its two subcommands to app; returns it.
CLI::App* addFt4Command(CLI::App& app, Ft4Options& options);

// Runs whichever subcommand was given; returns the exit code (errors go to err).
int runFt4Command(const CLI::App& ft4, const Ft4Options& options, std::ostream& out,
                  std::ostream& err);

}  // namespace cosim::orchestrator
