// Transport: ZeroMQ sockets carrying wire::Envelope messages. The orchestrator binds one Hub
// (ROUTER) at one address; each participant connects a Channel (DEALER); the hub tells its
// peers apart by their ZeroMQ routing ids. ipc:// locally, tcp:// across nodes, same code.
// Every receive is bounded. Over tcp:// the link is CurveZMQ (encrypted, and only the client
// keys the hub was given may connect: curve_keys.h) unless the scene says transport.insecure.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cosim.pb.h"
#include "cosim/link/curve_keys.h"

namespace cosim::link {

using Millis = std::chrono::milliseconds;

// Serialise / parse one envelope. parse throws ProtocolError on bytes that are not an Envelope.
std::string serialize(const wire::Envelope& env);
wire::Envelope parse(const void* data, std::size_t size);

// Participant side.
class Channel {
 public:
  // identity: the ZeroMQ routing id the hub sees as the peer; empty: one ZeroMQ makes up for
  // each connection (what participants use: a name a stranger could take first is no name to
  // rely on, so the orchestrator knows a participant by its Hello, not by its routing id).
  // curve: this participant's keys and the orchestrator's public key (empty: no encryption).
  Channel(const std::string& endpoint, const std::string& identity = "",
          const CurveClientKeys& curve = {});
  ~Channel();
  Channel(const Channel&) = delete;
  Channel& operator=(const Channel&) = delete;

  void send(const wire::Envelope& env);
  // nullopt on timeout; ProtocolError on undecodable bytes.
  std::optional<wire::Envelope> receive(Millis timeout);
  // Raw bytes (used by tests to send garbage).
  void sendRaw(const std::string& bytes);
  // How long this channel has been without a connection to the orchestrator's socket: zero
  // while connected, else the time since the connection closed (or since the channel was made,
  // if it never connected). A connection counts from the moment the socket connects, so an
  // orchestrator that is only slow or stopped (its socket still accepts) keeps it connected,
  // while one that is gone (nothing accepts at the address: killed, or its host unreachable
  // once ZeroMQ's heartbeat closes the connection) leaves it disconnected.
  Millis timeWithoutConnection();
  // How often this channel has connected again after losing a connection (ZeroMQ reconnects by
  // itself, e.g. once a network cut longer than its 5 s heartbeat is over). Whatever was in
  // flight on the lost connection may be lost, and the hub sees the new one as another peer.
  int reconnections();
  // Why the last security handshake with the orchestrator failed (e.g. its keys were refused),
  // empty if none did.
  std::string handshakeFailure();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The hub's CurveZMQ side: its key pair and the only client public keys it accepts.
struct HubSecurity {
  CurveKeyPair server;
  std::set<std::string> clients;  // Z85 public keys
  bool enabled() const { return !server.secret_key.empty(); }
};

// Orchestrator side.
class Hub {
 public:
  // security enabled: every connection is CurveZMQ; a ZAP handler (ZeroMQ's authentication
  // protocol, in a thread of the hub) lets in the clients whose public key is in
  // security.clients and refuses any other; a peer that does not speak CurveZMQ fails the
  // handshake. Neither reaches receive().
  explicit Hub(const std::string& endpoint, const HubSecurity& security = {});
  ~Hub();
  Hub(const Hub&) = delete;
  Hub& operator=(const Hub&) = delete;

  const std::string& endpoint() const;
  // To the peer with this routing id (Incoming::peer). Throws PeerError if it is not connected.
  void send(const std::string& peer, const wire::Envelope& env);

  struct Incoming {
    std::string peer;                        // the sender's routing id
    std::optional<wire::Envelope> envelope;  // empty if the bytes did not parse
    std::string parse_error;
  };
  // nullopt on timeout.
  std::optional<Incoming> receive(Millis timeout);

  // Lines saying which connections were refused since the last call (no keys in them): at most
  // 20 in the hub's life, then one saying that further ones are not listed.
  std::vector<std::string> takeRefusals();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cosim::link
