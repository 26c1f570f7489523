// report.json and the CSV tables of one run's report.
#include <fmt/format.h>

#include <fstream>
#include <limits>
#include <stdexcept>

#include "cosim/analysis/report.h"
#include "report_internal.h"

namespace cosim::analysis {

namespace {
Json series(const std::vector<CoatingStatistics>& s, double CoatingStatistics::*member) {
  Json a = Json::array();
  for (const auto& x : s) a.push_back(x.*member);
  return a;
}

Json toJson(const CoatingStatistics& s) {
  Json j = Json::object();
  j["time"] = s.time;
  j["count"] = static_cast<unsigned long long>(s.count);
  j["mean"] = s.mean;
  j["std"] = s.std_dev;
  j["variance"] = s.variance;
  j["cv"] = s.cv;
  j["min"] = s.min;
  j["max"] = s.max;
  j["total"] = s.total;
  j["uncoated_threshold"] = s.uncoated_threshold;
  j["uncoated_share"] = s.uncoated_share;
  j["skewness"] = s.skewness;
  j["excess_kurtosis"] = s.excess_kurtosis;
  return j;
}

Json toJson(const RunsTest& r) {
  Json j = Json::object();
  j["valid"] = r.valid;
  j["positive"] = static_cast<unsigned long long>(r.positive);
  j["negative"] = static_cast<unsigned long long>(r.negative);
  j["runs"] = static_cast<unsigned long long>(r.runs);
  j["expected_runs"] = r.expected_runs;
  j["z"] = r.z;
  j["p_too_few"] = r.p_too_few;
  return j;
}

Json strings(const std::vector<std::string>& v) {
  Json a = Json::array();
  for (const auto& s : v) a.push_back(s);
  return a;
}

class Csv {
 public:
  Csv(const std::filesystem::path& path, const std::string& header) : path_(path), f_(path) {
    if (!f_) throw std::runtime_error("cannot write " + path.string());
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
  Json j = Json::object();
  j["flow_lpm"] = c.flow_lpm;
  j["superficial_velocity_m_per_s"] = c.superficial_velocity;
  j["u_mf_m_per_s"] = c.u_mf;
  j["u_mf_source"] = c.u_mf_source;
  j["u_over_umf"] = c.uOverUmf();
  j["nozzle_velocity_m_per_s"] = c.nozzle_velocity;
  j["precursor_mass_fraction"] = c.precursor_fraction;
  j["parcels"] = static_cast<unsigned long long>(c.parcels);
  j["cg"] = c.grain.cg;
  j["cg_source"] = c.cg_source;
  j["coating_time_s"] = c.coating_time;
  j["parcel_diameter_m"] = c.parcel_diameter;
  j["parcel_diameter_source"] = c.parcel_diameter_source;
  j["grain_diameter_m"] = c.grain.grain_diameter;
  j["coating_density_kg_per_m3"] = c.grain.coating_density;
  j["coating_density_source"] = c.coating_density_source;
  return j;
}

Json unitsJson(const RunAnalysis& a) {
  return {{"mass", a.mass_unit.name},
          {"mass_ascii", a.mass_unit.ascii},
          {"mass_kg", a.mass_unit.si},
          {"thickness", a.thickness_unit.name},
          {"thickness_ascii", a.thickness_unit.ascii},
          {"thickness_m", a.thickness_unit.si}};
}

Json toJson(const RunAnalysis& a, const ReportOptions& o) {
  Json j = Json::object();
  j["format"] = "cosim-report";
  j["version"] = 1;
  j["run"] = a.run.string();
  j["label"] = a.label;
  j["run_status"] = a.run_status;
  // Every number below is in SI units (kg, m, s); `units` is what the pages and plots show.
  j["units"] = unitsJson(a);
  j["conditions"] = conditionsJson(a.conditions);
  {
    const auto& l = a.snapshots.back();
    const auto& gs = a.conditions.grain;
    j["end_of_run"] = {{"time", l.time},
                       {"mean_per_parcel_kg", l.mean},
                       {"sd_per_parcel_kg", l.std_dev},
                       {"mean_per_grain_kg", gs.perGrain(l.mean)},
                       {"sd_per_grain_kg", gs.perGrain(l.std_dev)},
                       {"layer_thickness_m", gs.thickness(l.mean)},
                       {"layer_thickness_sd_m", gs.thickness(l.std_dev)},
                       {"cv", l.cv},
                       {"uncoated_share", l.uncoated_share}};
  }
  Json& opt = j["options"] = Json::object();
  opt["fit_start"] = a.fit.t0;
  opt["fit_end"] = a.fit.t1;
  opt["coating_start"] = o.coating_start;
  opt["predict_times"] = Json(o.predict_times);
  opt["predict_until"] = o.predict_until;
  opt["band"] = o.band;
  opt["uncoated_relative"] = o.uncoated_relative;
  Json& cr = opt["criteria"] = Json::object();
  for (const auto& k : kMixingCriteria) cr[k.name] = o.criteria.*k.value;

  Json& s = j["snapshots"] = Json::object();
  s["time"] = series(a.snapshots, &CoatingStatistics::time);
  Json counts = Json::array();
  for (const auto& x : a.snapshots) counts.push_back(static_cast<unsigned long long>(x.count));
  s["count"] = counts;
  s["mean"] = series(a.snapshots, &CoatingStatistics::mean);
  s["std"] = series(a.snapshots, &CoatingStatistics::std_dev);
  s["variance"] = series(a.snapshots, &CoatingStatistics::variance);
  s["cv"] = series(a.snapshots, &CoatingStatistics::cv);
  s["uncoated_share"] = series(a.snapshots, &CoatingStatistics::uncoated_share);
  s["total"] = series(a.snapshots, &CoatingStatistics::total);
  s["skewness"] = series(a.snapshots, &CoatingStatistics::skewness);
  s["excess_kurtosis"] = series(a.snapshots, &CoatingStatistics::excess_kurtosis);

  Json& hs = j["histograms"] = Json::array();
  for (const auto& h : a.histograms) {
    Json x = toJson(h.stats);
    x["requested"] = h.requested;
    x["edges"] = Json(h.histogram.edges);
    Json c = Json::array();
    for (auto n : h.histogram.counts) c.push_back(static_cast<unsigned long long>(n));
    x["counts"] = c;
    x["rule"] = h.histogram.rule;
    hs.push_back(x);
  }

  const GrowthFit& f = a.fit;
  Json& fit = j["fit"] = Json::object();
  fit["ok"] = f.ok;
  fit["problem"] = f.problem;
  fit["t0"] = f.t0;
  fit["t1"] = f.t1;
  fit["coating_start"] = f.coating_start;
  fit["time"] = Json(f.time);
  fit["tau"] = Json(f.tau);
  fit["mean"] = Json(f.mean);
  fit["variance"] = Json(f.variance);
  fit["mean_residual"] = Json(f.mean_fit.residuals);
  fit["variance_residual"] = Json(f.variance_fit.residuals);
  fit["a1"] = f.a1;
  fit["a1_se"] = f.a1_se;
  fit["a1_se_classic"] = f.a1_se_classic;
  fit["a2"] = f.a2;
  fit["a2_se"] = f.a2_se;
  fit["a2_se_classic"] = f.a2_se_classic;
  fit["bootstrap_ok"] = a.bootstrap.ok;
  fit["bootstrap_problem"] = a.bootstrap.problem;
  fit["bootstrap_resamples"] = static_cast<unsigned long long>(a.bootstrap.resamples);
  fit["bootstrap_snapshots"] = static_cast<unsigned long long>(a.bootstrap.snapshots);
  fit["a1_se_bootstrap"] = a.bootstrap.ok ? Json(a.bootstrap.a1_se) : Json();
  fit["a2_se_bootstrap"] = a.bootstrap.ok ? Json(a.bootstrap.a2_se) : Json();
  fit["a1_error"] = a.a1Error();  // the one shown: bootstrap if available, else HC3
  fit["a2_error"] = a.a2Error();
  fit["mean_relative_rms"] = f.mean_relative_rms;
  fit["variance_relative_rms"] = f.variance_relative_rms;

  const MixingVerdict& v = a.verdict;
  Json& vj = j["verdict"] = Json::object();
  vj["well_mixed"] = v.well_mixed;
  vj["summary"] = v.summary();
  vj["short"] = shortVerdict(v);
  vj["plain"] = plainVerdict(a, o);
  vj["reasons"] = strings(v.reasons);
  vj["warnings"] = strings(v.warnings);
  vj["relaxed_criteria"] = strings(v.relaxed);
  vj["last_time"] = v.last_time;
  vj["uncoated_share"] = v.uncoated_share;
  Json& nj = vj["normality"] = Json::object();
  nj["valid"] = v.normality.valid;
  nj["problem"] = v.normality.problem;
  nj["n"] = static_cast<unsigned long long>(v.normality.n);
  nj["skewness"] = v.normality.skewness;
  nj["kurtosis"] = v.normality.kurtosis;
  nj["z_skewness"] = v.normality.z_skewness;
  nj["z_kurtosis"] = v.normality.z_kurtosis;
  nj["k2"] = v.normality.k2;
  nj["p_value"] = v.normality.p_value;
  nj["fading"] = v.fading_non_normal;
  Json& tj = nj["trend"] = Json::object();
  tj["measured"] = v.trend.measured;
  tj["from"] = v.trend.from;
  tj["to"] = v.trend.to;
  tj["snapshots"] = static_cast<unsigned long long>(v.trend.snapshots);
  tj["skewness_decay"] = v.trend.skewness_decay;
  tj["kurtosis_decay"] = v.trend.kurtosis_decay;
  tj["at"] = v.trend.at;
  tj["projected_skewness"] = v.trend.projected_skewness;
  tj["projected_excess_kurtosis"] = v.trend.projected_excess_kurtosis;
  vj["runs_mean"] = toJson(v.mean_runs);
  vj["runs_variance"] = toJson(v.variance_runs);

  Json& cv = j["cv_prediction"] = Json::object();
  cv["tau"] = Json(a.cv_prediction.tau);
  cv["cv"] = Json(a.cv_prediction.cv);
  cv["cv_low"] = Json(a.cv_prediction.cv_low);
  cv["cv_high"] = Json(a.cv_prediction.cv_high);
  cv["band"] = a.cv_prediction.band;

  Json& ds = j["distributions"] = Json::array();
  for (const auto& d : a.distributions) {
    Json x = Json::object();
    x["tau"] = d.tau;
    x["mean"] = d.mean;
    x["sigma"] = d.sigma;
    x["cv"] = d.cv;
    x["sigma_low"] = d.sigma_low;
    x["sigma_high"] = d.sigma_high;
    ds.push_back(x);
  }

  Json& pc = j["prediction_check"] = Json::object();
  Json pts = Json::array();
  for (const auto& p : a.prediction_check.points) {
    Json x = Json::object();
    x["time"] = p.time;
    x["simulated_mean"] = p.simulated_mean;
    x["predicted_mean"] = p.predicted_mean;
    x["mean_error"] = p.mean_error;
    x["simulated_std"] = p.simulated_std;
    x["predicted_std"] = p.predicted_std;
    x["std_error"] = p.std_error;
    x["simulated_cv"] = p.simulated_cv;
    x["predicted_cv"] = p.predicted_cv;
    x["cv_error"] = p.cv_error;
    pts.push_back(x);
  }
  pc["points"] = pts;
  pc["max_abs_mean_error"] = a.prediction_check.max_abs_mean_error;
  pc["max_abs_std_error"] = a.prediction_check.max_abs_std_error;
  pc["max_abs_cv_error"] = a.prediction_check.max_abs_cv_error;

  Json& ws = j["window_study"] = Json::object();
  ws["horizon"] = a.window_study.horizon;
  ws["run_end"] = a.window_study.run_end;
  ws["simulated_cv_run_end"] = a.window_study.simulated_cv_run_end;
  Json wpts = Json::array();
  for (const auto& p : a.window_study.points) {
    Json x = Json::object();
    x["t_end"] = p.t_end;
    x["wall_seconds"] = p.wall_seconds;
    x["ok"] = p.ok;
    x["a1"] = p.a1;
    x["a1_se"] = p.a1_se;
    x["a2"] = p.a2;
    x["a2_se"] = p.a2_se;
    x["cv_horizon"] = p.cv_horizon;
    x["cv_run_end"] = p.cv_run_end;
    x["cv_run_end_error"] = p.cv_run_end_error;
    wpts.push_back(x);
  }
  ws["points"] = wpts;

  if (a.mass_balance) {
    const MassBalance& b = *a.mass_balance;
    Json& mb = j["mass_balance"] = Json::object();
    mb["precursor_in"] = b.precursor_in;
    mb["precursor_out"] = b.precursor_out;
    mb["held_start"] = b.held_start;
    mb["held_end"] = b.held_end;
    mb["held_change"] = b.held_change;
    mb["expected_coating"] = b.expected_coating;
    mb["coated_start"] = b.coated_start;
    mb["coated_end"] = b.coated_end;
    mb["obtained_coating"] = b.obtained_coating;
    mb["error"] = b.error;
    mb["error_percent"] = b.error_percent;
    mb["initial_state"] = b.initial_state;
    mb["obtained_source"] = b.obtained_source;
    mb["removed"] = b.has_removed ? Json(b.removed) : Json();
    mb["pending"] = b.has_removed ? Json(b.pending) : Json();
  } else {
    j["mass_balance"] = nullptr;
    j["mass_balance_problem"] = a.mass_balance_problem;
  }
  j["wall_seconds"] = a.wall_seconds;
  j["steps"] = static_cast<unsigned long long>(a.steps);
  j["zone_passes"] = zonePassesJson(a);
  j["batch_model"] = batchJson(a);
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
