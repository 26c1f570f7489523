#pragma once

#include <stdexcept>
#include <string>

namespace cosim::link {

// A peer sent something this side cannot accept (bad bytes, wrong version, wrong step, bad field).
class ProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A peer did not answer within the allowed time.
class TimeoutError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The other side reported an error (wire::Error) or refused us.
class PeerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cosim::link
