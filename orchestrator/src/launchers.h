// How cosim starts a participant it launches itself (participants.<name>.launch): the command
// put in front of the adapter's own command line.
//   local   the adapter on this host; with mpi > 1 under `mpirun -np N`
//   mpirun  `mpirun -np N [--hostfile FILE]`: the ranks on the hosts of the host file
//   slurm   `srun --ntasks=N [--nodes=M] [--nodelist=L] ...`: a job step inside the user's
//           allocation (salloc, sbatch); outside one, srun asks Slurm for its own allocation
// external participants are not started by cosim (docs/cluster.md).
#pragma once

#include <string>
#include <vector>

#include "scenario/participants_section.h"

namespace cosim::orchestrator {

// The launcher's part of the command line (empty for a single-rank local participant). Throws
// RunFailure naming the participant when the launcher's program is not installed.
std::vector<std::string> launcherPrefix(const std::string& name, const ParticipantSpec& spec);

// One line for `cosim validate` and the run's log: where and how the participant is started.
std::string describeLaunch(const ParticipantSpec& spec);

}  // namespace cosim::orchestrator
