#include "cosim/link/transport.h"

#include <google/protobuf/stubs/logging.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <thread>
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

void configure(zmq::socket_t& s, const std::string& endpoint) {
  s.set(zmq::sockopt::linger, 0);
  // Across a network (tcp://), connection-level liveness (ZMTP heartbeats) on top of our own
  // application heartbeats: a cut link is dropped after 5 s. Not on one machine (ipc://), where
  // no link can be cut and a process that ends closes its end at once, but a process can be
  // stopped (Ctrl-Z, kill -STOP): there the heartbeats would drop the link of the process that
  // did not answer while it was stopped, and the run with it when it is continued.
  if (endpoint.rfind("tcp://", 0) == 0) {
    s.set(zmq::sockopt::heartbeat_ivl, 1000);
    s.set(zmq::sockopt::heartbeat_timeout, 5000);
  }
}
}  // namespace

std::string serialize(const wire::Envelope& env) {
  std::string out;
  if (!env.SerializeToString(&out)) throw ProtocolError("cannot serialise message");
  return out;
}

namespace {
// The message's bytes written straight into ZeroMQ's buffer: a step's arrays are copied once,
// not once into a string and again into the frame.
zmq::message_t frameOf(const wire::Envelope& env) {
  const std::size_t size = env.ByteSizeLong();
  if (size > static_cast<std::size_t>(INT32_MAX))
    throw ProtocolError("cannot serialise a message of " + std::to_string(size) +
                        " bytes (protobuf's limit is 2 GiB)");
  zmq::message_t frame(size);
  env.SerializeWithCachedSizesToArray(static_cast<std::uint8_t*>(frame.data()));
  return frame;
}
}  // namespace

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
  bool ever_up = false;
  int reconnections = 0;
  std::chrono::steady_clock::time_point down_since = std::chrono::steady_clock::now();
  std::string handshake_failure;

  void on_event_connected(const zmq_event_t&, const char*) override {
    if (ever_up) ++reconnections;
    up = ever_up = true;
  }
  void on_event_disconnected(const zmq_event_t&, const char*) override {
    up = false;
    down_since = std::chrono::steady_clock::now();
  }
  void on_event_handshake_failed_auth(const zmq_event_t& e, const char*) override {
    handshake_failure = "the orchestrator refused this participant's CurveZMQ key (ZAP status " +
                        std::to_string(e.value) +
                        "): the key is not one it issued for this run (a key file of another "
                        "run?)";
  }
  void on_event_handshake_failed_protocol(const zmq_event_t&, const char*) override {
    handshake_failure =
        "the security handshake with the orchestrator failed: one side uses CurveZMQ and the "
        "other not, or the orchestrator's public key is not the one in this participant's keys "
        "(--key-file of this run, or transport.insecure on both sides)";
  }
  void on_event_handshake_failed_no_detail(const zmq_event_t&, const char*) override {
    handshake_failure =
        "the security handshake with the orchestrator failed (is the orchestrator's public key "
        "in this participant's keys the one of this run?)";
  }
  void on_event_handshake_succeeded(const zmq_event_t&, const char*) override {
    handshake_failure.clear();
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

Channel::Channel(const std::string& endpoint, const std::string& identity,
                 const CurveClientKeys& curve)
    : impl_(std::make_unique<Impl>()) {
  silenceProtobufLog();
  configure(impl_->socket, endpoint);
  if (!identity.empty()) impl_->socket.set(zmq::sockopt::routing_id, identity);
  if (!curve.empty()) {
    requireCurve();
    impl_->socket.set(zmq::sockopt::curve_serverkey, curve.orchestrator_public);
    impl_->socket.set(zmq::sockopt::curve_publickey, curve.own.public_key);
    impl_->socket.set(zmq::sockopt::curve_secretkey, curve.own.secret_key);
  }
  impl_->watch.init(impl_->socket, uniqueMonitorAddress(),
                    ZMQ_EVENT_CONNECTED | ZMQ_EVENT_DISCONNECTED |
                        ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL | ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL |
                        ZMQ_EVENT_HANDSHAKE_FAILED_AUTH | ZMQ_EVENT_HANDSHAKE_SUCCEEDED);
  impl_->socket.connect(endpoint);
}

std::string Channel::handshakeFailure() {
  while (impl_->watch.check_event(0)) {
  }
  return impl_->watch.handshake_failure;
}

Millis Channel::timeWithoutConnection() {
  while (impl_->watch.check_event(0)) {
  }
  if (impl_->watch.up) return Millis(0);
  return std::chrono::duration_cast<Millis>(std::chrono::steady_clock::now() -
                                            impl_->watch.down_since);
}

int Channel::reconnections() {
  while (impl_->watch.check_event(0)) {
  }
  return impl_->watch.reconnections;
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

namespace {
// Waits while the message cannot be queued (no connection yet, or a full queue), as a blocking
// send would, but not for a connection the orchestrator refused at its security handshake
// (`refused` says why, empty while it was not): ZeroMQ then drops the connection and a blocking
// send would wait for ever. A send that cannot queue leaves the frame as it was.
template <class Refused>
void queue(zmq::socket_t& socket, zmq::message_t& frame, Refused refused) {
  for (;;) {
    if (socket.send(frame, zmq::send_flags::dontwait)) return;
    if (const std::string failure = refused(); !failure.empty()) throw PeerError(failure);
    zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLOUT, 0};
    try {
      zmq::poll(&item, 1, Millis(100));
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) throw;
    }
  }
}
}  // namespace

void Channel::send(const wire::Envelope& env) {
  zmq::message_t frame = frameOf(env);
  queue(impl_->socket, frame, [this] { return handshakeFailure(); });
}

void Channel::sendRaw(const std::string& bytes) {
  zmq::message_t frame(bytes.data(), bytes.size());
  queue(impl_->socket, frame, [this] { return handshakeFailure(); });
}

std::optional<wire::Envelope> Channel::receive(Millis timeout) {
  if (!readable(impl_->socket, timeout)) return std::nullopt;
  zmq::message_t msg;
  if (!impl_->socket.recv(msg, zmq::recv_flags::dontwait)) return std::nullopt;
  return parse(msg.data(), msg.size());
}

// ---- Hub -------------------------------------------------------------------------------------

namespace {
// At most this many refused connections are described (takeRefusals), whatever a stranger does.
constexpr std::size_t kMaxRefusalLines = 20;
constexpr const char* kZapEndpoint = "inproc://zeromq.zap.01";
constexpr const char* kHubMonitor = "inproc://cosim-hub-monitor";
}  // namespace

// The hub has a ZeroMQ context of its own: ZeroMQ asks the ZAP handler bound at
// inproc://zeromq.zap.01 in the socket's context, one per context, so that every hub (tests make
// several in one process) has its own.
struct Hub::Impl {
  zmq::context_t ctx{1};
  zmq::socket_t socket{ctx, zmq::socket_type::router};
  std::string endpoint;
  std::string ipc_file;  // the socket file this hub created, removed with it

  // CurveZMQ: the ZAP handler and the watch of failed handshakes, in a thread of their own.
  HubSecurity security;
  std::thread guard;
  std::atomic<bool> stop{false};
  std::mutex refusals_mutex;
  std::vector<std::string> refusals;
  std::size_t refusals_described = 0;

  void refused(const std::string& line) {
    std::lock_guard<std::mutex> lock(refusals_mutex);
    if (refusals_described > kMaxRefusalLines) return;
    ++refusals_described;
    refusals.push_back(refusals_described > kMaxRefusalLines
                           ? "further refused connections are not listed"
                           : line);
  }
  void serveZap(zmq::socket_t& zap);
  void noteHandshakeEvent(zmq::socket_t& monitor);
  void runGuard(zmq::socket_t zap, zmq::socket_t monitor);
};

// One ZAP request (RFC 27): version, request id, domain, address, routing id, mechanism,
// credentials; answered 200 for a client key of this run, 400 for any other.
void Hub::Impl::serveZap(zmq::socket_t& zap) {
  std::vector<zmq::message_t> frames;
  do {
    frames.emplace_back();
    if (!zap.recv(frames.back(), zmq::recv_flags::dontwait)) return;
  } while (frames.back().more() && frames.size() < 16);
  while (frames.back().more()) {  // drain what no ZAP request has
    zmq::message_t extra;
    if (!zap.recv(extra, zmq::recv_flags::dontwait)) break;
    frames.back() = std::move(extra);
  }
  const std::string request_id = frames.size() > 1 ? frames[1].to_string() : "";
  const std::string address = frames.size() > 3 ? frames[3].to_string() : "?";
  const std::string mechanism = frames.size() > 5 ? frames[5].to_string() : "";
  bool ok = false;
  std::string why = "it does not use CurveZMQ";
  if (mechanism == "CURVE" && frames.size() > 6 && frames[6].size() == 32) {
    char z85[41] = {0};
    zmq_z85_encode(z85, static_cast<const std::uint8_t*>(frames[6].data()), 32);
    ok = security.clients.count(z85) > 0;
    why = "its key was not issued for this run";
  }
  if (!ok) refused("refused a connection from " + address + ": " + why);
  const std::string status = ok ? "200" : "400";
  const std::string text = ok ? "OK" : "key not issued for this run";
  zap.send(zmq::buffer(std::string("1.0")), zmq::send_flags::sndmore);
  zap.send(zmq::buffer(request_id), zmq::send_flags::sndmore);
  zap.send(zmq::buffer(status), zmq::send_flags::sndmore);
  zap.send(zmq::buffer(text), zmq::send_flags::sndmore);
  zap.send(zmq::buffer(std::string()), zmq::send_flags::sndmore);  // user id
  zap.send(zmq::buffer(std::string()), zmq::send_flags::none);     // metadata
}

// A socket monitor event: 2 bytes event, 4 bytes value, then the peer's address.
void Hub::Impl::noteHandshakeEvent(zmq::socket_t& monitor) {
  zmq::message_t head, address;
  if (!monitor.recv(head, zmq::recv_flags::dontwait)) return;
  if (head.more()) (void)monitor.recv(address, zmq::recv_flags::dontwait);
  if (head.size() < 2) return;
  std::uint16_t event = 0;
  std::memcpy(&event, head.data(), sizeof event);
  if (event == ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL || event == ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL)
    refused("refused a connection from " + address.to_string() +
            ": its security handshake failed (no CurveZMQ keys, a wrong orchestrator key, or "
            "bytes that are not ZeroMQ)");
}

void Hub::Impl::runGuard(zmq::socket_t zap, zmq::socket_t monitor) {
  while (!stop) {
    zmq::pollitem_t items[] = {{zap.handle(), 0, ZMQ_POLLIN, 0},
                               {monitor.handle(), 0, ZMQ_POLLIN, 0}};
    try {
      zmq::poll(items, 2, Millis(100));
      if (items[0].revents & ZMQ_POLLIN) serveZap(zap);
      if (items[1].revents & ZMQ_POLLIN) noteHandshakeEvent(monitor);
    } catch (const zmq::error_t& e) {
      if (e.num() == ETERM) return;
      // EINTR and the like: poll again.
    }
  }
}

Hub::Hub(const std::string& endpoint, const HubSecurity& security)
    : impl_(std::make_unique<Impl>()) {
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
  }
  configure(impl_->socket, endpoint);
  // Fail loudly when sending to a peer that is not (or no longer) connected.
  impl_->socket.set(zmq::sockopt::router_mandatory, true);
  if (security.enabled()) {
    requireCurve();
    impl_->security = security;
    // The handler is bound before the hub's socket: no connection is ever let in unasked.
    zmq::socket_t zap(impl_->ctx, zmq::socket_type::rep);
    zap.set(zmq::sockopt::linger, 0);
    zap.bind(kZapEndpoint);
    if (zmq_socket_monitor(
            impl_->socket.handle(), kHubMonitor,
            ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL) != 0)
      throw PeerError(std::string("cannot watch the hub's handshakes: ") +
                      zmq_strerror(zmq_errno()));
    zmq::socket_t monitor(impl_->ctx, zmq::socket_type::pair);
    monitor.set(zmq::sockopt::linger, 0);
    monitor.connect(kHubMonitor);
    impl_->socket.set(zmq::sockopt::curve_server, true);
    impl_->socket.set(zmq::sockopt::curve_secretkey, security.server.secret_key);
    impl_->socket.set(zmq::sockopt::zap_domain, "cosim");
    Impl* impl = impl_.get();
    impl_->guard = std::thread([impl, z = std::move(zap), m = std::move(monitor)]() mutable {
      impl->runGuard(std::move(z), std::move(m));
    });
  }
  try {
    impl_->socket.bind(endpoint);
  } catch (...) {
    impl_->stop = true;
    if (impl_->guard.joinable()) impl_->guard.join();
    throw;
  }
  if (endpoint.rfind("ipc://", 0) == 0) impl_->ipc_file = endpoint.substr(6);
  impl_->endpoint = impl_->socket.get(zmq::sockopt::last_endpoint);
}

Hub::~Hub() {
  if (!impl_) return;
  impl_->stop = true;
  if (impl_->guard.joinable()) impl_->guard.join();
  impl_->socket.close();
  if (impl_->ipc_file.empty()) return;
  // Only the socket this hub bound: a socket file, at the path nothing existed at before.
  std::error_code ec;
  if (std::filesystem::symlink_status(impl_->ipc_file, ec).type() ==
      std::filesystem::file_type::socket) {
    std::filesystem::remove(impl_->ipc_file, ec);
  }
}

std::vector<std::string> Hub::takeRefusals() {
  std::lock_guard<std::mutex> lock(impl_->refusals_mutex);
  return std::exchange(impl_->refusals, {});
}

const std::string& Hub::endpoint() const { return impl_->endpoint; }

void Hub::send(const std::string& peer, const wire::Envelope& env) {
  zmq::message_t frame = frameOf(env);
  try {
    impl_->socket.send(zmq::buffer(peer), zmq::send_flags::sndmore);
    impl_->socket.send(frame, zmq::send_flags::none);
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
