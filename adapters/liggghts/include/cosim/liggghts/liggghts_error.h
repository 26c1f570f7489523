// Turning LIGGGHTS' own fatal errors into C++ exceptions.
//
// LIGGGHTS 3.8 handles an error in the user's script with error->all (prints "ERROR: ..." to its
// screen file, closes it, calls MPI_Finalize and exit) or error->one (prints, calls MPI_Abort).
// Either would kill the adapter before it can tell the orchestrator why. This adapter uses the
// MPI profiling interface: it defines MPI_Finalize and MPI_Abort itself (forwarding to
// PMPI_Finalize / PMPI_Abort) and, while a LIGGGHTS command runs inside a LiggghtsCall scope,
// throws LiggghtsStop instead, which unwinds back to the Engine. The Engine then reads LIGGGHTS'
// message from the screen file and throws a LiggghtsError carrying it.
#pragma once

#include <stdexcept>
#include <string>

#include "cosim/util/errors.h"

namespace cosim::liggghts {

// Thrown from inside LIGGGHTS (through our MPI_Finalize / MPI_Abort) while a LiggghtsCall is
// active. Not derived from std::exception so nothing in between swallows it by accident.
struct LiggghtsStop {
  bool aborted;  // true: error->one (MPI_Abort, other ranks may be stuck); false: error->all
};

// Marks a stretch of code that calls into LIGGGHTS; nesting allowed.
class LiggghtsCall {
 public:
  LiggghtsCall();
  ~LiggghtsCall();
  LiggghtsCall(const LiggghtsCall&) = delete;
  LiggghtsCall& operator=(const LiggghtsCall&) = delete;
};

// The error a user sees: LIGGGHTS' own message plus where to look.
class LiggghtsError : public cosim::SolverError {
 public:
  LiggghtsError(const std::string& message, bool collective_broken)
      : cosim::SolverError(message), collective_broken_(collective_broken) {}
  // true when the other MPI ranks may be blocked (error->one): the process must MPI_Abort.
  bool collectiveBroken() const { return collective_broken_; }

 private:
  bool collective_broken_;
};

// Last "ERROR..." line of a LIGGGHTS screen/log file, or "" if there is none.
std::string lastErrorLine(const std::string& screen_file);

}  // namespace cosim::liggghts
