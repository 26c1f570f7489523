#include "cosim/analysis/summary.h"

namespace cosim::analysis {

Json toJson(const Summary& s) {
  Json j = Json::object();
  j["format"] = "cosim-summary";
  j["version"] = 1;
  j["scenario"] = s.scenario;
  j["run_id"] = s.run_id;
  j["status"] = s.status;
  if (!s.message.empty()) j["message"] = s.message;
  j["start_time_s"] = s.start_time;
  j["end_time_s"] = s.end_time;
  j["steps"] = static_cast<long long>(s.steps);
  Json& h = j["headline"] = Json::object();
  for (const auto& [k, v] : s.headline) h[k] = v;
  Json& t = j["timings_s"] = Json::object();
  for (const auto& [k, v] : s.timings) t[k] = v;
  if (!s.extra.isNull()) j["extra"] = s.extra;
  return j;
}

void writeSummary(const std::filesystem::path& path, const Summary& summary) {
  writeFileAtomically(path, toJson(summary).dump(2) + "\n");
}

}  // namespace cosim::analysis
