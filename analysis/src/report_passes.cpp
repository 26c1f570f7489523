// The report's part on the passes through the coating zone: from zone_passes.csv the pass and
// cycle statistics, Mann's prediction beside the simulated coating, and for parcels that never
// reached the zone where they sit (docs/analysis.md section 10).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "cosim/analysis/display_units.h"
#include "cosim/analysis/report.h"
#include "cosim/link/fields.h"
#include "report_internal.h"
#include "report_json.h"

namespace cosim::analysis {

namespace {

// A run shorter than this many mean cycles is "short against the cycles".
constexpr double kMinCyclesPerRun = 5.0;
// Entry-rate cycle time this much above the observed mean: the run cuts off long cycles.
constexpr double kRateOverMean = 1.2;

// Each parcel's coating at the last snapshot, less its coating at the first, against the coating
// of its passes: the first parcel (in id order) whose two ledgers differ by more than round-off,
// or "" when every one agrees. Parcels deleted or inserted between the snapshots are left out
// (they are in only one of them).
std::string ledgerProblem(const ParticleFile& file, const ZonePassStatistics& s, double end) {
  const auto& snaps = file.snapshots();
  if (!file.hasField(field::coating_mass) || snaps.empty()) return "";
  const std::size_t last = snaps.size() - 1;
  if (end > snaps[last].time + 1e-9 * std::max(1.0, end))
    return fmt::format(
        "zone_passes.csv runs to t = {:.6g} s, particles.h5 only to {:.6g} s: the two records "
        "stop at different times (a run stopped by a cosim older than this one's report); "
        "resume it, or compare statistics only",
        end, snaps[last].time);
  const auto first_ids = file.ids(0), last_ids = file.ids(last);
  const auto first_m = file.read(0, field::coating_mass),
             last_m = file.read(last, field::coating_mass);
  std::unordered_map<std::int64_t, double> start;
  for (std::size_t i = 0; i < first_ids.size(); ++i) start[first_ids[i]] = first_m[i];
  std::unordered_map<std::int64_t, std::size_t> in_stats;
  for (std::size_t i = 0; i < s.ids.size(); ++i) in_stats[s.ids[i]] = i;
  double largest = 0;
  for (std::size_t i = 0; i < last_m.size(); ++i) largest = std::max(largest, std::fabs(last_m[i]));
  std::vector<std::size_t> order(last_ids.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto x, auto y) { return last_ids[x] < last_ids[y]; });
  for (const std::size_t i : order) {
    const auto st = start.find(last_ids[i]);
    const auto ps = in_stats.find(last_ids[i]);
    if (st == start.end() || ps == in_stats.end()) continue;
    const double gained = last_m[i] - st->second, passes = s.parcel_coating[ps->second];
    if (std::fabs(gained - passes) >
        1e-9 * std::max({std::fabs(gained), std::fabs(passes), 1e-6 * largest}))
      return fmt::format(
          "parcel {} gained {:.6g} kg of coating between t = {:.6g} and {:.6g} s (particles.h5) "
          "but its passes hold {:.6g} kg (zone_passes.csv)",
          last_ids[i], gained, snaps.front().time, snaps[last].time, passes);
  }
  return "";
}

}  // namespace

std::optional<ZonePassReport> analyseZonePasses(const std::filesystem::path& run,
                                                const ParticleFile& file, const RunAnalysis& a,
                                                const ReportOptions& o, std::string& problem) {
  const auto path = run / kZonePassesFile;
  if (!std::filesystem::exists(path)) {
    problem = "the run recorded no " + std::string(kZonePassesFile) +
              " (scenes without a coating zone, and runs made before cosim recorded passes)";
    return std::nullopt;
  }
  const auto passes = readZonePasses(path);
  const auto& snaps = file.snapshots();
  const std::size_t last = snaps.size() - 1;
  const double start = snaps.front().time;
  double end = snaps.back().time;
  for (const auto& p : passes) end = std::max(end, p.exit_time);

  // The bed: every parcel at the start or at the end (or with a pass: inserted and deleted ones).
  std::set<std::int64_t> bed;
  for (const std::size_t i : {std::size_t{0}, last}) {
    const auto ids = file.ids(i);
    bed.insert(ids.begin(), ids.end());
  }
  for (const auto& p : passes) bed.insert(p.parcel_id);

  ZonePassReport r;
  r.stats = zonePassStatistics(passes, {bed.begin(), bed.end()}, start, end);
  r.coating_on_parcels = a.snapshots.back().total - a.snapshots.front().total;
  if (a.run_status == "running") {
    // passes still open are written when they close: the two records agree once the run stops
    r.notes.push_back(
        "The run is still running (or its cosim was killed): passes still open are not in "
        "zone_passes.csv yet, so the passes hold less coating than the parcels until it stops.");
  } else {
    r.ledger_problem = ledgerProblem(file, r.stats, end);
    if (!r.ledger_problem.empty())
      r.notes.push_back("The records disagree: " + r.ledger_problem + ".");
  }
  r.simulated_time = a.snapshots.back().time;
  r.simulated_mean = a.snapshots.back().mean;
  r.simulated_cv = a.snapshots.back().cv;
  std::vector<double> times = {r.simulated_time - o.coating_start};
  for (double t : o.predict_times) times.push_back(t);
  times.push_back(o.predict_until);
  for (double t : times) r.predictions.push_back(predictFromPasses(r.stats, t));

  const auto& s = r.stats;
  const double duration = end - start;
  if (s.never_entered > 0) {
    std::unordered_set<std::int64_t> missed;
    for (std::size_t i = 0; i < s.ids.size(); ++i) {
      if (s.parcel_passes[i] == 0) missed.insert(s.ids[i]);
    }
    r.never_entered_places = placesOf(file, missed);
    r.notes.push_back(
        fmt::format("{:.1f} % of the parcels never entered the zone in the {:.3g} s simulated: "
                    "their cycles are "
                    "longer than the run and are missing from the cycle statistics.",
                    100.0 * s.never_entered_share, duration));
  }
  if (s.cycle_time.n > 0 && s.cycle_time_from_rate > kRateOverMean * s.cycle_time.mean) {
    r.notes.push_back(fmt::format(
        "From the entry rate of all parcels, a parcel enters every {:.3g} s on average, {:.2g} "
        "times "
        "the mean of the cycles seen ({:.3g} s): the run cuts off the long cycles, so the CV "
        "predicted from them is too small (optimistic).",
        s.cycle_time_from_rate, s.cycle_time_from_rate / s.cycle_time.mean, s.cycle_time.mean));
  }
  if (s.prediction_ok && duration < kMinCyclesPerRun * s.cycle_time.mean) {
    r.notes.push_back(fmt::format(
        "The run covers only {:.2g} mean cycles; Mann's formulas hold for many cycles per parcel.",
        duration / s.cycle_time.mean));
  }
  r.cycles_cut_by_run = !r.notes.empty();
  return r;
}

Json zonePassesJson(const RunAnalysis& a) {
  if (!a.zone_passes) return Json{{"recorded", false}, {"problem", a.zone_passes_problem}};
  const auto& r = *a.zone_passes;
  const auto& s = r.stats;
  Json j = {{"recorded", true},
            {"start", s.start},
            {"end", s.end},
            {"parcels", s.parcels},
            {"passes", s.passes},
            {"complete_passes", s.complete_passes},
            {"entries", s.entries},
            {"never_entered", s.never_entered},
            {"never_entered_share", s.never_entered_share},
            {"parcels_without_cycle", s.at_most_one_entry},
            {"passes_per_parcel", s.passes_per_parcel},
            {"passes_cv", s.passes_cv},
            {"time_in_zone_per_parcel_s", s.time_in_zone_per_parcel},
            {"time_in_zone_share", s.time_in_zone_share},
            {"uptake_rate_in_zone_kg_per_s", s.uptake_rate_in_zone},
            {"pass_duration_s", s.pass_duration},
            {"cycle_time_s", s.cycle_time},
            {"cycle_time_from_rate_s", s.cycle_time_from_rate},
            {"coating_per_pass_kg", s.coating_per_pass},
            {"coating_in_passes_kg", s.coating_in_passes},
            {"coating_on_parcels_kg", r.coating_on_parcels},
            {"ledgers_agree", r.ledger_problem.empty()}};
  if (!r.ledger_problem.empty()) j["ledger_problem"] = r.ledger_problem;
  j.update(Json{{"w0_kg", s.w0},
                {"simulated",
                 {{"time", r.simulated_time}, {"mean", r.simulated_mean}, {"cv", r.simulated_cv}}},
                {"prediction_ok", s.prediction_ok},
                {"prediction_problem", s.prediction_problem},
                {"mann_prediction", r.predictions}});
  if (const auto& pl = r.never_entered_places; pl.valid) {
    j["never_entered_places"] = {{"axis_x_m", pl.axis_x},
                                 {"axis_y_m", pl.axis_y},
                                 {"snapshots", pl.snapshots},
                                 {"never_entered", pl.group},
                                 {"others", pl.others}};
  }
  j.update(Json{{"cycles_cut_by_run", r.cycles_cut_by_run}, {"notes", r.notes}});
  return j;
}

void writeZonePassTables(const RunAnalysis& a, const std::filesystem::path& dir) {
  if (!a.zone_passes) return;
  const auto& s = a.zone_passes->stats;
  std::string csv = "parcel_id,passes,time_in_zone_s,coating_in_passes_kg\n";
  for (std::size_t i = 0; i < s.ids.size(); ++i) {
    csv +=
        fmt::format("{},{},{},{}\n", s.ids[i], s.parcel_passes[i],
                    formatShortest(s.parcel_time_in_zone[i]), formatShortest(s.parcel_coating[i]));
  }
  writeFileAtomically(dir / "zone_passes_per_parcel.csv", csv);
}

namespace {
// Where the parcels that never reached the zone sit, against the others
void neverEnteredPlacesHtml(std::ostringstream& h, const ParcelPlaces& pl) {
  h << "<p><b>Where the parcels that never reached the zone sit</b> (height z; distance from "
       "the vertical axis through the bed's centre at the start; averaged over "
    << pl.snapshots << " snapshots):</p>\n<table><tr><th class=l>parcels</th><th>number</th>"
    << "<th>mean height [mm]</th><th>mean distance from the axis [mm]</th><th>height at the "
       "start [mm]</th><th>distance at the start [mm]</th></tr>";
  for (const auto& [name, g] :
       {std::pair<const char*, const PlaceOfGroup&>{"never reached the zone", pl.group},
        std::pair<const char*, const PlaceOfGroup&>{"reached it", pl.others}}) {
    h << "<tr><td class=l>" << name << "</td><td>" << g.parcels << "</td><td>"
      << htmlFixed(1e3 * g.mean_height, 1) << "</td><td>" << htmlFixed(1e3 * g.mean_radius, 1)
      << "</td><td>" << htmlFixed(1e3 * g.start_height, 1) << "</td><td>"
      << htmlFixed(1e3 * g.start_radius, 1) << "</td></tr>";
  }
  h << "</table>\n";
}

// What Mann's cycle-time analysis predicts from the passes, beside the simulated coating (a
// labelled hypothetical where the run is poorly mixed or its cycles miss part of the bed)
void cyclePredictionHtml(std::ostringstream& h, const RunAnalysis& a) {
  const auto& r = *a.zone_passes;
  const auto& s = r.stats;
  h << "<p><b>What the cycles predict</b> (Mann's cycle-time analysis: a parcel entering every "
       "&mu;<sub>T</sub> &plusmn; &sigma;<sub>T</sub> and taking W<sub>0</sub> per pass has after "
       "a coating time t the mean W<sub>0</sub> t / &mu;<sub>T</sub> and the CV "
       "&sigma;<sub>T</sub> / &radic;(&mu;<sub>T</sub> t)):</p>\n";
  // Beyond the run's end these are extrapolations: shown only as a labelled hypothetical when the
  // run is poorly mixed or its cycles do not describe the whole bed.
  const bool hypothetical = s.prediction_ok && (!a.verdict.well_mixed || !r.notes.empty());
  if (hypothetical) {
    h << "<div class=\"hypothetical\">\n<p class=note><b>Hypothetical: if the bed were well "
         "mixed.</b> ";
    if (!a.verdict.well_mixed) {
      h << "The run is poorly mixed, so the numbers below show what cycles like the ones seen "
           "would give in a "
           "well-mixed bed, not a prediction for this bed. ";
    } else {
      h << "The cycles seen in this run do not describe the whole bed, so the numbers below show "
           "what cycles "
           "like these would give, not a prediction for this bed. ";
    }
    for (const auto& n : r.notes) h << htmlEscape(n) << " ";
    h << "</p>\n";
  } else if (!r.notes.empty()) {
    h << "<p class=note>";
    for (const auto& n : r.notes) h << htmlEscape(n) << " ";
    h << "</p>\n";
  }
  if (!s.prediction_ok) {
    h << "<p>No prediction: " << htmlEscape(s.prediction_problem) << ".</p>\n";
  } else {
    const char* cvHead = hypothetical ? "hypothetical CV" : "CV";
    h << "<table><tr><th>coating time</th><th>" << (hypothetical ? "hypothetical " : "")
      << "mean coating per parcel [" << a.mass_unit.name << "]</th><th>" << cvHead
      << " (cycle times)</th><th>" << cvHead
      << " (with the spread of coating per pass)</th><th>simulated mean [" << a.mass_unit.name
      << "]</th><th>simulated CV</th></tr>";
    for (std::size_t i = 0; i < r.predictions.size(); ++i) {
      const auto& p = r.predictions[i];
      h << "<tr><td>" << (i == 0 ? "run&nbsp;end,&nbsp;" : "") << htmlDuration(p.t) << "</td><td>"
        << htmlNumber(a.mass_unit.of(p.mean), 3) << "</td><td>" << htmlNumber(p.cv, 3)
        << "</td><td>" << htmlNumber(p.cv_with_pass_spread, 3) << "</td>";
      if (i == 0) {
        h << "<td>" << htmlNumber(a.mass_unit.of(r.simulated_mean), 3) << "</td><td>"
          << htmlNumber(r.simulated_cv, 3) << "</td>";
      } else {
        h << "<td>&ndash;</td><td>&ndash;</td>";
      }
      h << "</tr>";
    }
    h << "</table>\n<p>The number of passes per parcel alone has a CV of "
      << htmlNumber(s.passes_cv, 3) << " at the run end; the cycles predict "
      << htmlNumber(r.predictions.front().cv, 3) << " for it.</p>\n";
  }
  if (hypothetical) h << "</div>\n";
}

}  // namespace

std::string zonePassesHtml(const RunAnalysis& a) {
  std::ostringstream h;
  h << "<h2>Passes through the coating zone</h2>\n";
  if (!a.zone_passes) {
    h << "<p>No pass statistics: " << htmlEscape(a.zone_passes_problem) << ".</p>\n";
    return h.str();
  }
  const auto& r = *a.zone_passes;
  const auto& s = r.stats;
  const double duration = s.end - s.start;
  const auto mass = [&](double kg, int digits = 3) {
    return htmlQuantity(kg, a.mass_unit, digits);
  };
  h << "<p>The coating happens only while a parcel is in the coating zone. Every coupling step "
       "the simulation decides which parcels are in it; "
    << kZonePassesFile << " holds each parcel's passes (" << s.passes << " passes of " << s.parcels
    << " parcels over " << htmlDuration(duration) << " of coating).";
  if (!a.verdict.well_mixed) h << " They explain why the run is poorly mixed:";
  h << "</p>\n<ul>\n";
  h << "<li><b>Never reached the zone:</b> " << s.never_entered << " of " << s.parcels
    << " parcels (" << htmlPercent(s.never_entered_share, 1) << ").</li>\n";
  if (s.cycle_time.n > 0) {
    h << "<li><b>A cycle</b> (from one entry into the zone to the next) takes "
      << htmlDuration(s.cycle_time.mean) << " on average (standard deviation "
      << htmlDuration(s.cycle_time.sd) << ", median " << htmlDuration(s.cycle_time.p50)
      << ", 10&ndash;90&nbsp;%: " << htmlDuration(s.cycle_time.p10) << " to "
      << htmlDuration(s.cycle_time.p90) << "), from " << s.cycle_time.n
      << " cycles. Counting every parcel, also those that entered once or "
      << "never, a parcel enters every " << htmlDuration(s.cycle_time_from_rate) << ".</li>\n";
  } else {
    h << "<li><b>No cycle</b>: no parcel entered the zone twice. Counting every parcel, one "
         "enters every "
      << htmlDuration(s.cycle_time_from_rate) << ".</li>\n";
  }
  if (s.pass_duration.n > 0) {
    h << "<li><b>A pass</b> lasts " << htmlDuration(s.pass_duration.mean) << " on average (median "
      << htmlDuration(s.pass_duration.p50)
      << ", 10&ndash;90&nbsp;%: " << htmlDuration(s.pass_duration.p10) << " to "
      << htmlDuration(s.pass_duration.p90) << "); the parcels spend "
      << htmlPercent(s.time_in_zone_share, 1) << " of their time in the zone and take up "
      << mass(s.uptake_rate_in_zone)
      << " a second while in it (the coating rate of the bed is the parcels times that share "
         "times that rate: the share says how much of the bed the zone holds, the rate how "
         "much precursor reaches a parcel in it).</li>\n";
  }
  h << "<li><b>Passes per parcel:</b> " << htmlNumber(s.passes_per_parcel.mean, 3)
    << " on average (from " << htmlFixed(s.passes_per_parcel.min, 0) << " to "
    << htmlFixed(s.passes_per_parcel.max, 0) << "), coefficient of variation "
    << htmlNumber(s.passes_cv, 3) << ". Coating per pass: " << mass(s.w0)
    << " on average (all coating in passes divided by the passes).</li>\n";
  h << "<li><b>Coating only in the zone:</b> the passes hold " << mass(s.coating_in_passes, 6)
    << ", the parcels received " << mass(r.coating_on_parcels, 6) << ".</li>\n";
  if (!r.ledger_problem.empty())
    h << "<li><b>The records disagree:</b> " << htmlEscape(r.ledger_problem) << ".</li>\n";
  h << "</ul>\n";

  if (r.never_entered_places.valid && r.never_entered_places.group.parcels > 0)
    neverEnteredPlacesHtml(h, r.never_entered_places);
  cyclePredictionHtml(h, a);
  h << "<p>Per parcel: zone_passes_per_parcel.csv; every number: report.json "
       "(<code>zone_passes</code>).</p>\n";
  return h.str();
}

}  // namespace cosim::analysis
