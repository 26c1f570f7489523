#include "FoamParticipant.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "SceneCheck.h"
#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/particle_wire.h"
#include "cosim/util/child_process.h"
#include "cosim/util/errors.h"
#include "cosim/util/text_file.h"

namespace cosim::foam {
namespace fs = std::filesystem;

const std::vector<std::string>& foamSampleFields() {
  static const std::vector<std::string> fields{field::fluid_velocity,    field::voidage,
                                               field::fluid_density,     field::fluid_viscosity,
                                               field::pressure_gradient, field::precursor_fraction,
                                               field::cell_size};
  return fields;
}

namespace {

// argv for Foam::argList, alive as long as the strings
struct Argv {
  explicit Argv(std::vector<std::string>& args) {
    for (auto& a : args) ptrs.push_back(a.data());
    ptrs.push_back(nullptr);
  }
  int argc() const { return static_cast<int>(ptrs.size()) - 1; }
  char** argv() { return ptrs.data(); }
  std::vector<char*> ptrs;
};

// An OpenFOAM utility run in the case folder from an argument vector (no shell), its output in
// log.<tool>.
void runTool(const std::vector<std::string>& argv) {
  const std::string& tool = argv.front();
  const std::string log = "log." + tool;
  int rc = 0;
  std::string why;
  // A tool that could not start: what the machine lacks; one that failed: what it read from the
  // case is wrong (its log says what), unless it was killed (SIGKILL: out of memory).
  ErrorKind kind = ErrorKind::input;
  try {
    rc = util::runProgram(argv, log);
  } catch (const std::exception& e) {
    rc = 127;
    why = std::string(": ") + e.what();
    kind = kindOf(e, ErrorKind::resource);
  }
  if (rc == 128 + 9) kind = ErrorKind::resource;
  if (rc != 0) {
    throw Error(kind, "cosimFoam: `" + util::displayCommand(argv) + "` failed in " +
                          fs::current_path().string() + why + " (see " + log + "):\n" +
                          util::tailOfFile(log, 15));
  }
}

// Mesh (blockMesh) and decomposition (decomposePar) before OpenFOAM reads the case. Rank 0 only.
void prepareCase(const AdapterSettings& settings, int ranks) {
  const fs::path here = fs::current_path();
  checkCase(settings, ranks, here);  // what `cosim validate` checks too
  const bool haveMesh =
      fs::exists("constant/polyMesh/faces") || fs::exists("constant/polyMesh/faces.gz");
  bool meshed = false;
  if (settings.mesh == "blockMesh" || (settings.mesh == "auto" && !haveMesh)) {
    runTool({"blockMesh"});
    meshed = true;
  }
  if (ranks > 1) {
    bool decomposed = true;
    for (int r = 0; r < ranks; ++r) {
      if (!fs::exists("processor" + std::to_string(r) + "/constant/polyMesh")) decomposed = false;
    }
    if (fs::exists("processor" + std::to_string(ranks))) decomposed = false;
    if (meshed || !decomposed) runTool({"decomposePar", "-force"});
  }
}

// A folder name that is a time (OpenFOAM's time folders); nullopt for anything else.
std::optional<double> timeOfFolder(const fs::path& p) {
  const std::string name = p.filename().string();
  char* end = nullptr;
  const double t = std::strtod(name.c_str(), &end);
  if (name.empty() || *end != '\0' || !fs::is_directory(p)) return std::nullopt;
  return t;
}

// Resume: the checkpoint's time folder becomes the case's latest one (folders written after it
// by the stopped run are removed), so OpenFOAM starts from it (startFrom latestTime). `from`
// holds <time>/ for a serial case, processorN/<time>/ for a decomposed one. Returns the time.
double restoreTimeFolder(const fs::path& from, int ranks) {
  double restored = -1.0;
  for (int r = 0; r < std::max(ranks, 1); ++r) {
    const fs::path sub = ranks > 1 ? fs::path("processor" + std::to_string(r)) : fs::path();
    std::optional<fs::path> saved;
    if (fs::is_directory(from / sub))
      for (const auto& e : fs::directory_iterator(from / sub))
        if (timeOfFolder(e.path())) saved = e.path();
    if (!saved)
      throw InputError("cosimFoam: cannot resume: " + (from / sub).string() +
                       " holds no time folder (was the checkpoint written by cosimFoam?)");
    restored = *timeOfFolder(*saved);
    const fs::path caseDir = sub.empty() ? fs::current_path() : fs::current_path() / sub;
    for (const auto& e : fs::directory_iterator(caseDir)) {
      if (auto t = timeOfFolder(e.path()); t && *t > restored) fs::remove_all(e.path());
    }
    const fs::path to = caseDir / saved->filename();
    fs::remove_all(to);
    fs::copy(*saved, to, fs::copy_options::recursive);
  }
  return restored;
}

void moveTo(const std::string& workdir) {
  if (!workdir.empty() && fs::is_directory(workdir) &&
      fs::weakly_canonical(workdir) != fs::current_path()) {
    fs::current_path(workdir);
  }
  setenv("PWD", fs::current_path().c_str(), 1);
}

// The part of configure every rank does.
std::unique_ptr<GasDomain> makeGas(const RankBridge& bridge, std::vector<std::string> foamArgs,
                                   std::string& yaml, double& species, double& resuming,
                                   std::string& workdir) {
  bridge.share(yaml);
  bridge.share(species);
  bridge.share(resuming);
  bridge.share(workdir);
  moveTo(workdir);
  AdapterSettings settings = parseAdapterSettings(yaml, species != 0);
  settings.gas.resuming = resuming != 0;
  Argv argv(foamArgs);
  return GasDomain::create(argv.argc(), argv.argv(), settings.gas);
}

}  // namespace

FoamParticipant::FoamParticipant(const RankBridge& bridge, std::vector<std::string> foamArgs)
    : bridge_(bridge), foamArgs_(std::move(foamArgs)) {}

cosim::link::Capabilities FoamParticipant::capabilities() const {
  cosim::link::Capabilities caps;
  caps.role = wire::FLUID;
  caps.adapter = "openfoam";
  caps.provides = foamSampleFields();
  caps.provides.push_back(field::precursor_removed);
  caps.accepts = {field::position, field::radius, field::velocity, field::drag_coefficient,
                  field::transfer_coefficient};
  return caps;
}

void FoamParticipant::configure(const wire::Welcome& welcome) {
  send_.assign(welcome.send().begin(), welcome.send().end());
  species_ = welcome.species();
  const auto caps = capabilities();
  for (const auto& name : send_) {
    if (std::find(caps.provides.begin(), caps.provides.end(), name) == caps.provides.end()) {
      throw InputError("cosimFoam cannot send field '" + name +
                       "' the scene asks for (Welcome.send)");
    }
    if (name == field::precursor_fraction && !species_) {
      throw InputError(
          "the scene asks cosimFoam for precursor_fraction but has no mass transfer "
          "(Welcome.species is false): no precursor is solved");
    }
  }
  std::string workdir = welcome.workdir();
  moveTo(workdir);
  std::string yaml = welcome.config_yaml();
  const AdapterSettings settings = parseAdapterSettings(yaml, species_);  // errors early
  prepareCase(settings, bridge_.size());
  std::optional<double> resumeAt;
  if (!welcome.restart_from().empty())
    resumeAt = restoreTimeFolder(welcome.restart_from(), bridge_.size());
  double species = species_ ? 1.0 : 0.0;
  double resuming = resumeAt ? 1.0 : 0.0;
  bridge_.command(RankCommand::configure);
  gas_ = makeGas(bridge_, foamArgs_, yaml, species, resuming, workdir);
  if (resumeAt && std::abs(gas_->time() - *resumeAt) > 1e-9 * std::max(1.0, *resumeAt)) {
    throw InputError(
        "cosimFoam: cannot resume: OpenFOAM started at t = " + std::to_string(gas_->time()) +
        " s, not at the checkpoint's " + std::to_string(*resumeAt) +
        " s; system/controlDict must say `startFrom latestTime;`");
  }
}

void FoamParticipant::restore(const std::string& /*path*/) {
  // Done while configuring: the checkpoint's time folder is the one OpenFOAM started from.
}

void FoamParticipant::sample(const cosim::link::ParticleData& particles,
                             cosim::link::ParticleData& out, std::vector<std::int64_t>& lost_ids) {
  if (!particles.has(field::position) || !particles.has(field::radius)) {
    throw link::ProtocolError(
        "Sample for cosimFoam must carry position and radius of every particle (got: " +
        [&] {
          std::string s;
          for (const auto& n : particles.names()) s += n + " ";
          return s;
        }() +
        ")");
  }
  ParticleSet set;
  set.ids = particles.ids;
  set.position = particles.get(field::position);
  set.radius = particles.get(field::radius);
  if (particles.has(field::velocity)) set.velocity = particles.get(field::velocity);
  for (std::size_t i = 0; i < set.radius.size(); ++i) {
    if (!(set.radius[i] > 0)) {
      throw link::ProtocolError("Sample: particle " + std::to_string(set.ids[i]) + " has radius " +
                                std::to_string(set.radius[i]) + " (must be > 0)");
    }
  }
  std::vector<std::string> names;
  for (const auto& n : send_) {
    if (n != field::precursor_removed) names.push_back(n);
  }

  const auto t0 = std::chrono::steady_clock::now();
  bridge_.command(RankCommand::sample);
  bridge_.share(names);  // the parcels: each processor those that concern it (GasDomain::place)
  const auto lost = gas_->place(set);
  const auto values = gas_->sample(names);
  sampleSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  sampledIds_ = set.ids;
  out.ids = set.ids;
  for (const auto& [name, v] : values) out.field(name) = v;
  lost_ids.clear();
  for (const auto i : lost) lost_ids.push_back(set.ids[i]);
  lostCount_ = lost.size();
}

void FoamParticipant::advance(const wire::Advance& cmd, const cosim::link::ParticleData& terms,
                              wire::Advanced& out, cosim::link::ParticleData& state) {
  double dt = cmd.dt();
  if (dt == 0) return;  // nothing to report before the first step
  if (!(dt > 0)) {
    throw link::ProtocolError("Advance for cosimFoam: dt must be > 0, got " + std::to_string(dt));
  }

  // Terms aligned with the particles of the last Sample (same ids, any order)
  const std::size_t n = sampledIds_.size();
  std::vector<double> K, k;
  if (terms.size() > 0) {
    std::vector<std::size_t> slot(terms.size());
    if (terms.ids == sampledIds_) {
      for (std::size_t t = 0; t < terms.size(); ++t) slot[t] = t;  // the usual case: same order
    } else {
      std::map<std::int64_t, std::size_t> where;
      for (std::size_t i = 0; i < n; ++i) where[sampledIds_[i]] = i;
      for (std::size_t t = 0; t < terms.size(); ++t) {
        const auto it = where.find(terms.ids[t]);
        if (it == where.end()) {
          throw link::ProtocolError("Advance for cosimFoam: particle " +
                                    std::to_string(terms.ids[t]) +
                                    " has exchange terms but was not in this step's Sample");
        }
        slot[t] = it->second;
      }
    }
    auto align = [&](const std::string& name, std::vector<double>& dst) {
      if (!terms.has(name)) return;
      const auto& src = terms.get(name);
      dst.assign(n, 0.0);
      for (std::size_t t = 0; t < terms.size(); ++t) dst[slot[t]] = src[t];
    };
    align(field::drag_coefficient, K);
    if (species_) align(field::transfer_coefficient, k);
  }

  // Scheme `overlapped`: the session samples at position + velocity dt after this step. Where
  // that is, is known now: on a single processor the parcels are located there on a helper
  // thread during the gas step (the particles' core idles once their DEM steps are done).
  if (cmd.has_sample_ahead() && bridge_.size() == 1) {
    const auto ahead = cosim::link::predictedAt(cosim::link::fromWire(cmd.sample_ahead()), dt);
    if (ahead.has(field::position) && ahead.has(field::radius)) {
      ParticleSet set;
      set.ids = ahead.ids;
      set.position = ahead.get(field::position);
      set.radius = ahead.get(field::radius);
      gas_->prepare(set);
    }
  }

  bridge_.command(RankCommand::advance);
  bridge_.share(dt);  // the terms: each processor its parcels' (GasDomain::advance)
  const StepResult r = gas_->advance(dt, K, k);

  auto& report = *out.mutable_fluid();
  report.set_pressure_drop(r.pressure_drop);
  report.set_max_courant(r.max_courant);
  report.set_voidage_min(r.voidage_min);
  report.set_gas_mass_in(r.gas_mass_in);
  report.set_gas_mass_out(r.gas_mass_out);
  report.set_gas_mass_held(r.gas_mass_held);
  report.set_solve_seconds(r.solve_seconds);
  report.set_sample_seconds(sampleSeconds_);
  report.set_lost_particles(static_cast<std::uint64_t>(lostCount_));
  if (r.species) {
    auto& sp = *report.mutable_species();
    sp.set_precursor_in(r.precursor_in);
    sp.set_precursor_out(r.precursor_out);
    sp.set_precursor_held(r.precursor_held);
    sp.set_precursor_held_start(r.precursor_held_start);
    sp.set_precursor_removed_cells(r.precursor_removed_cells);
    sp.set_precursor_removed_total(r.precursor_removed_total);
    sp.set_precursor_min(r.precursor_min);
    sp.set_precursor_max(r.precursor_max);
  }
  if (std::find(send_.begin(), send_.end(), field::precursor_removed) != send_.end()) {
    state.ids = sampledIds_;
    auto& removed = state.field(field::precursor_removed);
    if (r.precursor_removed.size() == n) removed = r.precursor_removed;
  }
}

std::vector<std::string> FoamParticipant::checkpoint(const std::string& path) {
  std::string p = path;
  bridge_.command(RankCommand::checkpoint);
  bridge_.share(p);
  return gas_->checkpoint(p);
}

void FoamParticipant::finish() {
  if (!gas_) return;
  bridge_.command(RankCommand::finish);
  gas_->writeNow();
}

int serveRanks(const RankBridge& bridge, std::vector<std::string> foamArgs) {
  std::unique_ptr<GasDomain> gas;
  while (true) {
    switch (bridge.command()) {
      case RankCommand::configure: {
        std::string yaml, workdir;
        double species = 0, resuming = 0;
        gas = makeGas(bridge, foamArgs, yaml, species, resuming, workdir);
        break;
      }
      case RankCommand::place:
      case RankCommand::sample: {
        std::vector<std::string> names;
        bridge.share(names);
        gas->place(ParticleSet{});  // this processor's parcels come from the master
        gas->sample(names);
        break;
      }
      case RankCommand::advance: {
        double dt = 0;
        bridge.share(dt);
        gas->advance(dt, {}, {});  // ... and their terms
        break;
      }
      case RankCommand::checkpoint: {
        std::string path;
        bridge.share(path);
        gas->checkpoint(path);
        break;
      }
      case RankCommand::finish:
        gas->writeNow();
        break;
      case RankCommand::quit:
        return 0;
    }
  }
}

}  // namespace cosim::foam
