#include "cosim/liggghts/liggghts_error.h"

#include <mpi.h>

#include <fstream>

namespace {
int g_call_depth = 0;  // > 0 while LIGGGHTS code runs on this process (LIGGGHTS is single-threaded)
}

namespace cosim::liggghts {

LiggghtsCall::LiggghtsCall() { ++g_call_depth; }
LiggghtsCall::~LiggghtsCall() { --g_call_depth; }

std::string lastErrorLine(const std::string& screen_file) {
  std::ifstream in(screen_file);
  std::string line;
  std::string last;
  while (std::getline(in, line))
    if (line.rfind("ERROR", 0) == 0) last = line;
  return last;
}

}  // namespace cosim::liggghts

// MPI profiling-interface wrappers (see liggghts_error.h). Outside a LiggghtsCall they behave
// exactly like the library's functions.
extern "C" int MPI_Finalize(void) {
  if (g_call_depth > 0) throw cosim::liggghts::LiggghtsStop{false};
  return PMPI_Finalize();
}

extern "C" int MPI_Abort(MPI_Comm comm, int errorcode) {
  if (g_call_depth > 0) throw cosim::liggghts::LiggghtsStop{true};
  return PMPI_Abort(comm, errorcode);
}
