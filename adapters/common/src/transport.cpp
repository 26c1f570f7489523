#include "cosim/link/transport.h"

#include <google/protobuf/stubs/logging.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <zmq.hpp>

#include "cosim/link/errors.h"

namespace cosim::link {

namespace {
// Bytes from a peer that do not parse are reported as a ProtocolError by parse(); protobuf's own
// line on stderr for each (e.g. a string that is not UTF-8) would let any stranger fill the
// console. Silenced once, before the first socket exists.
void silenceProtobufLog() {
  static const bool silenced = (google::protobuf::SetLogHandler(nullptr), true);
  (void)silenced;
}

zmq::context_t& context() {
  static zmq::context_t ctx(1);
  return ctx;
}

void configure(zmq::socket_t& s) {
  s.set(zmq::sockopt::linger, 0);
  // Connection-level liveness (ZMTP heartbeats) on top of our own application heartbeats.
  s.set(zmq::sockopt::heartbeat_ivl, 1000);
  s.set(zmq::sockopt::heartbeat_timeout, 5000);
}
}  // namespace

std::string serialize(const wire::Envelope& env) {
  std::string out;
  if (!env.SerializeToString(&out)) throw ProtocolError("cannot serialise message");
  return out;
}

wire::Envelope parse(const void* data, std::size_t size) {
  silenceProtobufLog();
  wire::Envelope env;
  if (size > static_cast<std::size_t>(INT32_MAX) ||
      !env.ParseFromArray(data, static_cast<int>(size))) {
    throw ProtocolError("received " + std::to_string(size) +
                        " bytes that are not a cosim message (wrong peer or corrupted data)");
  }
  if (!env.has_header()) throw ProtocolError("received a cosim message without header");
  if (env.body_case() == wire::Envelope::BODY_NOT_SET) {
    throw ProtocolError("received a cosim message without body (unknown message type?)");
  }
  return env;
}

// ---- Channel ---------------------------------------------------------------------------------

namespace {
// A channel's connection, from ZeroMQ's socket monitor: up on CONNECTED, down on DISCONNECTED
// (and from the start until the first connection).
class ConnectionWatch : public zmq::monitor_t {
 public:
  bool up = false;
  std::chrono::steady_clock::time_point down_since = std::chrono::steady_clock::now();

  void on_event_connected(const zmq_event_t&, const char*) override { up = true; }
  void on_event_disconnected(const zmq_event_t&, const char*) override {
    up = false;
    down_since = std::chrono::steady_clock::now();
  }
};

std::string uniqueMonitorAddress() {
  static std::atomic<unsigned long> next{0};
  return "inproc://cosim-channel-watch-" + std::to_string(next++);
}
}  // namespace

struct Channel::Impl {
  zmq::socket_t socket{context(), zmq::socket_type::dealer};
  ConnectionWatch watch;  // declared after the socket: stops monitoring before it closes
};

Channel::Channel(const std::string& endpoint, const std::string& identity)
    : impl_(std::make_unique<Impl>()) {
  silenceProtobufLog();
  configure(impl_->socket);
  if (!identity.empty()) impl_->socket.set(zmq::sockopt::routing_id, identity);
  impl_->watch.init(impl_->socket, uniqueMonitorAddress(),
                    ZMQ_EVENT_CONNECTED | ZMQ_EVENT_DISCONNECTED);
  impl_->socket.connect(endpoint);
}

Millis Channel::timeWithoutConnection() {
  while (impl_->watch.check_event(0)) {
  }
  if (impl_->watch.up) return Millis(0);
  return std::chrono::duration_cast<Millis>(std::chrono::steady_clock::now() -
                                            impl_->watch.down_since);
}

namespace {
// Waits up to `timeout` for a message. A signal (Ctrl-C) interrupting the wait is a wake-up
// without a message, not an error: the caller's loop decides what the signal means.
bool readable(zmq::socket_t& socket, Millis timeout) {
  zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLIN, 0};
  try {
    zmq::poll(&item, 1, timeout);
  } catch (const zmq::error_t& e) {
    if (e.num() == EINTR) return false;
    throw;
  }
  return (item.revents & ZMQ_POLLIN) != 0;
}
}  // namespace

Channel::~Channel() = default;

void Channel::send(const wire::Envelope& env) { sendRaw(serialize(env)); }

void Channel::sendRaw(const std::string& bytes) {
  impl_->socket.send(zmq::buffer(bytes), zmq::send_flags::none);
}

std::optional<wire::Envelope> Channel::receive(Millis timeout) {
  if (!readable(impl_->socket, timeout)) return std::nullopt;
  zmq::message_t msg;
  if (!impl_->socket.recv(msg, zmq::recv_flags::dontwait)) return std::nullopt;
  return parse(msg.data(), msg.size());
}

// ---- Hub -------------------------------------------------------------------------------------

struct Hub::Impl {
  zmq::socket_t socket{context(), zmq::socket_type::router};
  std::string endpoint;
  std::string ipc_file;  // the socket file this hub created, removed with it
};

Hub::Hub(const std::string& endpoint) : impl_(std::make_unique<Impl>()) {
  silenceProtobufLog();
  // ZeroMQ unlinks whatever file an ipc:// endpoint names before it binds: never bind a path
  // that exists, so that no address can make cosim delete a file it did not create.
  if (endpoint.rfind("ipc://", 0) == 0) {
    const std::string path = endpoint.substr(6);
    std::error_code ec;
    if (path.empty() ||
        std::filesystem::symlink_status(path, ec).type() != std::filesystem::file_type::not_found) {
      throw PeerError("refusing to bind '" + endpoint +
                      "': the file exists (ZeroMQ would delete it); give an ipc path that does "
                      "not exist");
    }
    impl_->ipc_file = path;
  }
  configure(impl_->socket);
  // Fail loudly when sending to a peer that is not (or no longer) connected.
  impl_->socket.set(zmq::sockopt::router_mandatory, true);
  impl_->socket.bind(endpoint);
  impl_->endpoint = impl_->socket.get(zmq::sockopt::last_endpoint);
}

Hub::~Hub() {
  if (!impl_ || impl_->ipc_file.empty()) return;
  impl_->socket.close();
  // Only the socket this hub bound: a socket file, at the path nothing existed at before.
  std::error_code ec;
  if (std::filesystem::symlink_status(impl_->ipc_file, ec).type() ==
      std::filesystem::file_type::socket) {
    std::filesystem::remove(impl_->ipc_file, ec);
  }
}

const std::string& Hub::endpoint() const { return impl_->endpoint; }

void Hub::send(const std::string& peer, const wire::Envelope& env) {
  const std::string bytes = serialize(env);
  try {
    impl_->socket.send(zmq::buffer(peer), zmq::send_flags::sndmore);
    impl_->socket.send(zmq::buffer(bytes), zmq::send_flags::none);
  } catch (const zmq::error_t& e) {
    throw PeerError(std::string("cannot send to the peer: ") + e.what() +
                    " (not connected or gone)");
  }
}

std::optional<Hub::Incoming> Hub::receive(Millis timeout) {
  if (!readable(impl_->socket, timeout)) return std::nullopt;
  zmq::message_t id;
  zmq::message_t body;
  if (!impl_->socket.recv(id, zmq::recv_flags::dontwait)) return std::nullopt;
  Incoming in;
  in.peer = id.to_string();
  // A frame after the routing id is expected; extra frames are drained and reported.
  if (!id.more() || !impl_->socket.recv(body, zmq::recv_flags::dontwait)) {
    in.parse_error = "empty message";
    return in;
  }
  while (body.more()) {
    zmq::message_t extra;
    if (!impl_->socket.recv(extra, zmq::recv_flags::dontwait)) break;
    in.parse_error = "unexpected multi-part message";
    if (!extra.more()) break;
  }
  if (!in.parse_error.empty()) return in;
  try {
    in.envelope = parse(body.data(), body.size());
  } catch (const ProtocolError& e) {
    in.parse_error = e.what();
  }
  return in;
}

}  // namespace cosim::link
