// report.json and the CSV tables of one run's report.
#include <fmt/format.h>

#include <fstream>
#include <limits>
#include <stdexcept>

#include "cosim/analysis/report.h"
#include "cosim/util/errors.h"
#include "report_internal.h"
#include "report_json.h"

namespace cosim::analysis {

namespace {
Json series(const std::vector<CoatingStatistics>& s, double CoatingStatistics::*member) {
  Json a = Json::array();
  for (const auto& x : s) a.push_back(x.*member);
  return a;
}

class Csv {
 public:
  Csv(const std::filesystem::path& path, const std::string& header) : path_(path), f_(path) {
    if (!f_) throw Error(kindOfErrno(errno), "cannot write " + path.string());
    f_ << header << '\n';
  }
  Csv& operator<<(double v) {
    f_ << fmt::format("{}{:.10g}", first_ ? "" : ",", v);
    first_ = false;
    return *this;
  }
  Csv& operator<<(const std::string& s) {
    f_ << (first_ ? "" : ",") << '"' << s << '"';
    first_ = false;
    return *this;
  }
  void end() {
    f_ << '\n';
    first_ = true;
  }
  ~Csv() { f_.flush(); }

 private:
  std::filesystem::path path_;
  std::ofstream f_;
  bool first_ = true;
};
}  // namespace

Json conditionsJson(const OperatingConditions& c) {
  return {{"flow_lpm", c.flow_lpm},
          {"superficial_velocity_m_per_s", c.superficial_velocity},
          {"u_mf_m_per_s", c.u_mf},
          {"u_mf_source", c.u_mf_source},
          {"u_over_umf", c.uOverUmf()},
          {"nozzle_velocity_m_per_s", c.nozzle_velocity},
          {"precursor_mass_fraction", c.precursor_fraction},
          {"parcels", c.parcels},
          {"cg", c.grain.cg},
          {"cg_source", c.cg_source},
          {"coating_time_s", c.coating_time},
          {"parcel_diameter_m", c.parcel_diameter},
          {"parcel_diameter_source", c.parcel_diameter_source},
          {"grain_diameter_m", c.grain.grain_diameter},
          {"coating_density_kg_per_m3", c.grain.coating_density},
          {"coating_density_source", c.coating_density_source}};
}

Json unitsJson(const RunAnalysis& a) {
  return {{"mass", a.mass_unit.name},
          {"mass_ascii", a.mass_unit.ascii},
          {"mass_kg", a.mass_unit.si},
          {"thickness", a.thickness_unit.name},
          {"thickness_ascii", a.thickness_unit.ascii},
          {"thickness_m", a.thickness_unit.si}};
}

// The snapshots' statistics as one array per statistic
Json snapshotsJson(const std::vector<CoatingStatistics>& snapshots) {
  Json counts = Json::array();
  for (const auto& x : snapshots) counts.push_back(x.count);
  return {{"time", series(snapshots, &CoatingStatistics::time)},
          {"count", counts},
          {"mean", series(snapshots, &CoatingStatistics::mean)},
          {"std", series(snapshots, &CoatingStatistics::std_dev)},
          {"variance", series(snapshots, &CoatingStatistics::variance)},
          {"cv", series(snapshots, &CoatingStatistics::cv)},
          {"uncoated_share", series(snapshots, &CoatingStatistics::uncoated_share)},
          {"total", series(snapshots, &CoatingStatistics::total)},
          {"skewness", series(snapshots, &CoatingStatistics::skewness)},
          {"excess_kurtosis", series(snapshots, &CoatingStatistics::excess_kurtosis)}};
}

// The last snapshot per parcel, per grain and as a layer
Json endOfRunJson(const RunAnalysis& a) {
  const auto& l = a.snapshots.back();
  const auto& gs = a.conditions.grain;
  return {{"time", l.time},
          {"mean_per_parcel_kg", l.mean},
          {"sd_per_parcel_kg", l.std_dev},
          {"mean_per_grain_kg", gs.perGrain(l.mean)},
          {"sd_per_grain_kg", gs.perGrain(l.std_dev)},
          {"layer_thickness_m", gs.thickness(l.mean)},
          {"layer_thickness_sd_m", gs.thickness(l.std_dev)},
          {"cv", l.cv},
          {"uncoated_share", l.uncoated_share}};
}

Json optionsJson(const RunAnalysis& a, const ReportOptions& o) {
  Json criteria = Json::object();
  for (const auto& k : kMixingCriteria) criteria[k.name] = o.criteria.*k.value;
  return {{"fit_start", a.fit.t0},
          {"fit_end", a.fit.t1},
          {"coating_start", o.coating_start},
          {"predict_times", o.predict_times},
          {"predict_until", o.predict_until},
          {"band", o.band},
          {"uncoated_relative", o.uncoated_relative},
          {"criteria", criteria}};
}

// Eqs. 9-10 fitted, with the errors of a1 and a2 (HC3, classic, bootstrap)
Json fitJson(const RunAnalysis& a) {
  const GrowthFit& f = a.fit;
  const auto& b = a.bootstrap;
  return {{"ok", f.ok},
          {"problem", f.problem},
          {"t0", f.t0},
          {"t1", f.t1},
          {"coating_start", f.coating_start},
          {"time", f.time},
          {"tau", f.tau},
          {"mean", f.mean},
          {"variance", f.variance},
          {"mean_residual", f.mean_fit.residuals},
          {"variance_residual", f.variance_fit.residuals},
          {"a1", f.a1},
          {"a1_se", f.a1_se},
          {"a1_se_classic", f.a1_se_classic},
          {"a2", f.a2},
          {"a2_se", f.a2_se},
          {"a2_se_classic", f.a2_se_classic},
          {"bootstrap_ok", b.ok},
          {"bootstrap_problem", b.problem},
          {"bootstrap_resamples", b.resamples},
          {"bootstrap_snapshots", b.snapshots},
          {"a1_se_bootstrap", b.ok ? Json(b.a1_se) : Json()},
          {"a2_se_bootstrap", b.ok ? Json(b.a2_se) : Json()},
          {"a1_error", a.a1Error()},  // the one shown: bootstrap if available, else HC3
          {"a2_error", a.a2Error()},
          {"mean_relative_rms", f.mean_relative_rms},
          {"variance_relative_rms", f.variance_relative_rms}};
}

Json verdictJson(const RunAnalysis& a, const ReportOptions& o) {
  const MixingVerdict& v = a.verdict;
  Json normality = v.normality;
  normality["fading"] = v.fading_non_normal;
  normality["trend"] = v.trend;
  return {{"well_mixed", v.well_mixed},
          {"summary", v.summary()},
          {"short", shortVerdict(v)},
          {"plain", plainVerdict(a, o)},
          {"reasons", v.reasons},
          {"warnings", v.warnings},
          {"relaxed_criteria", v.relaxed},
          {"last_time", v.last_time},
          {"uncoated_share", v.uncoated_share},
          {"normality", normality},
          {"runs_mean", v.mean_runs},
          {"runs_variance", v.variance_runs}};
}

Json toJson(const RunAnalysis& a, const ReportOptions& o) {
  // Every number is in SI units (kg, m, s); `units` is what the pages and plots show.
  Json j = {{"format", "cosim-report"},
            {"version", 1},
            {"run", a.run.string()},
            {"label", a.label},
            {"run_status", a.run_status},
            {"units", unitsJson(a)},
            {"conditions", conditionsJson(a.conditions)},
            {"end_of_run", endOfRunJson(a)},
            {"options", optionsJson(a, o)},
            {"snapshots", snapshotsJson(a.snapshots)},
            {"histograms", a.histograms},
            {"fit", fitJson(a)},
            {"verdict", verdictJson(a, o)},
            {"cv_prediction", a.cv_prediction},
            {"distributions", a.distributions},
            {"prediction_check", a.prediction_check},
            {"window_study", a.window_study}};
  if (a.mass_balance) {
    j["mass_balance"] = *a.mass_balance;
  } else {
    j.update(Json{{"mass_balance", nullptr}, {"mass_balance_problem", a.mass_balance_problem}});
  }
  j.update(Json{{"wall_seconds", a.wall_seconds},
                {"steps", a.steps},
                {"zone_passes", zonePassesJson(a)},
                {"batch_model", batchJson(a)}});
  return j;
}

void writeRunTables(const RunAnalysis& a, const std::filesystem::path& dir) {
  writeZonePassTables(a, dir);
  {
    Csv c(dir / "statistics.csv",
          "time_s,count,mean_kg,std_kg,variance_kg2,cv,uncoated_share,min_kg,max_kg,total_kg,"
          "skewness,excess_kurtosis");
    for (const auto& s : a.snapshots) {
      c << s.time << static_cast<double>(s.count) << s.mean << s.std_dev << s.variance << s.cv
        << s.uncoated_share << s.min << s.max << s.total << s.skewness << s.excess_kurtosis;
      c.end();
    }
  }
  {
    Csv c(dir / "histograms.csv", "time_s,bin_low_kg,bin_high_kg,count");
    for (const auto& h : a.histograms) {
      for (std::size_t i = 0; i < h.histogram.counts.size(); ++i) {
        c << h.stats.time << h.histogram.edges[i] << h.histogram.edges[i + 1]
          << static_cast<double>(h.histogram.counts[i]);
        c.end();
      }
    }
  }
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Csv c(
        dir / "fit.csv",
        "parameter,value,standard_error_bootstrap,standard_error_hc3,standard_error_classic,unit");
    c << std::string("a1") << a.fit.a1 << (a.bootstrap.ok ? a.bootstrap.a1_se : nan) << a.fit.a1_se
      << a.fit.a1_se_classic << std::string("kg/s");
    c.end();
    c << std::string("a2") << a.fit.a2 << (a.bootstrap.ok ? a.bootstrap.a2_se : nan) << a.fit.a2_se
      << a.fit.a2_se_classic << std::string("kg/s^0.5");
    c.end();
  }
  {
    Csv c(dir / "fit_residuals.csv",
          "time_s,tau_s,mean_kg,mean_fit_kg,mean_residual_kg,variance_kg2,variance_fit_kg2,"
          "variance_residual_kg2");
    for (std::size_t i = 0; i < a.fit.tau.size() && a.fit.ok; ++i) {
      const double tau = a.fit.tau[i];
      c << a.fit.time[i] << tau << a.fit.mean[i] << a.fit.a1 * tau << a.fit.mean_fit.residuals[i]
        << a.fit.variance[i] << a.fit.a2 * a.fit.a2 * tau << a.fit.variance_fit.residuals[i];
      c.end();
    }
  }
  {
    Csv c(dir / "cv_prediction.csv", "tau_s,cv,cv_low,cv_high");
    for (std::size_t i = 0; i < a.cv_prediction.tau.size(); ++i) {
      c << a.cv_prediction.tau[i] << a.cv_prediction.cv[i] << a.cv_prediction.cv_low[i]
        << a.cv_prediction.cv_high[i];
      c.end();
    }
  }
  {
    Csv c(dir / "distributions.csv", "tau_s,mean_kg,sigma_kg,cv,sigma_low_kg,sigma_high_kg");
    for (const auto& d : a.distributions) {
      c << d.tau << d.mean << d.sigma << d.cv << d.sigma_low << d.sigma_high;
      c.end();
    }
  }
  {
    Csv c(dir / "prediction_check.csv",
          "time_s,simulated_mean_kg,predicted_mean_kg,mean_error,simulated_std_kg,predicted_std_kg,"
          "std_error,"
          "simulated_cv,predicted_cv,cv_error");
    for (const auto& p : a.prediction_check.points) {
      c << p.time << p.simulated_mean << p.predicted_mean << p.mean_error << p.simulated_std
        << p.predicted_std << p.std_error << p.simulated_cv << p.predicted_cv << p.cv_error;
      c.end();
    }
  }
  {
    Csv c(dir / "window_study.csv",
          "fit_end_s,wall_seconds,a1_kg_per_s,a1_se,a2_kg_per_sqrt_s,a2_se,cv_at_horizon,cv_at_run_"
          "end,"
          "cv_error_at_run_end");
    for (const auto& p : a.window_study.points) {
      c << p.t_end << p.wall_seconds << p.a1 << p.a1_se << p.a2 << p.a2_se << p.cv_horizon
        << p.cv_run_end << p.cv_run_end_error;
      c.end();
    }
  }
  if (a.mass_balance) {
    const MassBalance& b = *a.mass_balance;
    Csv c(dir / "mass_balance.csv", "quantity,value,unit");
    auto row = [&](const char* q, double v, const char* unit) {
      c << std::string(q) << v << std::string(unit);
      c.end();
    };
    row("precursor in", b.precursor_in, "kg");
    row("precursor out", b.precursor_out, "kg");
    row("held in gas (change)", b.held_change, "kg");
    row("expected coating", b.expected_coating, "kg");
    if (b.has_removed) row("removed from the gas by the coating sink", b.removed, "kg");
    row("coating on particles", b.obtained_coating, "kg");
    row("error", b.error, "kg");
    row("error %", b.error_percent, "%");
  }
}

}  // namespace cosim::analysis
