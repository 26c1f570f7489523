#include "checkpoints.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/link/zone_pass_tracker.h"
#include "cosim/util/errors.h"
#include "cosim/util/format.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;
using Json = analysis::Json;

namespace {

constexpr const char* kStateFile = "orchestrator.json";
constexpr const char* kPartialPrefix = ".partial-";

Json toJson(const CoupledState& s) {
  const auto& b = s.balance;
  Json owed = Json::array();
  for (const auto& [id, m] : s.pending) owed.push_back({id, m});
  Json monitor = {{"courant_warned", s.monitor.courant_warned}};
  if (s.monitor.baseline) monitor["baseline"] = *s.monitor.baseline;
  Json j = {{"format", "cosim-checkpoint"},
            {"version", 1},
            {"step", s.step},
            {"time", s.time},
            {"balance",
             {{"in", b.in},
              {"out", b.out},
              {"held", b.held},
              {"held_start", b.held_start},
              {"removed", b.removed},
              {"credited", b.credited},
              {"left_domain", b.left_domain},
              {"any_left", b.any_left},
              {"deleted_coating", b.deleted_coating},
              {"coating_initial", b.coating_initial}}},
            {"pending", owed},
            {"totals", s.totals},
            {"monitor", monitor},
            {"initial_count", s.initial_count},
            {"initial_row_written", s.initial_row_written},
            {"series_rows", s.series_rows},
            {"next_output", s.next_output},
            {"wall_seconds", s.wall_seconds},
            {"phases", s.phases},
            {"compute", s.compute},
            {"scene", s.scene},
            {"particle_digest", s.particle_digest}};
  if (s.clock) j["clock"] = {{"start", s.clock->start}, {"dt", s.clock->dt}};
  if (s.zone_passes) {
    Json open = Json::array();
    for (const auto& [id, p] : s.zone_passes->open)
      open.push_back({id, p.entry_time, p.coating, p.at_start});
    j["zone_passes"] = {{"rows", s.zone_passes->rows},
                        {"coating_outside", s.zone_passes->coating_outside},
                        {"open", open}};
  }
  if (s.wake) {
    Json parcels = Json::array();  // [id, anchor (3), y (3 per mode), K, v (3), dt]
    for (const auto& [id, p] : *s.wake) parcels.push_back({id, p.anchor, p.y, p.K, p.v, p.dt});
    j["wake"] = {{"modes", models::WakeKernel::kModes}, {"parcels", parcels}};
  }
  if (s.sample_ahead) {  // doubles as JSON numbers round-trip exactly (shortest form)
    j["sample_ahead"] = {{"ids", s.sample_ahead->ids}, {"fields", s.sample_ahead->fields()}};
  }
  return j;
}

CoupledState fromJson(const Json& j) {
  CoupledState s;
  s.step = j.at("step").get<std::uint64_t>();
  s.time = j.at("time").get<double>();
  if (j.contains("clock"))
    s.clock =
        StepClock{j.at("clock").at("start").get<double>(), j.at("clock").at("dt").get<double>()};
  const Json& b = j.at("balance");
  s.balance.in = b.at("in");
  s.balance.out = b.at("out");
  s.balance.held = b.at("held");
  s.balance.held_start = b.at("held_start");
  s.balance.removed = b.at("removed");
  s.balance.credited = b.at("credited");
  s.balance.left_domain = b.at("left_domain");
  s.balance.any_left = b.at("any_left");
  s.balance.deleted_coating = b.at("deleted_coating");
  s.balance.coating_initial = b.at("coating_initial");
  for (const auto& e : j.at("pending")) s.pending[e.at(0).get<std::int64_t>()] = e.at(1);
  s.totals = j.at("totals").get<std::map<std::string, double>>();
  s.monitor.courant_warned = j.at("monitor").at("courant_warned");
  if (j.at("monitor").contains("baseline"))
    s.monitor.baseline = j.at("monitor").at("baseline").get<std::array<double, 4>>();
  s.initial_count = j.at("initial_count");
  s.initial_row_written = j.at("initial_row_written");
  s.series_rows = j.at("series_rows");
  s.next_output = j.at("next_output");
  s.wall_seconds = j.at("wall_seconds");
  s.phases = j.at("phases").get<std::map<std::string, double>>();
  s.compute = j.at("compute").get<std::map<std::string, double>>();
  s.scene = j.at("scene");
  if (j.contains("particle_digest"))
    s.particle_digest = j.at("particle_digest").get<std::map<std::string, std::string>>();
  if (j.contains("zone_passes")) {
    const Json& z = j.at("zone_passes");
    ZonePassRecorder::State zp;
    zp.rows = z.at("rows");
    zp.coating_outside = z.at("coating_outside");
    for (const auto& e : z.at("open")) {
      zp.open[e.at(0).get<std::int64_t>()] = {e.at(1).get<double>(), e.at(2).get<double>(),
                                              e.at(3).get<bool>()};
    }
    s.zone_passes = std::move(zp);
  }
  if (j.contains("wake")) {
    const Json& w = j.at("wake");
    if (w.at("modes").get<std::size_t>() != models::WakeKernel::kModes) {
      throw InputError(fmt::format(
          "its wake history has {} modes per parcel, this cosim keeps {} (written by another "
          "version of undisturbed_velocity 'self_disturbance_transient'): start a new run",
          w.at("modes").get<std::size_t>(), models::WakeKernel::kModes));
    }
    models::WakeBuildup::State wake;
    for (const auto& e : w.at("parcels")) {
      auto& p = wake[e.at(0).get<std::int64_t>()];
      p.anchor = e.at(1).get<std::array<double, 3>>();
      p.y = e.at(2).get<std::array<double, 3 * models::WakeKernel::kModes>>();
      p.K = e.at(3).get<double>();
      p.v = e.at(4).get<std::array<double, 3>>();
      p.dt = e.at(5).get<double>();
    }
    s.wake = std::move(wake);
  }
  if (j.contains("sample_ahead")) {
    const Json& a = j.at("sample_ahead");
    link::ParticleData where;
    where.ids = a.at("ids").get<std::vector<std::int64_t>>();
    for (const auto& [name, values] : a.at("fields").items()) {
      where.field(name) = values.get<std::vector<double>>();
      if (where.field(name).size() % std::max<std::size_t>(where.ids.size(), 1) != 0)
        throw InputError("its sample_ahead." + name + " does not match its ids");
    }
    s.sample_ahead = std::move(where);
  }
  return s;
}

// Every leaf of a YAML tree as "a.b[2].c" -> its text.
void flatten(const YAML::Node& n, const std::string& path,
             std::map<std::string, std::string>& out) {
  if (n.IsMap()) {
    for (const auto& kv : n) {
      const std::string k = kv.first.as<std::string>();
      flatten(kv.second, path.empty() ? k : path + "." + k, out);
    }
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i)
      flatten(n[i], path + "[" + std::to_string(i) + "]", out);
  } else if (n.IsScalar()) {
    out[path] = n.Scalar();
  } else {
    out[path] = "~";
  }
}

bool under(const std::string& key, const std::string& prefix) {
  return key == prefix || key.rfind(prefix + ".", 0) == 0 || key.rfind(prefix + "[", 0) == 0;
}

bool mayChange(const std::string& key) {
  // coupling.dt and coupling.dem_steps: as refusedStepChange allows
  // coupling.scheme: the saved state is the same under either (the first interval after a
  // resume samples between the intervals anyway); coupling.cpus: where the processes run, not
  // what they compute (a bound run is the same to the bit)
  for (const char* p : {"coupling.end_time", "coupling.scheme", "coupling.cpus", "coupling.dt",
                        "coupling.dem_steps", "output", "checkpoint", "transport", "checks",
                        "observables", "description"}) {
    if (under(key, p)) return true;
  }
  // participants.<name>.timeout, and how often the fluid's solver residuals are logged
  for (const std::string t : {".timeout", ".options.solver_log_every"}) {
    if (key.rfind("participants.", 0) == 0 && key.size() > t.size() &&
        key.compare(key.size() - t.size(), t.size(), t) == 0)
      return true;
  }
  return false;
}

// 1.0e-3 and 0.001 are the same setting.
bool sameNumber(const std::string& a, const std::string& b) {
  char *ea = nullptr, *eb = nullptr;
  const double x = std::strtod(a.c_str(), &ea);
  const double y = std::strtod(b.c_str(), &eb);
  return !a.empty() && !b.empty() && *ea == '\0' && *eb == '\0' && x == y;
}

double timeOf(const fs::path& p) { return std::strtod(p.filename().c_str(), nullptr); }

double numberAt(const YAML::Node& scene, const char* section, const char* key, double absent) {
  const YAML::Node n = scene[section] ? scene[section][key] : YAML::Node();
  return n && n.IsScalar() ? std::strtod(n.Scalar().c_str(), nullptr) : absent;
}

std::string textAt(const YAML::Node& scene, const char* section, const char* key,
                   const char* absent) {
  const YAML::Node n = scene[section] ? scene[section][key] : YAML::Node();
  return n && n.IsScalar() ? n.Scalar() : absent;
}

}  // namespace

double StepClock::time(std::uint64_t k) const { return link::stepTime(start, dt, k); }

std::uint64_t StepClock::stepsTo(double end) const {
  return static_cast<std::uint64_t>(std::llround((end - start) / dt));
}

StepClock clockOf(const CoupledState& saved) {
  if (saved.clock) return *saved.clock;
  const YAML::Node scene = YAML::Load(saved.scene);
  return {numberAt(scene, "coupling", "start_time", 0.0), numberAt(scene, "coupling", "dt", 0.0)};
}

std::string refusedStepChange(const YAML::Node& saved, const YAML::Node& now) {
  const double dt0 = numberAt(saved, "coupling", "dt", 0.0);
  const double dt1 = numberAt(now, "coupling", "dt", 0.0);
  const double n0 = numberAt(saved, "coupling", "dem_steps", 1.0);
  const double n1 = numberAt(now, "coupling", "dem_steps", 1.0);
  if (dt0 == dt1 && n0 == n1) return "";
  const std::string change =
      fmt::format("coupling.dt {} -> {} s, coupling.dem_steps {} -> {}",
                  analysis::formatShortest(dt0), analysis::formatShortest(dt1), n0, n1);
  const bool particles = now["participants"] && now["participants"]["particles"];
  const double dem0 = dt0 / n0;
  if (particles && std::abs(dt1 / n1 - dem0) > 1e-12 * dem0) {
    const double n = dt1 / dem0;
    const std::string hint = std::abs(n - std::round(n)) < 1e-9 * n && n >= 1
                                 ? fmt::format(" (with coupling.dt={}: coupling.dem_steps={})",
                                               analysis::formatShortest(dt1), std::llround(n))
                                 : fmt::format(" (coupling.dt a whole multiple of {} s)",
                                               analysis::formatShortest(dem0));
    return change + ": the DEM step coupling.dt / coupling.dem_steps would change from " +
           analysis::formatShortest(dem0) + " to " + analysis::formatShortest(dt1 / n1) +
           " s, but the particle solver continues from its restart with the step its script "
           "set; keep the DEM step" +
           hint;
  }
  if (textAt(now, "coupling", "data_path", "central") == "peer" &&
      textAt(now, "coupling", "scheme", "parallel") == "overlapped")
    return change +
           ": with coupling.data_path peer and coupling.scheme overlapped the particles hold "
           "the gas sampled ahead over the old step in their checkpoint; resume with the step "
           "it was written with";
  return "";
}

std::optional<std::string> offTheStepGrid(double start_time, double time, double dt) {
  const double steps = (time - start_time) / dt;
  const double off = std::abs(steps - std::round(steps)) * dt;
  if (off <= 1e-6 * dt) return std::nullopt;
  return "the resume continues from t = " + analysis::formatShortest(time) +
         " s, which is not a whole number of the new coupling step " +
         analysis::formatShortest(dt) + " s from coupling.start_time: the rows, snapshots and " +
         "checkpoints from here on fall " + util::significant(off, 3) +
         " s off the times a run at this step would write (e.g. its output.interval). To keep "
         "them on it, go on at the old step to a time on the new step's grid first (--set "
         "coupling.end_time=...), or resume from a checkpoint on it (cosim resume --from)";
}

CheckpointStore::CheckpointStore(const fs::path& run_folder) : dir_(run_folder / "checkpoints") {}

fs::path CheckpointStore::begin(double time, const std::vector<std::string>& participants) const {
  const fs::path partial = dir_ / (kPartialPrefix + analysis::formatShortest(time));
  std::error_code ec;
  fs::remove_all(partial, ec);  // a checkpoint that a crash interrupted
  fs::create_directories(partial);
  for (const auto& p : participants) fs::create_directories(partial / p);
  return partial;
}

fs::path CheckpointStore::commit(const fs::path& partial, const CoupledState& state,
                                 int keep) const {
  analysis::writeFileAtomically(partial / kStateFile, toJson(state).dump(1) + "\n");
  const fs::path final_dir = dir_ / analysis::formatShortest(state.time);
  std::error_code ec;
  fs::remove_all(final_dir, ec);
  fs::rename(partial, final_dir);
  auto done = all();
  while (static_cast<int>(done.size()) > keep) {
    fs::remove_all(done.front(), ec);
    done.erase(done.begin());
  }
  return final_dir;
}

std::vector<fs::path> CheckpointStore::all() const {
  std::vector<fs::path> found;
  std::error_code ec;
  if (!fs::is_directory(dir_, ec)) return found;
  for (const auto& e : fs::directory_iterator(dir_)) {
    const std::string name = e.path().filename().string();
    if (!e.is_directory() || name.rfind(kPartialPrefix, 0) == 0) continue;
    if (!fs::exists(e.path() / kStateFile)) continue;  // not complete
    found.push_back(e.path());
  }
  std::sort(found.begin(), found.end(),
            [](const fs::path& a, const fs::path& b) { return timeOf(a) < timeOf(b); });
  return found;
}

std::optional<fs::path> CheckpointStore::at(double time) const {
  for (const auto& c : all())
    if (std::abs(timeOf(c) - time) <= 1e-9 * std::max(1.0, std::abs(time))) return c;
  return std::nullopt;
}

std::vector<fs::path> CheckpointStore::setAsideAfter(const fs::path& kept) const {
  std::vector<fs::path> moved;
  const double t = timeOf(kept);
  for (const auto& c : all()) {
    if (timeOf(c) <= t) continue;
    const fs::path aside = dir_ / "superseded";
    fs::create_directories(aside);
    fs::path to = aside / c.filename();
    for (int k = 2; fs::exists(to); ++k)
      to = aside / (c.filename().string() + "-" + std::to_string(k));
    fs::rename(c, to);
    moved.push_back(to);
  }
  return moved;
}

std::string CheckpointStore::listTimes() const {
  std::string out;
  for (const auto& c : all()) out += (out.empty() ? "" : ", ") + c.filename().string() + " s";
  return out.empty() ? "none" : out;
}

std::optional<fs::path> CheckpointStore::newest() const {
  auto done = all();
  if (done.empty()) return std::nullopt;
  return done.back();
}

CoupledState readCoupledState(const fs::path& checkpoint) {
  const fs::path file = checkpoint / kStateFile;
  try {
    const Json j = analysis::readJsonFile(file);
    if (j.value("format", "") != "cosim-checkpoint")
      throw InputError("not a cosim checkpoint (no format: cosim-checkpoint)");
    return fromJson(j);
  } catch (const nlohmann::json::exception& e) {
    // a key missing or of the wrong type: the file is not what this cosim wrote
    throw InputError(file.string() +
                     ": the checkpoint's state is damaged or was not written by this "
                     "version of cosim (" +
                     e.what() + ")");
  } catch (const std::exception& e) {
    throw Error(kindOf(e, ErrorKind::input), file.string() + ": " + e.what());
  }
}

namespace {
void fnv1a(std::uint64_t& h, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
}
std::string hex(std::uint64_t h) { return fmt::format("{:016x}", h); }
}  // namespace

std::map<std::string, std::string> particleDigest(const link::ParticleData& state) {
  // In id order, so that a participant that reports its particles in another order agrees
  std::vector<std::size_t> order(state.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return state.ids[a] < state.ids[b]; });
  std::map<std::string, std::string> out;
  std::uint64_t h = 14695981039346656037ULL;
  for (std::size_t i : order) fnv1a(h, &state.ids[i], sizeof(std::int64_t));
  out["ids"] = hex(h);
  for (const std::string& name : state.names()) {
    const auto& v = state.get(name);
    const std::size_t per = state.size() ? v.size() / state.size() : 0;
    h = 14695981039346656037ULL;
    for (std::size_t i : order) fnv1a(h, v.data() + i * per, per * sizeof(double));
    out[name] = hex(h);
  }
  return out;
}

std::vector<std::string> digestDifferences(const std::map<std::string, std::string>& saved,
                                           const std::map<std::string, std::string>& now) {
  std::vector<std::string> diff;
  for (const auto& [name, digest] : saved) {
    const auto it = now.find(name);
    if (it == now.end())
      diff.push_back(name + " (not reported after the resume)");
    else if (it->second != digest)
      diff.push_back(name);
  }
  return diff;
}

std::vector<std::string> sceneDifferences(const YAML::Node& saved, const YAML::Node& now) {
  std::map<std::string, std::string> a, b;
  flatten(saved, "", a);
  flatten(now, "", b);
  std::set<std::string> keys;
  for (const auto& [k, v] : a) keys.insert(k);
  for (const auto& [k, v] : b) keys.insert(k);
  std::vector<std::string> diff;
  for (const auto& k : keys) {
    if (mayChange(k)) continue;
    auto ia = a.find(k), ib = b.find(k);
    const std::string va = ia == a.end() ? "(absent)" : ia->second;
    const std::string vb = ib == b.end() ? "(absent)" : ib->second;
    if (va != vb && !sameNumber(va, vb)) diff.push_back(k + ": " + va + " -> " + vb);
  }
  return diff;
}

}  // namespace cosim::orchestrator
