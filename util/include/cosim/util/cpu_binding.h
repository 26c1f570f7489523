// Binding processes to CPUs (Linux sched_setaffinity). On a machine with as many cores as busy
// solvers, the scheduler otherwise moves the DEM, the gas solver, the gas solver's placement
// thread and the orchestrator between the cores, and the critical solver loses time to the
// others (docs/performance.md, "Bound to CPUs"). coupling.cpus: auto uses it.
#pragma once

#include <string>
#include <vector>

namespace cosim::util {

// The CPUs this process may run on, in increasing order (empty if the system does not say).
std::vector<int> allowedCpus();
// allowedCpus() as it was at the first call: what the process was given before it bound itself.
std::vector<int> initialCpus();

// Binds every thread of this process to `cpus` (threads started later inherit it). Throws
// cosim::InputError naming the CPUs when the system refuses (choose others: coupling.cpus).
void bindThisProcess(const std::vector<int>& cpus);

// "0", "1-3", "0,2": the list as taskset and Slurm write it.
std::string cpuListText(const std::vector<int>& cpus);

}  // namespace cosim::util
