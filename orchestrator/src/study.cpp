#include "study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "checkpoints.h"
#include "cosim/analysis/files.h"
#include "cosim/analysis/summary.h"
#include "cosim/util/format.h"
#include "coupler.h"
#include "scenario.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

std::pair<std::string, std::vector<std::string>> parseVary(const std::string& text) {
  auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 >= text.size()) {
    throw InputError("--vary " + text +
                     ": expected key=v1,v2,... (e.g. --vary coupling.dem_steps=5,10,20)");
  }
  std::vector<std::string> values;
  std::stringstream ss(text.substr(eq + 1));
  for (std::string v; std::getline(ss, v, ',');) {
    if (v.empty()) throw InputError("--vary " + text + ": empty value in the list");
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
  std::vector<std::string> sets;    // the varied assignments, key=value
  std::vector<std::string> values;  // the varied values
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
  std::ostringstream expected;  // written the way the coupler writes it (YAML emitter)
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

// A variant stopped before its end (Ctrl-C, a kill, a job's time limit), or one that completed
// and is now asked to run longer, whose newest checkpoint was written with this scene up to what a
// resume may change (the end time, output, ...): the checkpoint's time, to resume from it instead
// of running the variant again.
std::optional<double> resumableCheckpoint(const fs::path& folder, const Scenario& sc) {
  if (!fs::is_directory(folder)) return std::nullopt;
  try {
    const auto newest = CheckpointStore(folder).newest();
    if (!newest) return std::nullopt;
    const CoupledState saved = readCoupledState(*newest);
    if (!sceneDifferences(YAML::Load(saved.scene), sc.resolved).empty()) return std::nullopt;
    if (saved.step >= sc.coupling.steps()) return std::nullopt;  // nothing left to run
    return saved.time;
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable: run the variant again
  }
}

// Every combination of the varied values, in the order the keys were given (the last varies
// fastest).
std::vector<Variant> combinations(const StudyOptions& opt) {
  std::vector<Variant> variants(1);
  for (const auto& [key, values] : opt.vary) {
    std::vector<Variant> next;
    for (const auto& v : variants) {
      for (const auto& value : values) {
        Variant n = v;
        n.sets.push_back(key + "=" + value);
        n.values.push_back(value);
        n.label += (n.label.empty() ? "" : " ") + key + "=" + value;
        next.push_back(n);
      }
    }
    variants = next;
  }
  return variants;
}

void printOutcome(const Variant& v, const std::string& before) {
  std::cout << "study:   " << before << "wall " << util::significant(v.wall, 6) << " s";
  for (const auto& o : v.observables)
    std::cout << ", " << o.name << " = " << util::significant(o.value, 6);
  if (v.exit_code != 0) std::cout << "  FAILED: " << v.message.substr(0, v.message.find('\n'));
  std::cout << std::endl;
}

// Renames `folder` to the first free FOLDER.previous-N and returns that name.
fs::path keepAside(const fs::path& folder) {
  for (int i = 1;; ++i) {
    const fs::path kept = folder.string() + ".previous-" + std::to_string(i);
    if (fs::exists(kept)) continue;
    fs::rename(folder, kept);
    return kept;
  }
}

// The variant's scene: the study's --set overrides, then the variant's own values.
Scenario variantScene(const StudyOptions& opt, const Variant& v) {
  std::vector<std::string> sets = opt.sets;
  sets.insert(sets.end(), v.sets.begin(), v.sets.end());
  return loadScenario(opt.scenario, sets, opt.unsets);
}

// Runs one variant in its folder, or reads it back when it completed before with the same scene.
void runVariant(const StudyOptions& opt, Variant& v) {
  Scenario sc = variantScene(opt, v);
  if (!opt.rerun && reuseCompleted(v.folder, sc, v)) {
    if (!opt.quiet) printOutcome(v, "done before (" + v.folder.string() + "): ");
    return;
  }
  RunOptions ro;
  ro.quiet = true;
  ro.stop = opt.stop;
  if (const auto from = !opt.rerun ? resumableCheckpoint(v.folder, sc) : std::nullopt) {
    // Stopped before (Ctrl-C, a kill, a job's time limit) with this scene: continue it
    ro.resume = v.folder;
    if (!opt.quiet)
      std::cout << "study:   resuming " << v.folder.string()
                << " from its checkpoint at t = " << util::significant(*from, 6) << " s"
                << std::endl;
  } else {
    // A folder holding a run of another scene (or a failed one) is kept under another name,
    // never written over; --rerun asks for the variant's folder to be replaced.
    if (!opt.rerun && fs::exists(v.folder) && !fs::is_empty(v.folder)) {
      const fs::path kept = keepAside(v.folder);
      if (!opt.quiet)
        std::cout << "study:   " << v.folder.string()
                  << " holds a run of another scene (or an unfinished one): kept as "
                  << kept.string() << std::endl;
    }
    ro.output = v.folder;
    ro.overwrite = true;
  }
  Coupler c(std::move(sc), ro);
  RunResult r = c.run();
  v.exit_code = r.exit_code;
  v.message = r.message;
  v.wall = r.wall_seconds;
  v.observables = r.observables;
  if (!opt.quiet) printOutcome(v, "");
}

// The variant that is the reference where an observable has no analytic one: --finest, else the
// slowest completed variant; -1 if none completed.
int finestVariant(const StudyOptions& opt, const std::vector<Variant>& variants) {
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
    throw InputError("--finest is larger than the number of variants");
  return finest;
}

// References, errors and the Pareto front on (wall time, worst error over the observables).
StudyRecord evaluate(const StudyOptions& opt, const Scenario& base,
                     const std::vector<Variant>& variants) {
  StudyRecord record;
  record.scenario = base.file.string();
  for (const auto& [key, values] : opt.vary) record.vary.push_back(key);
  const int finest = finestVariant(opt, variants);
  const Variant* ref = finest >= 0 && variants[static_cast<std::size_t>(finest)].exit_code == 0
                           ? &variants[static_cast<std::size_t>(finest)]
                           : nullptr;
  const std::size_t nobs = base.observables.size();
  for (std::size_t k = 0; k < nobs; ++k) {
    const std::string kind = base.observables[k].reference ? "analytic"
                             : ref                         ? "finest variant (" + ref->label + ")"
                                                           : "none";
    record.references.emplace_back(base.observables[k].name, kind);
  }
  std::vector<double> cost, worst;
  std::vector<std::size_t> ok;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const auto& v = variants[i];
    StudyRecord::Variant& r = record.variants.emplace_back();
    r.label = v.label;
    r.values = v.values;
    r.folder = v.folder.string();
    r.wall_s = v.wall;
    r.ok = v.exit_code == 0;
    if (!r.ok) {
      r.message = v.message;
      continue;
    }
    double w = 0;
    for (std::size_t k = 0; k < nobs; ++k) {
      const auto& o = v.observables[k];
      std::optional<double> reference = o.reference;
      if (!reference && !base.observables[k].reference && ref)
        reference = ref->observables[k].value;
      if (reference && std::isnan(*reference)) reference.reset();
      const auto error = relativeError(o.value, reference);
      const bool defined = error && !std::isnan(*error);
      r.observables.push_back(
          {base.observables[k].name, o.value, reference, defined ? error : std::nullopt});
      if (defined) w = std::max(w, *error);
    }
    ok.push_back(i);
    cost.push_back(v.wall);
    worst.push_back(w);
  }
  const std::vector<bool> front = paretoFront(cost, worst);
  for (std::size_t j = 0; j < ok.size(); ++j) record.variants[ok[j]].pareto = front[j];
  return record;
}

void drawPlot(const fs::path& folder, bool quiet) {
  std::string why;
  if (!analysis::drawStudyPlot(folder, why)) {
    std::cerr << "study: the plot was not drawn: " << why << "; the tables are complete\n";
  } else if (!quiet) {
    std::cout << "study: plot " << (folder / "error_vs_runtime.png").string() << "\n";
  }
}

}  // namespace

int runStudy(const StudyOptions& opt) {
  if (opt.vary.empty()) throw InputError("cosim study needs at least one --vary key=v1,v2,...");
  // Validate the base scenario first (clear errors before any run starts).
  Scenario base = loadScenario(opt.scenario, opt.sets, opt.unsets);
  if (base.observables.empty()) {
    throw InputError(
        base.file.string() +
        ": observables: the scenario defines no observables, so a study has nothing to measure; "
        "add e.g. observables: { v: { quantity: particles.velocity.z.mean } }");
  }

  std::vector<Variant> variants = combinations(opt);
  // Every variant's scene is read before the first one runs: a value outside a parameter's range
  // in the last of four hour-long variants is refused now, not after three of them.
  for (std::size_t i = 0; i < variants.size(); ++i) {
    try {
      variantScene(opt, variants[i]);
    } catch (const ScenarioError& e) {
      throw ScenarioError(fmt::format("study variant {} of {} ({}): {}", i + 1, variants.size(),
                                      variants[i].label, e.what()));
    }
  }
  const fs::path folder = opt.output.empty() ? fs::current_path() / "runs" / (base.name + "-study")
                                             : fs::absolute(opt.output);
  // The study's own files may replace only an earlier study's; checked before the first variant
  // runs, not after hours of them. Variant folders of another scene are kept aside (runVariant).
  analysis::claimOutputFiles({folder / "study.json", folder / "study.csv", folder / "study.md",
                              folder / "error_vs_runtime.png", folder / "plot_study.log"},
                             "\"vary\"", "cosim study -o");
  fs::create_directories(folder);

  for (std::size_t i = 0; i < variants.size(); ++i) {
    auto& v = variants[i];
    v.folder = folder / fmt::format("variant-{:02d}", i);
    if (!opt.quiet)
      std::cout << "study: [" << i + 1 << "/" << variants.size() << "] " << v.label << std::endl;
    runVariant(opt, v);
    if (v.exit_code == exit_code::interrupted) {
      // Ctrl-C or SIGTERM: the variant wrote a checkpoint; the same command continues the study
      std::cerr << "study: interrupted in " << v.folder.string()
                << "; run the same cosim study command again to continue: completed variants are "
                   "read back, this one resumes from its checkpoint\n";
      return exit_code::interrupted;
    }
  }

  const StudyRecord record = evaluate(opt, base, variants);
  analysis::writeStudyFiles(folder, record);
  if (!opt.quiet) {
    std::cout << "study: written " << (folder / "study.csv").string() << ", study.json, study.md\n"
              << analysis::studyMarkdown(record);
  }
  if (opt.plots) drawPlot(folder, opt.quiet);
  // The study's table is written; a failed variant's exit code says of which kind its failure
  // was (the first failed variant's, cosim/util/errors.h).
  for (const auto& v : variants) {
    if (v.exit_code != 0) return v.exit_code;
  }
  return exit_code::ok;
}

}  // namespace cosim::orchestrator
