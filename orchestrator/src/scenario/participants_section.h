// participants: the fluid and particle solvers of a scene, the adapter each runs behind and how
// it is started.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cosim.pb.h"
#include "scenario/context.h"

namespace cosim::orchestrator {

// participants.<name>.slurm: the job step srun starts (launch: slurm).
struct SlurmLaunch {
  int nodes = 0;                  // --nodes; 0: as Slurm places the ranks
  std::string nodelist;           // --nodelist, e.g. "node[01-04]"; empty: any of the allocation
  std::vector<std::string> args;  // further srun options, e.g. --cpus-per-task=2, --mpi=pmi2

  static const std::vector<KeySpec>& keys();
};

struct ParticipantSpec {
  std::string name;  // key under participants: "fluid" or "particles"
  wire::Role role = wire::ROLE_UNSPECIFIED;
  std::string adapter;             // analytic-fluid | openfoam | free-particles | liggghts | custom
  std::string command;             // executable (resolved from adapter unless given)
  std::vector<std::string> args;   // extra arguments for the executable
  std::string launch = "local";    // local | mpirun | slurm: cosim starts it (launchers.h);
                                   // external: it is started elsewhere and connects by itself
  int mpi = 1;                     // ranks; > 1 runs it under mpirun -np (srun with launch: slurm)
  SlurmLaunch slurm;               // launch: slurm
  std::filesystem::path hostfile;  // launch: mpirun: mpirun's --hostfile (empty: this host)
  // A folder on the participant's node (absolute) when it does not see the run folder: cosim
  // starts it with --workdir WORKDIR/<run id>/<name> and sends its files over the link
  // (docs/cluster.md). Empty: the run folder is shared (one machine, or a shared filesystem).
  std::string workdir;
  std::filesystem::path files;  // case folder to copy and template into the run folder
  double timeout = 300.0;       // seconds one step may take before it counts as hung
  YAML::Node options;           // adapter-specific, sent verbatim in Welcome.config_yaml

  static const std::vector<KeySpec>& keys();
};

// As written, by name (may include one the plan does not start).
using ParticipantsSection = std::map<std::string, ParticipantSpec>;

// `dir`: the scenario's folder (files: is relative to it).
ParticipantsSection parseParticipants(const YAML::Node& node, const Context& ctx,
                                      const std::filesystem::path& dir);

// Adapter name -> default executable name and role.
struct AdapterInfo {
  std::string executable;
  wire::Role role;
};
const std::map<std::string, AdapterInfo>& knownAdapters();

}  // namespace cosim::orchestrator
