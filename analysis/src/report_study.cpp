// The files of `cosim study`: study.json, study.csv, study.md, and its plot.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "cosim/analysis/report.h"
#include "cosim/analysis/study.h"
#include "cosim/util/format.h"

namespace cosim::analysis {

namespace {
double orNaN(const std::optional<double>& v) {
  return v ? *v : std::numeric_limits<double>::quiet_NaN();
}
std::optional<double> number(const Json& o, const char* key) {
  const auto it = o.find(key);
  if (it == o.end() || it->is_null()) return std::nullopt;
  return it->get<double>();
}
}  // namespace

namespace {
// One variant: what it set, where it ran, what it cost and measured
Json variantJson(const StudyRecord::Variant& v) {
  Json observables = Json::object();
  for (const auto& o : v.observables) {
    Json x = {{"value", o.value}};
    if (o.reference) x.update(Json{{"reference", *o.reference}});
    if (o.error) x.update(Json{{"error", *o.error}});
    observables[o.name] = x;
  }
  Json r = {{"label", v.label},
            {"values", v.values},
            {"folder", v.folder},
            {"wall_s", v.wall_s},
            {"ok", v.ok}};
  if (!v.ok) r.update(Json{{"message", v.message}});
  r.update(Json{{"pareto", v.pareto}, {"observables", observables}});
  return r;
}
}  // namespace

void to_json(Json& j, const StudyRecord& s) {
  Json references = Json::object();
  for (const auto& [name, kind] : s.references) references[name] = kind;
  Json variants = Json::array();
  for (const auto& v : s.variants) variants.push_back(variantJson(v));
  j = {{"scenario", s.scenario},
       {"vary", s.vary},
       {"references", references},
       {"variants", variants}};
}

void from_json(const Json& j, StudyRecord& s) {
  s = StudyRecord{};
  j.at("scenario").get_to(s.scenario);
  j.at("vary").get_to(s.vary);
  for (const auto& [name, kind] : j.at("references").items())
    s.references.emplace_back(name, kind.get<std::string>());
  for (const auto& r : j.at("variants")) {
    StudyRecord::Variant& v = s.variants.emplace_back();
    r.at("label").get_to(v.label);
    if (const auto values = r.find("values"); values != r.end()) values->get_to(v.values);
    r.at("folder").get_to(v.folder);
    r.at("wall_s").get_to(v.wall_s);
    r.at("ok").get_to(v.ok);
    v.message = r.value("message", std::string());
    r.at("pareto").get_to(v.pareto);
    for (const auto& [name, o] : r.at("observables").items()) {
      StudyRecord::Observable& x = v.observables.emplace_back();
      x.name = name;
      x.value = orNaN(number(o, "value"));
      x.reference = number(o, "reference");
      x.error = number(o, "error");
    }
  }
}

namespace {

std::string studyCsv(const StudyRecord& s) {
  std::string csv = "variant";
  for (const auto& key : s.vary) csv += "," + key;
  csv += ",wall_s,status";
  for (const auto& [name, kind] : s.references)
    csv += fmt::format(",{0},{0}_reference,{0}_error", name);
  csv += ",pareto\n";
  for (std::size_t i = 0; i < s.variants.size(); ++i) {
    const auto& v = s.variants[i];
    csv += std::to_string(i);
    for (const auto& value : v.values) csv += "," + value;
    csv += fmt::format(",{:.10g},{}", v.wall_s, v.ok ? "ok" : "failed");
    for (std::size_t k = 0; k < s.references.size(); ++k) {
      if (!v.ok || k >= v.observables.size()) {
        csv += ",,,";
        continue;
      }
      const auto& o = v.observables[k];
      csv += fmt::format(",{:.12g},{:.12g},{:.12g}", o.value, orNaN(o.reference), orNaN(o.error));
    }
    csv += v.pareto ? ",1\n" : ",0\n";
  }
  return csv;
}

}  // namespace

std::string studyMarkdown(const StudyRecord& s) {
  std::string md = "| variant | wall [s] |";
  for (const auto& [name, kind] : s.references) md += " " + name + " | error |";
  md += " Pareto |\n|---|---|";
  for (std::size_t k = 0; k < s.references.size(); ++k) md += "---|---|";
  md += "---|\n";
  for (const auto& v : s.variants) {
    md += fmt::format("| {} | {:.6g} |", v.label, v.wall_s);
    for (std::size_t k = 0; k < s.references.size(); ++k) {
      if (!v.ok || k >= v.observables.size()) {
        md += " failed | |";
        continue;
      }
      const auto& o = v.observables[k];
      md += fmt::format(" {:.6g} | {} |", o.value, o.error ? util::significant(*o.error, 6) : "-");
    }
    md += v.pareto ? " yes |\n" : " |\n";
  }
  md += "\nReferences: ";
  for (std::size_t k = 0; k < s.references.size(); ++k)
    md += (k ? "; " : "") + s.references[k].first + ": " + s.references[k].second;
  md +=
      ". Error = |value - reference| / |reference|; Pareto = no other variant is both faster "
      "and more accurate (worst error over the observables).\n";
  return md;
}

void writeStudyFiles(const std::filesystem::path& folder, const StudyRecord& study) {
  writeFileAtomically(folder / "study.csv", studyCsv(study));
  writeJsonFile(folder / "study.json", Json(study), 2);
  writeFileAtomically(folder / "study.md", studyMarkdown(study));
}

bool drawStudyPlot(const std::filesystem::path& folder, std::string& message) {
  return runPlotScript("plot_study.py", folder, folder / "plot_study.log", message);
}

}  // namespace cosim::analysis
