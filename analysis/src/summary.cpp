#include "cosim/analysis/summary.h"

#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "cosim/util/errors.h"

namespace cosim::analysis {

namespace {

using Named = std::vector<std::pair<std::string, double>>;

// name -> number objects in the order given; NaN and infinities are written as null
Json namedNumbers(const Named& values) {
  Json j = Json::object();
  for (const auto& [k, v] : values) j[k] = v;
  return j;
}

// null reads back as NaN (what a non-finite number was written as)
double number(const Json& j) {
  return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>();
}

Named readNamedNumbers(const Json& j) {
  Named values;
  for (const auto& [k, v] : j.items()) values.emplace_back(k, number(v));
  return values;
}

// Each observable: its value (or why it has none), its reference and error where it has them
Json observablesJson(const std::vector<ObservableValue>& observables) {
  Json obs = Json::object();
  for (const auto& o : observables) {
    Json j = o.undefined.empty() ? Json{{"value", o.value}} : Json{{"undefined", o.undefined}};
    if (o.reference) j.update(Json{{"reference", *o.reference}});
    if (o.relative_error) j.update(Json{{"relative_error", *o.relative_error}});
    obs[o.name] = j;
  }
  return obs;
}

std::vector<ObservableValue> readObservables(const Json& obs) {
  std::vector<ObservableValue> observables;
  for (const auto& [name, j] : obs.items()) {
    ObservableValue o;
    o.name = name;
    const auto value = j.find("value");
    if (value != j.end() && value->is_number()) {
      o.value = value->get<double>();
    } else {
      o.value = std::numeric_limits<double>::quiet_NaN();
      o.undefined = j.value("undefined", std::string("no value"));
    }
    if (const auto r = j.find("reference"); r != j.end() && r->is_number())
      o.reference = r->get<double>();
    if (const auto e = j.find("relative_error"); e != j.end() && e->is_number())
      o.relative_error = e->get<double>();
    observables.push_back(std::move(o));
  }
  return observables;
}

}  // namespace

void to_json(Json& j, const Summary& s) {
  j = {{"format", "cosim-summary"},
       {"version", 1},
       {"scenario", s.scenario},
       {"run_id", s.run_id},
       {"status", s.status}};
  if (!s.message.empty()) j["message"] = s.message;
  j.update(Json{{"start_time_s", s.start_time},
                {"end_time_s", s.end_time},
                {"steps", s.steps},
                {"headline", namedNumbers(s.headline)},
                {"timings_s", namedNumbers(s.timings)},
                {"extra",
                 {{"parameters", namedNumbers(s.parameters)},
                  {"coupling_dt", s.coupling_dt},
                  {"dem_steps", s.dem_steps},
                  {"cg", s.cg},
                  {"coating", s.coating},
                  {"observables", observablesJson(s.observables)}}}});
}

void from_json(const Json& j, Summary& s) {
  if (j.value("format", std::string()) != "cosim-summary")
    throw InputError("not a cosim summary (\"format\" is not \"cosim-summary\")");
  s = Summary{};
  j.at("scenario").get_to(s.scenario);
  j.at("run_id").get_to(s.run_id);
  j.at("status").get_to(s.status);
  s.message = j.value("message", std::string());
  s.start_time = number(j.at("start_time_s"));
  s.end_time = number(j.at("end_time_s"));
  j.at("steps").get_to(s.steps);
  s.headline = readNamedNumbers(j.at("headline"));
  s.timings = readNamedNumbers(j.at("timings_s"));
  const Json& extra = j.at("extra");
  s.parameters = readNamedNumbers(extra.at("parameters"));
  s.coupling_dt = number(extra.at("coupling_dt"));
  extra.at("dem_steps").get_to(s.dem_steps);
  s.cg = number(extra.at("cg"));
  extra.at("coating").get_to(s.coating);
  s.observables = readObservables(extra.at("observables"));
}

void writeSummary(const std::filesystem::path& path, const Summary& summary) {
  const Json json(summary);
  try {
    writeJsonFile(path, json, 2);
  } catch (const std::runtime_error& e) {
    if (!std::filesystem::exists(path)) throw;
    try {
      overwriteFile(path, jsonText(json, 2));
    } catch (const std::runtime_error& again) {
      throw Error(kindOf(again, ErrorKind::resource),
                  std::string(e.what()) + "; in place: " + again.what());
    }
  }
}

Summary readSummary(const std::filesystem::path& path) {
  const Json j = readJsonFile(path);
  try {
    return j.get<Summary>();
  } catch (const std::exception& e) {
    throw InputError(path.string() + " is not a cosim summary: " + e.what());
  }
}

}  // namespace cosim::analysis
