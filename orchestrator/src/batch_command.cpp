#include "batch_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>

#include "cli_checks.h"
#include "cosim/analysis/files.h"
#include "cosim/analysis/long_time.h"
#include "cosim/analysis/long_time_check.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/util/errors.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;
namespace a = cosim::analysis;

namespace {
constexpr const char* kCsvHeader = "time_s,mean_kg,cv,never_coated_share,from_record";

// The record's end, then 20 s, 1, 5, 10, 20, 30, 40, 50 and 60 min, up to `until`, with `extra`.
std::vector<double> reportTimes(double end, double until, const std::vector<double>& extra) {
  std::vector<double> t = {end};
  for (double x : {20.0, 60.0, 300.0, 600.0, 1200.0, 1800.0, 2400.0, 3000.0, 3600.0})
    if (x > end && x < until) t.push_back(x);
  if (until > end) t.push_back(until);
  for (double x : extra) t.push_back(x);
  std::sort(t.begin(), t.end());
  t.erase(
      std::unique(t.begin(), t.end(), [](double x, double y) { return std::fabs(x - y) < 1e-9; }),
      t.end());
  return t;
}

// The check's times (--to): the run's snapshots on the record's grid after its end, nearest below
// a quarter, half and three quarters of the way, the batch report's times and `extra`, and the
// last.
std::vector<double> checkTimes(const a::CoatingDatabase& db, double step,
                               const a::ParticleFile& file, const std::vector<double>& extra) {
  const double end = db.times.back();
  std::vector<double> grid;  // the snapshots at whole steps of the model after the record
  for (const auto& s : file.snapshots()) {
    const double k = (s.time - end) / step;
    if (s.time > end + 1e-9 && std::fabs(k - std::round(k)) <= 1e-6 * std::max(1.0, k))
      grid.push_back(s.time);
  }
  if (grid.empty()) return {};
  const double last = grid.back();
  std::vector<double> want = {end + 0.25 * (last - end), end + 0.5 * (last - end),
                              end + 0.75 * (last - end), last};
  for (double x : reportTimes(end, last, extra)) want.push_back(x);
  std::vector<double> t;
  for (double w : want) {
    const auto it = std::upper_bound(grid.begin(), grid.end(), w + 1e-9);
    if (it != grid.begin()) t.push_back(*std::prev(it));
  }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

// The model against the rest of its run, printed.
void printCheck(const a::LongTimeCheck& c, std::ostream& out) {
  out << "  the model against the run's own snapshots after the record (--to):\n"
      << "  time [s]   mean: model / run      CV: model / run     never coated: model / run\n";
  for (const auto& r : c.rows)
    out << fmt::format(
        "  {:>8.6g}  {:>10.4g} / {:<10.4g} {:+6.2f} %  {:>7.4f} / {:<7.4f} {:+6.2f} %  {:>6.2f} / "
        "{:<6.2f} % {:+6.2f} points\n",
        r.time, r.predicted.mean, r.recorded.mean, 100 * r.mean_error, r.predicted.cv,
        r.recorded.cv, 100 * r.cv_error, 100 * r.predicted.never_coated_share,
        100 * r.recorded.never_coated_share, r.never_points);
  out << fmt::format(
      "  the parcels' coating at t = {:g} s ({} parcels): Kolmogorov-Smirnov distance {:.4f} "
      "(two independent samples of this size exceed {:.4f} one time in twenty)\n",
      c.rows.empty() ? 0.0 : c.rows.back().time, c.parcels, c.ks_distance, c.ks_critical);
  out << "  deciles [kg], model / run:";
  for (std::size_t i = 0; i < c.predicted_deciles.size(); ++i)
    out << fmt::format(" {:.3g}/{:.3g}", c.predicted_deciles[i], c.recorded_deciles[i]);
  out << "\n";
}
}  // namespace

CLI::App* addBatchCommand(CLI::App& app, BatchOptions& o) {
  auto* b = app.add_subcommand(
      "batch",
      "A whole coating batch from a recorded run: every parcel carried on between compartments of "
      "the bed with the coating gains the record holds for each move (CV, mean, never-coated "
      "share to --until)");
  b->add_option("run", o.run, "run folder of a scene with coating (its particles.h5)")
      ->required()
      ->check(CLI::ExistingDirectory);
  b->add_option("--until", o.until, "the batch's length [s] (default 3600)")
      ->check(cli::above(0.0, "seconds", 1.0e7));
  b->add_option("--times", o.times, "more times to report [s], comma separated")
      ->delimiter(',')
      ->check(cli::atLeast(0.0, "seconds"));
  b->add_option("--from", o.from, "the record used starts here [s] (skip the start-up)")
      ->check(cli::atLeast(0.0, "seconds"));
  b->add_option("--to", o.to,
                "the record used ends here [s]; the run's snapshots after it check the model "
                "(its prediction beside what the run recorded)")
      ->check(cli::atLeast(0.0, "seconds"));
  b->add_option("--rings", o.rings,
                "compartments: rings about the vertical axis (default: the grid the record holds "
                "best of 6x8, 12x16, 16x24, 24x32; 6 when only --layers is given)")
      ->check(cli::wholeNumber(1, 100));
  b->add_option("--layers", o.layers,
                "compartments: layers of the bed (default: as --rings; 8 when only --rings is "
                "given)")
      ->check(cli::wholeNumber(1, 100));
  b->add_option("--step", o.step,
                "the model's step [s], a whole number of the record's intervals (default: the "
                "step the record holds best of its interval, 0.2, 0.5 and 1 s)")
      ->check(cli::above(0.0, "seconds"));
  b->add_option("--seed", o.seed, "seed of the random moves (the same seed, the same answer)");
  b->add_option("-o,--output", o.output, "folder for batch.json and batch.csv (default RUN/batch)");
  return b;
}

namespace {

// The compartments and the model's step the record holds best (those --rings/--layers and
// --step leave free), the table of trials printed and kept in `trials`. Returns the step in the
// record's intervals, 0 when --step fixes it (and the grid) and nothing was chosen.
std::size_t chooseModel(const a::ParticleFile& file, const BatchOptions& o, a::Compartments& grid,
                        a::Json& trials, std::ostream& out) {
  const bool fixed_grid = o.rings > 0 || o.layers > 0, fixed_step = o.step > 0;
  if (fixed_grid && fixed_step) return 0;
  const auto choice = a::chooseCompartments(
      file, o.from, o.to, fixed_grid ? std::vector<a::Compartments>{grid} : a::kCandidateGrids,
      fixed_step ? std::vector<double>{o.step} : a::kCandidateSteps);
  grid = choice.chosen;
  if (!choice.trials.empty())
    out << fmt::format(
        "cosim batch: choosing the compartments and the model's step: each model fitted on "
        "the record to t = {:g} s, held against the record's end at t = {:g} s; and fitted on "
        "half the parcels over the whole record, holding the other half from its start to its "
        "end (held out)\n"
        "  rings x layers   step     mean     CV       never coated   Kolmogorov-Smirnov   "
        "wall     held out: CV, never coated, Kolmogorov-Smirnov\n",
        choice.trials.front().half.record_to, choice.trials.front().half.check.rows.back().time);
  for (const auto& t : choice.trials) {
    const auto& r = t.half.check.rows.back();
    const bool used =
        t.grid.rings == grid.rings && t.grid.layers == grid.layers && t.lag == choice.lag;
    const std::string held =
        t.held_out && !t.held_out->rows.empty()
            ? fmt::format("{:+6.2f} %, {:+6.2f} points, {:.4f}",
                          100 * t.held_out->rows.back().cv_error,
                          t.held_out->rows.back().never_points, t.held_out->ks_distance)
            : std::string("-");
    out << fmt::format(
        "  {:>5} x {:<5}  {:>5.3g} s  {:+6.2f} %  {:+6.2f} %  {:+6.2f} points   {:.4f} (5 %: "
        "{:.4f})   {:.3g} s   {}{}{}\n",
        t.grid.rings, t.grid.layers, t.half.step, 100 * r.mean_error, 100 * r.cv_error,
        r.never_points, t.half.check.ks_distance, t.half.check.ks_critical, t.half.wall_seconds,
        held, t.half.settles_off ? "   (settles off the record's coating rate)" : "",
        used ? "   <- used" : "");
    trials.push_back(t);
  }
  return choice.lag;
}

}  // namespace

int runBatchCommand(const BatchOptions& o, std::ostream& out, std::ostream& err) {
  try {
    const fs::path run(o.run);
    const fs::path folder = o.output.empty() ? run / "batch" : fs::path(o.output);
    const fs::path json = folder / "batch.json", csv = folder / "batch.csv";
    a::claimOutputFiles({json, csv}, "\"long_time_model\"", "-o");
    const a::ParticleFile file(run / "particles.h5");
    a::Compartments grid{o.rings > 0 ? o.rings : 6, o.layers > 0 ? o.layers : 8, 0, 0};
    a::Json trials = a::Json::array();
    std::size_t lag = chooseModel(file, o, grid, trials, out);  // 0: --step as given
    if (o.to >= 0 && o.to <= o.from)
      throw InputError(fmt::format(
          "command line: --to {:g} lies before --from {:g}: the record must have a length", o.to,
          o.from));
    const auto db = a::readCoatingDatabase(file, o.from, o.to, grid);
    if (o.step > 0) {
      const double intervals = o.step / db.interval;
      if (std::fabs(intervals - std::round(intervals)) > 1e-6 * std::max(1.0, intervals) ||
          intervals < 0.5)
        throw InputError(fmt::format(
            "command line: --step {:g} is not a whole number of the record's interval ({:g} s): "
            "give {:g} or {:g}",
            o.step, db.interval, db.interval * std::max(1.0, std::floor(intervals)),
            db.interval * std::max(1.0, std::floor(intervals) + 1)));
    }
    if (lag == 0) lag = a::candidateLags(db.interval, {o.step}).front();
    auto model = a::fitLongTimeModel(db, lag);
    a::warnWhenTheBedOutlastsTheBatch(model, db.times.back(), o.until);
    const auto times = reportTimes(db.times.back(), o.until, o.times);
    const auto pr = a::predictLongTime(model, db, times, o.seed);

    out << fmt::format(
        "cosim batch: {} parcels, record t = {:g} .. {:g} s ({} snapshots, every {:g} s), {} x {} "
        "compartments ({} rings to r = {:.4g} m, {} layers to z = {:.4g} m), steps of {:g} s\n",
        db.ids.size(), db.times.front(), db.times.back(), db.times.size(), db.interval, grid.rings,
        grid.layers, grid.rings, db.grid.r_max, grid.layers, db.grid.z_max, model.interval);
    if (db.left_out > 0)
      out << fmt::format("  {} parcels not in every snapshot (inserted or deleted) left out\n",
                         db.left_out);
    for (const double t : db.off_interval)
      out << fmt::format(
          "  the snapshot at t = {:g} s lies between two of the record's interval (written where "
          "the run was stopped): set aside\n",
          t);
    out << fmt::format(
        "  longest wait for the coating zone {:.3g} s, mixing time {:.3g} s, record {:.3g} s; "
        "{} moves into compartments the record never shows a parcel leaving left out\n",
        model.longest_wait_seconds, model.mixing_seconds, model.record_seconds,
        model.dead_end_moves);
    out << fmt::format(
        "  coating per parcel and second: {:.4g} kg in the record's second half, {:.4g} kg in the "
        "model once settled\n",
        model.record_gain_per_interval / model.interval,
        model.settled_gain_per_interval / model.interval);
    for (const auto& w : model.warnings) out << "  warning: " << w << "\n";
    out << "  time [s]     mean [kg]      CV       never coated\n";
    std::string text = std::string(kCsvHeader) + "\n";
    a::Json points = a::Json::array();
    for (const auto& p : pr.points) {
      const bool recorded = p.time <= db.times.back() + 1e-9;
      out << fmt::format("  {:>8.6g}  {:>12.5g}  {:>8.4f}  {:>10.2f} %{}\n", p.time, p.mean, p.cv,
                         100 * p.never_coated_share, recorded ? "  (the record)" : "");
      text += fmt::format("{},{},{},{},{}\n", a::formatShortest(p.time), a::formatShortest(p.mean),
                          a::formatShortest(p.cv), a::formatShortest(p.never_coated_share),
                          recorded ? 1 : 0);
      points.push_back({{"time_s", p.time},
                        {"mean_kg", p.mean},
                        {"cv", p.cv},
                        {"never_coated_share", p.never_coated_share},
                        {"from_record", recorded}});
    }
    out << fmt::format("  predicted in {:.3g} s\n", pr.wall_seconds);
    a::Json j;
    if (o.to >= 0) {
      const auto check = a::checkLongTime(
          model, db, a::readRecordedCoating(file, checkTimes(db, model.interval, file, o.times)),
          o.seed);
      if (check.rows.empty())
        out << "  --to: the run has no snapshot after the record's end to check the model with\n";
      else {
        printCheck(check, out);
        j["check"] = check;
      }
    }
    j["long_time_model"] = {{"record_from_s", db.times.front()},
                            {"record_to_s", db.times.back()},
                            {"interval_s", db.interval},
                            {"step_s", model.interval},
                            {"parcels", db.ids.size()},
                            {"left_out", db.left_out},
                            {"rings", grid.rings},
                            {"layers", grid.layers},
                            {"r_max_m", db.grid.r_max},
                            {"z_max_m", db.grid.z_max},
                            {"longest_wait_s", model.longest_wait_seconds},
                            {"mixing_s", model.mixing_seconds},
                            {"dead_end_moves", model.dead_end_moves},
                            {"record_rate_kg_s", model.record_gain_per_interval / model.interval},
                            {"settled_rate_kg_s", model.settled_gain_per_interval / model.interval},
                            {"seed", o.seed},
                            {"warnings", model.warnings},
                            {"wall_s", pr.wall_seconds}};
    j["points"] = points;
    j["compartment_trials"] = trials;
    fs::create_directories(folder);
    a::writeJsonFile(json, j, 1);
    a::writeFileAtomically(csv, text);
    out << "  written: " << json.string() << ", " << csv.string() << "\n";
    return 0;
  } catch (const std::exception& e) {
    err << "cosim batch: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace cosim::orchestrator
