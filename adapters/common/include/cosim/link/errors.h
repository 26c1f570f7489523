#pragma once

#include <stdexcept>
#include <string>

#include "cosim/util/errors.h"

namespace cosim::link {

// The link's errors are peer errors of cosim's hierarchy (cosim/util/errors.h, exit code 3).

// A peer sent something this side cannot accept (bad bytes, wrong version, wrong step, bad field).
class ProtocolError : public cosim::PeerError {
 public:
  using cosim::PeerError::PeerError;
};

// A peer did not answer within the allowed time.
class TimeoutError : public cosim::PeerError {
 public:
  using cosim::PeerError::PeerError;
};

// The other side reported an error (wire::Error) or refused us, or went away.
class PeerError : public cosim::PeerError {
 public:
  using cosim::PeerError::PeerError;
};

}  // namespace cosim::link
