// One error hierarchy for every process of cosim (the orchestrator and the adapters), by what
// the user does about an error, and the one place where each kind becomes an exit code.
//
//   kind      what went wrong                                        what to do            exit
//   input     a scenario, a file, the command line, an option        fix it, run again        1
//   solver    a solver failed, a check on the physics stopped it    change the settings      2
//   peer      another process broke the protocol, fell silent or     resume (cosim resume)    3
//             went away (the network, the orchestrator, a rank)
//   resource  the machine lacks something: disk space, memory, a     free it, resume          4
//             socket, an executable, a time limit
//   (interrupted by Ctrl-C or SIGTERM: 130, 128 + the signal as a shell reports it)
//
// Header only and C++17, so that the OpenFOAM adapter (compiled against the v1912 headers)
// shares it.
#pragma once

#include <cerrno>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>

namespace cosim {

enum class ErrorKind { input, solver, peer, resource };

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  ErrorKind kind() const noexcept { return kind_; }

 private:
  ErrorKind kind_;
};

// A scenario, a file, the command line or an option is wrong: fix it and run again.
class InputError : public Error {
 public:
  explicit InputError(const std::string& what) : Error(ErrorKind::input, what) {}
};

// A solver failed or a check on the physics stopped the run: change the settings.
class SolverError : public Error {
 public:
  explicit SolverError(const std::string& what) : Error(ErrorKind::solver, what) {}
};

// Another process broke the protocol, fell silent or went away: resume once it is back.
class PeerError : public Error {
 public:
  explicit PeerError(const std::string& what) : Error(ErrorKind::peer, what) {}
};

// The machine lacks something (disk space, memory, a socket, an executable, a time limit):
// free it and resume.
class ResourceError : public Error {
 public:
  explicit ResourceError(const std::string& what) : Error(ErrorKind::resource, what) {}
};

namespace exit_code {
inline constexpr int ok = 0;
inline constexpr int input = 1;
inline constexpr int solver = 2;
inline constexpr int peer = 3;
inline constexpr int resource = 4;
inline constexpr int interrupted = 130;
}  // namespace exit_code

inline int exitCodeOf(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::input:
      return exit_code::input;
    case ErrorKind::solver:
      return exit_code::solver;
    case ErrorKind::peer:
      return exit_code::peer;
    case ErrorKind::resource:
      return exit_code::resource;
  }
  return exit_code::solver;
}

inline const char* nameOf(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::input:
      return "input";
    case ErrorKind::solver:
      return "solver";
    case ErrorKind::peer:
      return "peer";
    case ErrorKind::resource:
      return "resource";
  }
  return "solver";
}

// The kind of any exception: an Error's own, memory exhausted is a resource, anything else
// `otherwise` (what the caller was doing decides: reading input, or running a solver).
inline ErrorKind kindOf(const std::exception& e, ErrorKind otherwise) {
  if (const auto* c = dynamic_cast<const Error*>(&e)) return c->kind();
  if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr) return ErrorKind::resource;
  return otherwise;
}

// The kind of a failed file operation, from its errno: a path that does not exist or may not be
// written is an input error (choose another), anything else (the disk full, a quota, an I/O
// error, no memory) a resource.
inline ErrorKind kindOfErrno(int err) {
  switch (err) {
    case EACCES:
    case EPERM:
    case EROFS:
    case ENOENT:
    case ENOTDIR:
    case EISDIR:
    case ENAMETOOLONG:
    case ELOOP:
      return ErrorKind::input;
    default:
      return ErrorKind::resource;
  }
}

// The kind of error a cosim process ended with, from its exit code (the table above); killed by
// SIGKILL (128 + 9: the kernel out of memory, or a batch system's limit) is a resource; any other
// code or signal (a crash) a solver error.
inline ErrorKind kindOfExitCode(int code) {
  switch (code) {
    case exit_code::input:
      return ErrorKind::input;
    case exit_code::peer:
      return ErrorKind::peer;
    case exit_code::resource:
    case 128 + 9:
      return ErrorKind::resource;
    default:
      return ErrorKind::solver;
  }
}

}  // namespace cosim
