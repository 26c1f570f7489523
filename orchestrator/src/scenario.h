// The scenario file: what a user writes to describe a scene. Loaded, templated (${expr} with the
// scenario's parameters), overridden (--set key=value) and validated before anything starts.
// Every error names the file, the line, the key, what was expected and what to do.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosim.pb.h"
#include "cosim/models/parameters.h"
#include "cosim/models/parcels.h"
#include "expression.h"
#include "observables.h"

namespace cosim::orchestrator {

class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ParticipantSpec {
  std::string name;  // key under participants: "fluid" or "particles"
  wire::Role role = wire::ROLE_UNSPECIFIED;
  std::string adapter;            // analytic-fluid | openfoam | free-particles | liggghts | custom
  std::string command;            // executable (resolved from adapter unless given)
  std::vector<std::string> args;  // extra arguments for the executable
  std::string launch = "local";   // local: cosim starts it; external: it connects by itself
  int mpi = 1;                    // ranks; > 1 runs it under mpirun -np
  std::filesystem::path files;    // case folder to copy and template into the run folder
  double timeout = 300.0;         // seconds one step may take before it counts as hung
  YAML::Node options;             // adapter-specific, sent verbatim in Welcome.config_yaml
};

struct ModelSpec {
  std::string law;  // registered name
  models::Parameters params;
  int line = 0;
};

struct Scenario {
  std::filesystem::path file;  // absolute path of the scenario file
  std::filesystem::path dir;   // its folder (relative paths are relative to it)
  std::string name;
  std::string description;
  Variables parameters;

  std::map<std::string, ParticipantSpec> participants;  // as written (may include unused ones)

  double dt = 0.0;         // coupling interval = CFD time step [s]
  unsigned dem_steps = 1;  // DEM steps per coupling interval
  double end_time = 0.0;   // [s]
  double start_time = 0.0;

  models::SceneConstants constants;
  // Particle material, optional: used by the stability checks (Rayleigh time, relaxation time).
  struct Material {
    double particle_density = 0.0;  // [kg/m3]; 0 = unknown
    double youngs_modulus = 0.0;    // [Pa]; 0 = unknown
    double poisson_ratio = 0.3;
  } material;

  std::optional<ModelSpec> drag;
  std::vector<ModelSpec> forces;
  std::optional<ModelSpec> mass_transfer;
  std::optional<ModelSpec> coating_zone;
  std::vector<std::filesystem::path> plugins;

  std::filesystem::path output_folder;  // run folder
  double output_interval = 0.0;         // particle snapshots [s]; 0 = every step

  // Checkpoints of the whole coupled state under RUN/checkpoints/<time>/ (docs/restarts.md).
  double checkpoint_interval = 0.0;  // simulated seconds; 0 = none (a final one on Ctrl-C)
  int checkpoint_keep = 3;           // the newest ones kept

  std::string bind_endpoint;        // empty: ipc in /tmp
  std::string connect_endpoint;     // what participants connect to (defaults to bind)
  double heartbeat_timeout = 10.0;  // s without any sign of life from a participant
  double handshake_timeout = 60.0;  // s for every participant to connect and say Hello

  // Stability checks: "refuse" (default) stops unstable settings; "warn" only reports.
  std::string stability = "refuse";
  double max_particle_speed = 50.0;      // m/s; a faster particle stops the run
  double mass_balance_tolerance = 1e-4;  // relative drift that stops the run (coating scenes)
  double max_courant = 5.0;              // fluid Courant number that stops the run

  std::vector<ObservableSpec> observables;  // measured at the end, with analytic references

  YAML::Node resolved;  // the scenario after templating and --set, as run
};

// Loads and validates. `sets` are "key.path=value" overrides (a bare name sets a parameter; a
// YAML list or map as value replaces the whole node); `unsets` are "key.path" names of nodes to
// remove, applied before the sets. Errors in overridden values name the override.
Scenario loadScenario(const std::filesystem::path& file, const std::vector<std::string>& sets = {},
                      const std::vector<std::string>& unsets = {});

// Same from text (for tests); `origin` is the name used in messages.
Scenario parseScenario(const std::string& text, const std::filesystem::path& origin,
                       const std::vector<std::string>& sets = {},
                       const std::vector<std::string>& unsets = {});

// Adapter name -> default executable name and role.
struct AdapterInfo {
  std::string executable;
  wire::Role role;
};
const std::map<std::string, AdapterInfo>& knownAdapters();

}  // namespace cosim::orchestrator
