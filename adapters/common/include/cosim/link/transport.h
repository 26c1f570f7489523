// Transport: ZeroMQ sockets carrying wire::Envelope messages. The orchestrator binds one Hub
// (ROUTER) at one address; each participant connects a Channel (DEALER) whose routing id is its
// participant name. ipc:// locally, tcp:// across nodes, same code. Every receive is bounded.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "cosim.pb.h"

namespace cosim::link {

using Millis = std::chrono::milliseconds;

// Serialise / parse one envelope. parse throws ProtocolError on bytes that are not an Envelope.
std::string serialize(const wire::Envelope& env);
wire::Envelope parse(const void* data, std::size_t size);

// Participant side.
class Channel {
 public:
  Channel(const std::string& endpoint, const std::string& identity);
  ~Channel();
  Channel(const Channel&) = delete;
  Channel& operator=(const Channel&) = delete;

  void send(const wire::Envelope& env);
  // nullopt on timeout; ProtocolError on undecodable bytes.
  std::optional<wire::Envelope> receive(Millis timeout);
  // Raw bytes (used by tests to send garbage).
  void sendRaw(const std::string& bytes);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Orchestrator side.
class Hub {
 public:
  explicit Hub(const std::string& endpoint);
  ~Hub();
  Hub(const Hub&) = delete;
  Hub& operator=(const Hub&) = delete;

  const std::string& endpoint() const;
  void send(const std::string& peer, const wire::Envelope& env);

  struct Incoming {
    std::string peer;
    std::optional<wire::Envelope> envelope;  // empty if the bytes did not parse
    std::string parse_error;
  };
  // nullopt on timeout.
  std::optional<Incoming> receive(Millis timeout);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cosim::link
