#include "launchers.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#include "participants.h"
#include "processes.h"

namespace cosim::orchestrator {

namespace {

std::string program(const std::string& name, const std::string& exe, const std::string& why) {
  const auto found = findExecutable(exe);
  if (!found) throw RunFailure(name, why);
  return found->string();
}

bool hasOption(const std::vector<std::string>& args, const std::string& option) {
  return std::any_of(args.begin(), args.end(),
                     [&](const std::string& a) { return a.rfind(option, 0) == 0; });
}

}  // namespace

std::vector<std::string> launcherPrefix(const std::string& name, const ParticipantSpec& spec) {
  const std::string np = std::to_string(spec.mpi);
  if (spec.launch == "slurm") {
    std::vector<std::string> argv = {
        program(name, "srun",
                "launch: slurm needs srun (apt-get install slurm-client), found neither next to "
                "cosim nor in PATH"),
        "--ntasks=" + np, "--job-name=cosim-" + name, "--kill-on-bad-exit=1"};
    if (spec.slurm.nodes > 0) argv.push_back("--nodes=" + std::to_string(spec.slurm.nodes));
    if (!spec.slurm.nodelist.empty()) argv.push_back("--nodelist=" + spec.slurm.nodelist);
    // Only the CPUs asked for: by default a step takes every CPU of its nodes in the allocation,
    // and the other participant's step would then wait for it for ever.
    if (!hasOption(spec.slurm.args, "--overlap") && !hasOption(spec.slurm.args, "--whole"))
      argv.push_back("--exact");
    // MPI ranks started by srun meet through Slurm's PMIx (Debian's OpenMPI speaks it); a single
    // rank needs it too, since OpenMPI under srun looks for it in MPI_Init (LIGGGHTS)
    if (!hasOption(spec.slurm.args, "--mpi")) argv.push_back("--mpi=pmix");
    argv.insert(argv.end(), spec.slurm.args.begin(), spec.slurm.args.end());
    return argv;
  }
  if (spec.mpi <= 1 && spec.launch != "mpirun") return {};
  std::vector<std::string> argv = {
      program(name, "mpirun", "mpi: " + np + " needs mpirun (apt-get install openmpi-bin)"), "-np",
      np};
  if (geteuid() == 0) argv.push_back("--allow-run-as-root");
  if (!spec.hostfile.empty()) {
    argv.push_back("--hostfile");
    argv.push_back(spec.hostfile.string());
  } else {
    argv.push_back("--oversubscribe");  // this host only: more ranks than cores are allowed
  }
  return argv;
}

std::string describeLaunch(const ParticipantSpec& spec) {
  const std::string ranks = spec.mpi > 1 ? std::to_string(spec.mpi) + " MPI ranks" : "1 process";
  if (spec.launch == "external") {
    return "external: started by you (or your job script) anywhere that reaches the "
           "orchestrator's address; cosim prints its command line";
  }
  if (spec.launch == "slurm") {
    std::string where = std::getenv("SLURM_JOB_ID")
                            ? "as a step of Slurm job " + std::string(std::getenv("SLURM_JOB_ID"))
                            : "by srun outside an allocation (srun requests one of its own)";
    std::string how = ranks;
    if (spec.slurm.nodes > 0) how += " on " + std::to_string(spec.slurm.nodes) + " node(s)";
    if (!spec.slurm.nodelist.empty()) how += " (" + spec.slurm.nodelist + ")";
    return "slurm: srun, " + how + ", " + where;
  }
  if (spec.launch == "mpirun") {
    return "mpirun: " + ranks +
           (spec.hostfile.empty() ? " on this host" : " on the hosts of " + spec.hostfile.string());
  }
  return "local: " + ranks + " on this host" + (spec.mpi > 1 ? " (mpirun)" : "");
}

}  // namespace cosim::orchestrator
