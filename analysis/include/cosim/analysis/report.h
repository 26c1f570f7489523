// The report (`cosim report RUN [RUN...]`): reads each run folder's particles.h5 and
// timeseries.csv, computes the coating analytics (statistics, histograms, Eqs. 9-10 fit,
// mixing verdict, extrapolation, prediction check, mass balance), writes report.json and CSV
// tables, draws the PNGs with scripts/plot_report.py (python3 + matplotlib) and writes
// report.html. Several runs (e.g. a sweep over fluidization flow) also get one comparison
// report. Layouts and formulas: docs/analysis.md.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cosim/analysis/bootstrap_errors.h"
#include "cosim/analysis/coating_statistics.h"
#include "cosim/analysis/display_units.h"
#include "cosim/analysis/extrapolation.h"
#include "cosim/analysis/files.h"
#include "cosim/analysis/growth_fit.h"
#include "cosim/analysis/histogram.h"
#include "cosim/analysis/long_time_check.h"
#include "cosim/analysis/mass_balance.h"
#include "cosim/analysis/mixing_verdict.h"
#include "cosim/analysis/operating_conditions.h"
#include "cosim/analysis/parcel_places.h"
#include "cosim/analysis/window_study.h"
#include "cosim/analysis/zone_pass_statistics.h"

namespace cosim::analysis {

struct ReportOptions {
  std::vector<std::filesystem::path> runs;  // run folders (each holds particles.h5)
  // Output folder. Empty: <run>/report for one run, <parent of the first run>/report-comparison
  // for several (each run's report then goes to a subfolder named after the run folder).
  std::filesystem::path output;
  // Fit window [fit_start, fit_end] in simulated seconds; NaN = first / last snapshot.
  double fit_start = std::numeric_limits<double>::quiet_NaN();
  double fit_end = std::numeric_limits<double>::quiet_NaN();
  double coating_start = 0;             // [s] time at which coating starts (origin of Eqs. 9-10)
  std::vector<double> histogram_times;  // [s]; empty = 1/4, 1/2, 3/4 and all of the run
  std::vector<double> predict_times = {300.0, 1200.0};  // [s] reconstructed distributions (Fig. 12)
  double predict_until = 3600.0;                        // [s] CV prediction horizon (Fig. 11)
  double band = 0.2;                                    // relative band on a2 (Fig. 11)
  double uncoated_relative = 1e-6;  // never-coated threshold as a fraction of the mean
  MixingCriteria criteria;
  // Density of the coating layer [kg/m3] for its thickness; NaN = the scene's parameter
  // coating_density, else kDefaultCoatingDensity (operating_conditions.h).
  double coating_density = std::numeric_limits<double>::quiet_NaN();
  // Minimum fluidization velocity [m/s] for u / u_mf; NaN = the scene's parameter u_mf, else
  // Wen-Yu for the real grains in the fluid's gas.
  double u_mf = std::numeric_limits<double>::quiet_NaN();
  // Particle-bootstrap standard errors of a1 and a2 (bootstrap_errors.h): resamples (0 = off)
  // over at most bootstrap_snapshots snapshots evenly spread over the fit window.
  std::size_t bootstrap_resamples = 100;
  std::size_t bootstrap_snapshots = 50;
  bool plots = true;  // false: numbers and HTML only
  bool batch = true;  // the whole batch by the long-time model (cosim batch) to predict_until
  // Check for CI: when set, runReport returns 3 if a run has no mass balance or its |error %|
  // exceeds this limit (the project's target: 0.01). NaN = no check.
  double mass_balance_limit_percent = std::numeric_limits<double>::quiet_NaN();
  std::ostream* log = nullptr;  // progress and messages; nullptr = std::cout
};

struct HistogramAt {
  double requested = 0;  // [s]
  CoatingStatistics stats;
  Histogram histogram;
};

// The passes through the coating zone (zone_passes.csv, zone_pass_statistics.h) and what they
// predict, beside the simulated coating.
struct ZonePassReport {
  ZonePassStatistics stats;
  double coating_on_parcels = 0;  // [kg] last snapshot minus first: what the passes should hold
  double simulated_time = 0;      // [s] the last snapshot
  double simulated_mean = 0;      // [kg] mean coating per parcel there
  double simulated_cv = 0;        // CV of the coating there
  // Mann's prediction at the run's end, at the --predict times and at predict_until (times since
  // the coating start).
  std::vector<MannPrediction> predictions;
  ParcelPlaces never_entered_places;  // where the parcels that never entered sit (if any did not)
  bool cycles_cut_by_run = false;     // the run is short against the cycles (see zone_passes notes)
  // The two ledgers: each parcel's coating gain between the first and the last snapshot equals
  // the coating of its passes (to 1e-9 relative, sums of the same increments in another order);
  // empty when they agree, else the first parcel that disagrees and by how much.
  std::string ledger_problem;
  std::vector<std::string> notes;  // plain-language cautions
};

// The long-time model's answer for a run's report (cosim batch with its defaults).
struct BatchPrediction {
  double record_from = 0, record_to = 0;  // [s]
  double longest_wait = 0, mixing = 0;    // [s]
  std::size_t dead_end_moves = 0;         // LongTimeModel::dead_end_moves
  std::vector<std::string> warnings;
  std::vector<double> times, mean, cv, never_coated;  // at the record's end, then later
  double wall_seconds = 0;
  // The compartments: each candidate's model fitted on the record's first half only and held
  // against the run's own second half (how far the batch's answer may be from CFD-DEM on this
  // bed); the batch uses the one that holds best (`grid`; `chosen` indexes grid_trials).
  std::vector<GridTrial> grid_trials;
  Compartments grid;
  double step = 0;  // [s] the model's step
  std::optional<std::size_t> chosen;
};

struct RunAnalysis {
  // Standard errors shown with a1 and a2: the particle bootstrap when available, else HC3.
  double a1Error() const { return bootstrap.ok ? bootstrap.a1_se : fit.a1_se; }
  double a2Error() const { return bootstrap.ok ? bootstrap.a2_se : fit.a2_se; }

  std::filesystem::path run;
  std::string label;
  std::vector<CoatingStatistics> snapshots;
  std::vector<HistogramAt> histograms;
  GrowthFit fit;
  BootstrapErrors bootstrap;  // particle-bootstrap errors of a1, a2 (preferred when ok)
  MixingVerdict verdict;
  CvPrediction cv_prediction;
  std::vector<PredictedDistribution> distributions;
  PredictionCheck prediction_check;
  WindowStudy window_study;  // extrapolation against run length / wall time
  std::optional<MassBalance> mass_balance;
  std::string mass_balance_problem;                                // why there is no mass balance
  double wall_seconds = std::numeric_limits<double>::quiet_NaN();  // last wall_seconds (cumulative)
  std::string run_status;  // summary.json "status" ("completed", "failed", ...); empty if none
  std::vector<std::pair<std::string, double>>
      parameters;                             // summary.json extra.parameters (numbers)
  std::size_t steps = 0;                      // rows of the time series
  std::optional<ZonePassReport> zone_passes;  // when the run recorded zone_passes.csv
  std::string zone_passes_problem;            // why there is none
  // The whole batch by the long-time model (long_time.h) to predict_until; none when the record
  // holds fewer than 3 evenly spaced snapshots or the options turn it off (then the reason)
  std::optional<BatchPrediction> batch;
  std::string batch_problem;
  OperatingConditions conditions;  // flow, u / u_mf, parcels, cg, grain scale, ...
  // The units the pages show: one for every coating mass (from the largest mean coating per
  // parcel; a comparison puts every run in the same), one for the layer thickness.
  DisplayUnit mass_unit, thickness_unit;
};

// The units of a report of these runs: mass from the largest mean coating per parcel over all
// their snapshots, thickness from the layer that coating makes.
void chooseDisplayUnits(std::vector<RunAnalysis>& runs);

// The numbers of one run (no files written). Throws std::runtime_error with the file at fault.
RunAnalysis analyseRun(const std::filesystem::path& run, const ReportOptions& options);

Json toJson(const RunAnalysis& a, const ReportOptions& options);

// Writes report.json, the CSV tables, the PNGs (if possible) and report.html into folder.
// Returns the names of the PNGs drawn; `plot_message` receives why plots are missing, if so.
std::vector<std::string> writeRunReport(const RunAnalysis& a, const ReportOptions& options,
                                        const std::filesystem::path& folder,
                                        std::string& plot_message);

// Runs the whole report. Returns 0 on success (also when only the plots could not be drawn:
// the message says what to install), 1 on an error (printed to std::cerr with what to do),
// 3 when mass_balance_limit_percent is set and a run misses it (after writing every report).
int runReport(const ReportOptions& options);

// Plotting helpers (report_plots.cpp).
// A script of scripts/: $COSIM_SCRIPTS/<name>, else next to the executable
// (<exe>/../share/cosim/scripts, <exe>/../../scripts), else the source tree's scripts/.
std::optional<std::filesystem::path> findScript(const std::string& name);
std::optional<std::filesystem::path> findPlotScript();  // findScript("plot_report.py")
// A python3 that imports matplotlib and numpy: $COSIM_PYTHON if set (only that one), else
// python3 on the PATH, else /usr/bin/python3.
std::optional<std::string> findPython(std::string& why_not);
// Runs `python3 <script> <folder>` (argument vector, no shell; MPLBACKEND=Agg) with its output
// in log; returns true on success, else message says why (with the log's tail).
bool runPlotScript(const std::string& script, const std::filesystem::path& folder,
                   const std::filesystem::path& log, std::string& message);
// Runs `python3 <script> <args...>` the same way.
bool runPlotScript(const std::string& script, const std::vector<std::string>& args,
                   const std::filesystem::path& log, std::string& message);
// For a command's one figure: runs `python3 <script> <args...>` with its output in log and
// returns the line to print: "plot: <png>" (the log removed), or "no plot: <why>" (what to
// install or the script's failure); the command's numbers are written either way.
std::string drawFigure(const std::string& script, const std::vector<std::string>& args,
                       const std::filesystem::path& png, const std::filesystem::path& log);
// Runs plot_report.py on a report folder; returns true on success, else message says why.
bool drawPlots(const std::filesystem::path& folder, std::string& message);

}  // namespace cosim::analysis
