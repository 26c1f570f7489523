#include "study.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cosim/analysis/report.h"
#include "cosim/analysis/summary.h"
#include "coupler.h"
#include "scenario.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

std::pair<std::string, std::vector<std::string>> parseVary(const std::string& text) {
  auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 >= text.size()) {
    throw std::runtime_error("--vary " + text +
                             ": expected key=v1,v2,... (e.g. --vary coupling.dem_steps=5,10,20)");
  }
  std::vector<std::string> values;
  std::stringstream ss(text.substr(eq + 1));
  for (std::string v; std::getline(ss, v, ',');) {
    if (v.empty()) throw std::runtime_error("--vary " + text + ": empty value in the list");
    values.push_back(v);
  }
  return {text.substr(0, eq), values};
}

std::vector<bool> paretoFront(const std::vector<double>& cost, const std::vector<double>& error) {
  std::vector<bool> front(cost.size(), true);
  for (std::size_t i = 0; i < cost.size(); ++i) {
    for (std::size_t j = 0; j < cost.size() && front[i]; ++j) {
      if (i == j) continue;
      const bool no_worse = cost[j] <= cost[i] && error[j] <= error[i];
      const bool better = cost[j] < cost[i] || error[j] < error[i];
      if (no_worse && better) front[i] = false;
    }
  }
  return front;
}

namespace {

struct Variant {
  std::vector<std::string> sets;  // the varied assignments
  std::string label;
  fs::path folder;
  int exit_code = 0;
  std::string message;
  double wall = 0;
  std::vector<ObservableValue> observables;
};

// A variant already run with exactly this scene (same resolved scenario) and completed: its
// observables and wall time are read back instead of running it again, so an interrupted or
// re-analysed study (another --finest) costs nothing for what is done.
bool reuseCompleted(const fs::path& folder, const Scenario& sc, Variant& v) {
  std::ifstream ry(folder / "scenario.resolved.yaml");
  if (!ry || !fs::exists(folder / analysis::kSummaryFile)) return false;
  std::stringstream a;
  a << ry.rdbuf();
  const std::string resolved = a.str();
  const auto nl = resolved.find('\n');
  std::ostringstream expected;  // written the way the coupler writes it
  expected << sc.resolved << "\n";
  if (nl == std::string::npos || resolved.substr(nl + 1) != expected.str()) return false;
  analysis::Summary summary;
  try {
    summary = analysis::readSummary(folder / analysis::kSummaryFile);
  } catch (const std::exception&) {
    return false;
  }
  if (summary.status != "completed") return false;
  const auto total = std::find_if(summary.timings.begin(), summary.timings.end(),
                                  [](const auto& t) { return t.first == "total"; });
  if (total == summary.timings.end()) return false;
  std::vector<ObservableValue> values;
  for (const auto& spec : sc.observables) {
    const auto o = std::find_if(summary.observables.begin(), summary.observables.end(),
                                [&](const auto& x) { return x.name == spec.name; });
    if (o == summary.observables.end()) return false;
    ObservableValue ov;
    ov.name = spec.name;
    ov.reference = spec.reference;
    ov.value = o->value;
    if (o->undefined.empty() && !std::isnan(o->value)) {
      ov.relative_error = relativeError(ov.value, ov.reference);
    } else {
      ov.undefined = o->undefined.empty() ? "no value" : o->undefined;
    }
    values.push_back(ov);
  }
  v.wall = total->second;
  v.observables = values;
  v.exit_code = 0;
  return true;
}

std::string fmt(double v) {
  std::ostringstream os;
  os << std::setprecision(6) << v;
  return os.str();
}

}  // namespace

void to_json(analysis::Json& j, const StudyRecord& s) {
  j = analysis::Json::object();
  j["scenario"] = s.scenario;
  j["vary"] = s.vary;
  analysis::Json& refs = j["references"] = analysis::Json::object();
  for (const auto& [name, kind] : s.references) refs[name] = kind;
  analysis::Json& rows = j["variants"] = analysis::Json::array();
  for (const auto& v : s.variants) {
    analysis::Json& r = rows.emplace_back(analysis::Json::object());
    r["label"] = v.label;
    r["folder"] = v.folder;
    r["wall_s"] = v.wall_s;
    r["ok"] = v.ok;
    if (!v.ok) r["message"] = v.message;
    r["pareto"] = v.pareto;
    analysis::Json& obs = r["observables"] = analysis::Json::object();
    for (const auto& o : v.observables) {
      analysis::Json& x = obs[o.name] = analysis::Json::object();
      x["value"] = o.value;
      if (o.error) x["error"] = *o.error;
    }
  }
}

void from_json(const analysis::Json& j, StudyRecord& s) {
  s = StudyRecord{};
  j.at("scenario").get_to(s.scenario);
  j.at("vary").get_to(s.vary);
  for (const auto& [name, kind] : j.at("references").items())
    s.references.emplace_back(name, kind.get<std::string>());
  for (const auto& r : j.at("variants")) {
    StudyRecord::Variant& v = s.variants.emplace_back();
    r.at("label").get_to(v.label);
    r.at("folder").get_to(v.folder);
    r.at("wall_s").get_to(v.wall_s);
    r.at("ok").get_to(v.ok);
    v.message = r.value("message", std::string());
    r.at("pareto").get_to(v.pareto);
    for (const auto& [name, o] : r.at("observables").items()) {
      StudyRecord::Observable& x = v.observables.emplace_back();
      x.name = name;
      const auto& value = o.at("value");
      x.value = value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>();
      if (const auto e = o.find("error"); e != o.end()) x.error = e->get<double>();
    }
  }
}

int runStudy(const StudyOptions& opt) {
  if (opt.vary.empty())
    throw std::runtime_error("cosim study needs at least one --vary key=v1,v2,...");
  // Validate the base scenario first (clear errors before any run starts).
  Scenario base = loadScenario(opt.scenario, opt.sets, opt.unsets);
  if (base.observables.empty()) {
    throw std::runtime_error(
        base.file.string() +
        ": observables: the scenario defines no observables, so a study has nothing to measure; "
        "add e.g. observables: { v: { quantity: particles.velocity.z.mean } }");
  }
  fs::path folder = opt.output.empty() ? fs::current_path() / "runs" / (base.name + "-study")
                                       : fs::absolute(opt.output);
  fs::create_directories(folder);

  // Cartesian product of the varied values.
  std::vector<Variant> variants(1);
  for (const auto& [key, values] : opt.vary) {
    std::vector<Variant> next;
    for (const auto& v : variants) {
      for (const auto& value : values) {
        Variant n = v;
        n.sets.push_back(key + "=" + value);
        n.label += (n.label.empty() ? "" : " ") + key + "=" + value;
        next.push_back(n);
      }
    }
    variants = next;
  }
  for (std::size_t i = 0; i < variants.size(); ++i) {
    auto& v = variants[i];
    std::ostringstream name;
    name << "variant-" << std::setw(2) << std::setfill('0') << i;
    v.folder = folder / name.str();
    std::vector<std::string> sets = opt.sets;
    sets.insert(sets.end(), v.sets.begin(), v.sets.end());
    if (!opt.quiet)
      std::cout << "study: [" << i + 1 << "/" << variants.size() << "] " << v.label << std::endl;
    Scenario sc = loadScenario(opt.scenario, sets, opt.unsets);
    if (!opt.rerun && reuseCompleted(v.folder, sc, v)) {
      if (!opt.quiet) {
        std::cout << "study:   done before (" << v.folder.string() << "): wall " << fmt(v.wall)
                  << " s";
        for (const auto& o : v.observables) std::cout << ", " << o.name << " = " << fmt(o.value);
        std::cout << std::endl;
      }
      continue;
    }
    RunOptions ro;
    ro.quiet = true;
    ro.output = v.folder;
    ro.overwrite = true;
    Coupler c(std::move(sc), ro);
    RunResult r = c.run();
    v.exit_code = r.exit_code;
    v.message = r.message;
    v.wall = r.wall_seconds;
    v.observables = r.observables;
    if (!opt.quiet) {
      std::cout << "study:   wall " << fmt(v.wall) << " s";
      for (const auto& o : v.observables) std::cout << ", " << o.name << " = " << fmt(o.value);
      if (r.exit_code != 0) std::cout << "  FAILED: " << r.message.substr(0, r.message.find('\n'));
      std::cout << std::endl;
    }
  }

  // Reference per observable: analytic, else the finest variant.
  int finest = opt.finest;
  if (finest < 0) {
    double slowest = -1;
    for (std::size_t i = 0; i < variants.size(); ++i) {
      if (variants[i].exit_code == 0 && variants[i].wall > slowest) {
        slowest = variants[i].wall;
        finest = static_cast<int>(i);
      }
    }
  }
  if (finest >= static_cast<int>(variants.size()))
    throw std::runtime_error("--finest is larger than the number of variants");
  const std::size_t nobs = base.observables.size();
  std::vector<std::string> ref_kind(nobs);
  std::vector<double> ref(nobs, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < nobs; ++k) {
    if (base.observables[k].reference) {
      ref_kind[k] = "analytic";
    } else if (finest >= 0 && variants[static_cast<std::size_t>(finest)].exit_code == 0) {
      ref_kind[k] = "finest variant (" + variants[static_cast<std::size_t>(finest)].label + ")";
      ref[k] = variants[static_cast<std::size_t>(finest)].observables[k].value;
    } else {
      ref_kind[k] = "none";
    }
  }
  // errors[v][k]
  std::vector<std::vector<double>> err(
      variants.size(), std::vector<double>(nobs, std::numeric_limits<double>::quiet_NaN()));
  for (std::size_t i = 0; i < variants.size(); ++i) {
    if (variants[i].exit_code != 0) continue;
    for (std::size_t k = 0; k < nobs; ++k) {
      const auto& o = variants[i].observables[k];
      std::optional<double> r = o.reference;
      if (!r && !std::isnan(ref[k])) r = ref[k];
      if (auto e = relativeError(o.value, r)) err[i][k] = *e;
    }
  }
  // Pareto front on (wall, worst error over the observables) among successful variants.
  std::vector<double> cost, worst;
  std::vector<std::size_t> ok;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    if (variants[i].exit_code != 0) continue;
    double w = 0;
    for (double e : err[i]) w = std::isnan(e) ? w : std::max(w, e);
    ok.push_back(i);
    cost.push_back(variants[i].wall);
    worst.push_back(w);
  }
  std::vector<bool> front_ok = paretoFront(cost, worst);
  std::vector<bool> front(variants.size(), false);
  for (std::size_t j = 0; j < ok.size(); ++j) front[ok[j]] = front_ok[j];

  // study.csv
  {
    std::ofstream csv(folder / "study.csv");
    csv << "variant";
    for (const auto& [key, values] : opt.vary) csv << "," << key;
    csv << ",wall_s,status";
    for (const auto& o : base.observables)
      csv << "," << o.name << "," << o.name << "_reference," << o.name << "_error";
    csv << ",pareto\n";
    for (std::size_t i = 0; i < variants.size(); ++i) {
      const auto& v = variants[i];
      csv << i;
      for (const auto& s : v.sets) csv << "," << s.substr(s.find('=') + 1);
      csv << "," << std::setprecision(10) << v.wall << "," << (v.exit_code == 0 ? "ok" : "failed");
      for (std::size_t k = 0; k < nobs; ++k) {
        if (v.exit_code != 0) {
          csv << ",,,";
          continue;
        }
        const auto& o = v.observables[k];
        const double r = o.reference ? *o.reference : ref[k];
        csv << "," << std::setprecision(12) << o.value << "," << r << "," << err[i][k];
      }
      csv << "," << (front[i] ? 1 : 0) << "\n";
    }
  }
  // study.json
  StudyRecord record;
  record.scenario = base.file.string();
  for (const auto& [key, values] : opt.vary) record.vary.push_back(key);
  for (std::size_t k = 0; k < nobs; ++k)
    record.references.emplace_back(base.observables[k].name, ref_kind[k]);
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const auto& v = variants[i];
    StudyRecord::Variant& r = record.variants.emplace_back();
    r.label = v.label;
    r.folder = v.folder.string();
    r.wall_s = v.wall;
    r.ok = v.exit_code == 0;
    if (!r.ok) r.message = v.message;
    r.pareto = front[i];
    for (std::size_t k = 0; k < nobs && r.ok; ++k) {
      r.observables.push_back({base.observables[k].name, v.observables[k].value,
                               std::isnan(err[i][k]) ? std::nullopt : std::optional(err[i][k])});
    }
  }
  analysis::writeJsonFile(folder / "study.json", analysis::Json(record), 2);
  // study.md: the table for docs/
  {
    std::ofstream md(folder / "study.md");
    md << "| variant | wall [s] |";
    for (const auto& o : base.observables) md << " " << o.name << " | error |";
    md << " Pareto |\n|---|---|";
    for (std::size_t k = 0; k < nobs; ++k) md << "---|---|";
    md << "---|\n";
    for (std::size_t i = 0; i < variants.size(); ++i) {
      const auto& v = variants[i];
      md << "| " << v.label << " | " << fmt(v.wall) << " |";
      for (std::size_t k = 0; k < nobs; ++k) {
        if (v.exit_code != 0) {
          md << " failed | |";
          continue;
        }
        md << " " << fmt(v.observables[k].value) << " | "
           << (std::isnan(err[i][k]) ? std::string("-") : fmt(err[i][k])) << " |";
      }
      md << (front[i] ? " yes |" : " |") << "\n";
    }
    md << "\nReferences: ";
    for (std::size_t k = 0; k < nobs; ++k)
      md << (k ? "; " : "") << base.observables[k].name << ": " << ref_kind[k];
    md << ". Error = |value - reference| / |reference|; Pareto = no other variant is both faster "
          "and more accurate (worst error over the observables).\n";
  }
  if (!opt.quiet) {
    std::cout << "study: written " << (folder / "study.csv").string() << ", study.json, study.md\n";
    std::ifstream md(folder / "study.md");
    std::cout << md.rdbuf();
  }
  if (opt.plots) {
    const char* env = std::getenv("COSIM_SCRIPTS");
    fs::path script =
        env ? fs::path(env) / "plot_study.py" : fs::path(COSIM_SCRIPTS_DIR) / "plot_study.py";
    std::string why;
    auto python = analysis::findPython(why);
    const std::string cmd = python ? "MPLBACKEND=Agg '" + *python + "' '" + script.string() +
                                         "' '" + folder.string() + "'"
                                   : "";
    if (!python) {
      std::cerr << "study: the plot was not drawn: " << why << "; the tables are complete\n";
    } else if (std::system(cmd.c_str()) != 0) {
      std::cerr << "study: the plot script failed (" << cmd << "); the tables are complete\n";
    } else if (!opt.quiet) {
      std::cout << "study: plot " << (folder / "error_vs_runtime.png").string() << "\n";
    }
  }
  for (const auto& v : variants) {
    if (v.exit_code != 0) return 3;
  }
  return 0;
}

}  // namespace cosim::orchestrator
