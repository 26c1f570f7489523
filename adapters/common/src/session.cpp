#include "cosim/link/session.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "CLI/CLI.hpp"
#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/file_transfer.h"
#include "cosim/link/particle_wire.h"

namespace cosim::link {

namespace fs = std::filesystem;

namespace {
using Clock = std::chrono::steady_clock;

// How often an unanswered Hello is sent again, and how often a wait for a command looks
// whether the orchestrator is gone.
constexpr Millis kHelloResend{1000};
constexpr Millis kCommandSlice{200};
// Time the solver gets to come back to the session after the orchestrator is gone, before the
// heartbeat thread ends the process (exitProcessWhenOrphaned).
constexpr Millis kOrphanGrace{5000};

// Why a participant whose connection to the orchestrator was lost and made again stops.
std::string reconnectedMessage(const std::string& endpoint) {
  return "the connection to the orchestrator at " + endpoint +
         " was lost and made again (the network between them was cut for longer than ZeroMQ's "
         "5 s heartbeat): messages in flight may have been lost, so this participant cannot go "
         "on with the run; stopping (the orchestrator stops the run too; continue it with "
         "cosim resume)";
}

Millis until(Clock::time_point deadline) {
  return std::max(Millis(0), std::chrono::duration_cast<Millis>(deadline - Clock::now()));
}

// The run token in `file` (surrounding white space removed).
std::string readTokenFile(const std::string& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  std::string token = text.str();
  const auto first = token.find_first_not_of(" \t\r\n");
  const auto last = token.find_last_not_of(" \t\r\n");
  token = first == std::string::npos ? "" : token.substr(first, last - first + 1);
  if (!in.is_open() || token.empty()) {
    const int err = errno;
    throw Error(in.is_open() ? ErrorKind::input : kindOfErrno(err),
                "--token-file " + file + ": " +
                    (in.is_open() ? "the file is empty" : std::strerror(err)) +
                    "; cosim writes the run's token to .cosim-run-token in the run folder "
                    "when it starts a run with a participant of launch: external");
  }
  return token;
}

const char* bodyName(const wire::Envelope& e) {
  switch (e.body_case()) {
    case wire::Envelope::kHello:
      return "Hello";
    case wire::Envelope::kWelcome:
      return "Welcome";
    case wire::Envelope::kRefused:
      return "Refused";
    case wire::Envelope::kSample:
      return "Sample";
    case wire::Envelope::kSamples:
      return "Samples";
    case wire::Envelope::kAdvance:
      return "Advance";
    case wire::Envelope::kAdvanced:
      return "Advanced";
    case wire::Envelope::kCheckpoint:
      return "Checkpoint";
    case wire::Envelope::kCheckpointWritten:
      return "CheckpointWritten";
    case wire::Envelope::kShutdown:
      return "Shutdown";
    case wire::Envelope::kGoodbye:
      return "Goodbye";
    case wire::Envelope::kError:
      return "Error";
    case wire::Envelope::kHeartbeat:
      return "Heartbeat";
    case wire::Envelope::kPeerReady:
      return "PeerReady";
    default:
      return "(none)";
  }
}
}  // namespace

std::optional<ParticipantOptions> ParticipantOptions::parse(int argc, char** argv,
                                                            const std::string& about,
                                                            std::vector<std::string>* rest) {
  const std::string program = argc > 0 ? argv[0] : "adapter";
  const std::string usage = "usage: " + program +
                            " --endpoint ENDPOINT --name PARTICIPANT [--run-id ID] (normally "
                            "started by `cosim run`)";
  ParticipantOptions o;
  int command_timeout_s = o.command_timeout_ms / 1000;
  CLI::App app(about, program);
  app.set_help_flag("--help", "print this help and exit");
  app.allow_extras();
  app.add_option("--endpoint", o.endpoint, "the orchestrator's ZeroMQ address (ipc:// or tcp://)");
  app.add_option("--name", o.name, "this participant's name in the scenario (fluid, particles)");
  app.add_option("--run-id", o.run_id, "the run's id, checked against the orchestrator's Welcome");
  std::string token_file;
  app.add_option("--token-file", token_file,
                 "file holding the run's token (RUN/.cosim-run-token; otherwise the environment "
                 "variable " +
                     std::string(kRunTokenVariable) + ")");
  std::string key_file;
  app.add_option("--key-file", key_file,
                 "file holding this participant's CurveZMQ keys for a tcp:// run (cosim writes it "
                 "to RUN/.cosim-NAME.key for participants of launch: external; otherwise the "
                 "environment variable " +
                     std::string(kCurveKeysVariable) + ")");
  app.add_option("--heartbeat-ms", o.heartbeat_ms, "heartbeat interval [ms]")
      ->capture_default_str();
  app.add_option("--command-timeout", command_timeout_s,
                 "give up when the orchestrator is silent this long [s]")
      ->capture_default_str();
  app.add_option("--check-options", o.check_options,
                 "only check a scene's options for this adapter and exit (0: accepted, 2: "
                 "refused, with the reason); FILE is written by `cosim validate`");
  app.add_option("--workdir", o.workdir,
                 "a folder of this participant's own on its node, when it does not see the run "
                 "folder: case files and restarts come over the link, checkpoints go back");
  app.add_option("--ranks", o.check_ranks, "with --check-options: the MPI ranks of the run")
      ->check(CLI::Range(1, 4096));
  app.add_flag("--options-reference", o.options_reference,
               "print this adapter's options (the scenario's participants.NAME.options) with "
               "their defaults and meaning as a Markdown table, and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    throw InputError(std::string(e.what()) + "; " + usage);
  }
  o.command_timeout_ms = 1000 * command_timeout_s;
  if (rest != nullptr) *rest = app.remaining();
  if (!o.check_options.empty() || o.options_reference) return o;
  if (o.endpoint.empty() || o.name.empty()) throw InputError(usage);
  if (!token_file.empty()) {
    o.token = readTokenFile(token_file);
  } else if (const char* t = std::getenv(kRunTokenVariable)) {
    o.token = t;
  }
  if (!key_file.empty()) {
    const ParticipantKeyFile f = readParticipantKeyFile(key_file);
    if (!f.participant.empty() && f.participant != o.name) {
      throw InputError("--key-file " + key_file + " holds the keys of participant '" +
                       f.participant + "', not of '" + o.name +
                       "': give this participant its own key file");
    }
    if (!o.run_id.empty() && !f.run_id.empty() && f.run_id != o.run_id) {
      throw InputError("--key-file " + key_file + " holds the keys of run " + f.run_id +
                       ", not of run " + o.run_id +
                       ": every run issues new keys; copy this run's key file");
    }
    o.curve = f.keys;
  } else if (const char* k = std::getenv(kCurveKeysVariable)) {
    o.curve = parseCurveKeysVariable(k);
  }
  return o;
}

Session::Session(const ParticipantOptions& options, const Capabilities& caps)
    : options_(options),
      caps_(caps),
      channel_(std::make_unique<Channel>(options.endpoint, "", options.curve)) {}

Session::~Session() {
  stop_heartbeat_ = true;
  if (heartbeat_.joinable()) heartbeat_.join();
}

void Session::fillHeader(wire::Header* h) const {
  h->set_protocol_version(wire::PROTOCOL_VERSION);
  h->set_run_id(run_id_);
  h->set_participant(options_.name);
  h->set_step(step_);
  h->set_time(time_);
  h->set_token(options_.token);
}

wire::Welcome Session::handshake() {
  wire::Envelope hello;
  fillHeader(hello.mutable_header());
  auto* h = hello.mutable_hello();
  h->set_role(caps_.role);
  h->set_adapter(caps_.adapter);
  for (const auto& f : caps_.provides) h->add_provides(f);
  for (const auto& f : caps_.accepts) h->add_accepts(f);
  h->set_pid(static_cast<int>(getpid()));
  char host[256] = {0};
  gethostname(host, sizeof(host) - 1);
  h->set_host(host);
  h->set_own_folder(!options_.workdir.empty());

  // Sent again every second until answered: the orchestrator ignores the copies it gets after
  // its Welcome, and a stranger that held this participant's name at the orchestrator's socket
  // when the first one went out only delays it.
  const auto deadline = Clock::now() + Millis(options_.handshake_timeout_ms);
  std::optional<wire::Envelope> reply;
  while (!reply && Clock::now() < deadline) {
    try {
      channel_->send(hello);
    } catch (const PeerError& e) {
      throw PeerError("the orchestrator at " + options_.endpoint +
                      " does not let this participant in: " + e.what());
    }
    reply = channel_->receive(std::min(kHelloResend, until(deadline)));
  }
  if (!reply) {
    const std::string failure = channel_->handshakeFailure();
    throw TimeoutError(
        "no answer from the orchestrator at " + options_.endpoint + " within " +
        std::to_string(options_.handshake_timeout_ms / 1000) + " s" +
        (failure.empty() ? std::string() : ": " + failure) +
        (failure.empty() && options_.curve.empty() && options_.endpoint.rfind("tcp://", 0) == 0
             ? std::string(" (this participant has no CurveZMQ keys: over tcp:// the "
                           "orchestrator accepts only the keys it issued, --key-file)")
             : std::string()));
  }
  if (reply->has_refused()) {
    throw PeerError("the orchestrator refused this participant: " + reply->refused().reason());
  }
  if (!reply->has_welcome()) {
    throw ProtocolError(std::string("expected Welcome from the orchestrator, got ") +
                        bodyName(*reply));
  }
  if (!options_.run_id.empty() && reply->header().run_id() != options_.run_id) {
    throw ProtocolError("run id mismatch: started for run '" + options_.run_id +
                        "' but the orchestrator runs '" + reply->header().run_id() + "'");
  }
  run_id_ = reply->header().run_id();
  reconnections_at_welcome_ = channel_->reconnections();

  // Heartbeats from a socket of their own (ZeroMQ sockets belong to one thread). Its connection
  // also tells whether the orchestrator is still there.
  heartbeat_ = std::thread([this] {
    Channel hb(options_.endpoint, "", options_.curve);
    std::uint64_t seq = 0;
    Clock::time_point gone_at;
    while (!stop_heartbeat_) {
      // Connected again after a loss: the command channel will have lost its connection too,
      // and no more heartbeats must make the orchestrator wait for this participant.
      if (!orchestrator_gone_ && hb.reconnections() > 0) {
        gone_message_ = reconnectedMessage(options_.endpoint);
        gone_at = Clock::now();
        orchestrator_gone_ = true;
      }
      if (!orchestrator_gone_) {
        wire::Envelope e;
        fillHeader(e.mutable_header());
        e.mutable_heartbeat()->set_sequence(seq++);
        try {
          hb.send(e);
        } catch (...) {
        }
        const Millis lost = hb.timeWithoutConnection();
        if (lost > Millis(options_.orchestrator_gone_ms)) {
          gone_message_ = "the orchestrator at " + options_.endpoint +
                          " is gone: no connection to it for " +
                          std::to_string(lost.count() / 1000) +
                          " s (cosim was killed, its host is down, or the network to it is cut); "
                          "stopping";
          gone_at = Clock::now();
          orchestrator_gone_ = true;
        }
      } else if (exit_when_orphaned_ && Clock::now() - gone_at > kOrphanGrace) {
        // The solver is still busy in a step: nobody will ever read its result.
        std::cerr << "[" << options_.name << "] " << gone_message_ << std::endl;
        std::_Exit(3);
      }
      for (int waited = 0; waited < options_.heartbeat_ms && !stop_heartbeat_; waited += 50) {
        std::this_thread::sleep_for(Millis(50));
      }
    }
  });
  wire::Welcome welcome = reply->welcome();
  if (!options_.workdir.empty()) receiveFiles(welcome);
  return welcome;
}

// A participant with a folder of its own: the case files and the restart the Welcome carries
// are written there, and the Welcome then names that folder instead of the run folder's.
void Session::receiveFiles(wire::Welcome& welcome) const {
  const fs::path own = fs::absolute(options_.workdir);
  fs::create_directories(own);
  unpackFiles(welcome.case_files(), own);
  welcome.clear_case_files();
  welcome.set_workdir(own.string());
  if (!welcome.restart_from().empty()) {
    const fs::path restart = own / "restart";
    fs::remove_all(restart);
    fs::create_directories(restart);
    unpackFiles(welcome.restart_files(), restart);
    welcome.set_restart_from(restart.string());
  }
  welcome.clear_restart_files();
}

wire::Envelope Session::nextCommand() {
  const auto deadline = Clock::now() + Millis(options_.command_timeout_ms);
  std::optional<wire::Envelope> env;
  while (!env) {
    env = channel_->receive(std::min(kCommandSlice, until(deadline)));
    if (env) break;
    if (orchestrator_gone_) throw PeerError(gone_message_);
    checkStillConnected();
    if (Clock::now() >= deadline) {
      throw TimeoutError("the orchestrator sent nothing for " +
                         std::to_string(options_.command_timeout_ms / 1000) + " s; giving up");
    }
  }
  const auto& h = env->header();
  if (h.protocol_version() != wire::PROTOCOL_VERSION) {
    throw ProtocolError("orchestrator speaks protocol version " +
                        std::to_string(h.protocol_version()) + ", this adapter " +
                        std::to_string(wire::PROTOCOL_VERSION));
  }
  if (h.run_id() != run_id_) {
    throw ProtocolError("message for run '" + h.run_id() + "' but this participant is in run '" +
                        run_id_ + "'");
  }
  if (env->has_error()) {
    throw PeerError("orchestrator aborted the run: " + env->error().message());
  }
  const bool in_order = !any_command_ ? true : (h.step() == step_ || h.step() == step_ + 1);
  if (!in_order) {
    const std::string msg = std::string(bodyName(*env)) + " for step " + std::to_string(h.step()) +
                            " refused: this participant is at step " + std::to_string(step_) +
                            " (out-of-order step)";
    sendError(msg, "header.step");
    throw ProtocolError(msg);
  }
  any_command_ = true;
  step_ = h.step();
  time_ = h.time();
  return std::move(*env);
}

void Session::checkOrchestrator() {
  if (orchestrator_gone_) throw PeerError(gone_message_);
  checkStillConnected();
}

void Session::checkStillConnected() {
  if (channel_->reconnections() != reconnections_at_welcome_)
    throw PeerError(reconnectedMessage(options_.endpoint));
}

void Session::reply(wire::Envelope& env) {
  checkStillConnected();
  fillHeader(env.mutable_header());
  channel_->send(env);
}

void Session::sendError(const std::string& message, const std::string& where) {
  wire::Envelope e;
  fillHeader(e.mutable_header());
  e.mutable_error()->set_message(message);
  e.mutable_error()->set_where(where);
  try {
    channel_->send(e);
  } catch (...) {
  }
}

bool checkOptionsRequested(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--check-options" || a.rfind("--check-options=", 0) == 0 || a == "--options-reference")
      return true;
  }
  return false;
}

int checkSceneOptions(const ParticipantOptions& options, const SceneCheck& check) {
  std::ifstream in(options.check_options, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  wire::Welcome welcome;
  if (!in.is_open() || !welcome.ParseFromString(bytes.str())) {
    std::cerr << "--check-options " << options.check_options << ": "
              << (in.is_open() ? "not a Welcome message" : std::strerror(errno))
              << "; the file is written by `cosim validate`\n";
    return cosim::exit_code::input;
  }
  try {
    check(welcome, options.check_ranks);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return cosim::exitCodeOf(cosim::kindOf(e, cosim::ErrorKind::input));
  }
  std::cout << "options accepted\n";
  return 0;
}

void sampleInto(Solver& solver, const ParticleData& in, wire::Samples& s,
                SharedArrayWriter* shared) {
  const auto t0 = std::chrono::steady_clock::now();
  ParticleData samples;
  samples.ids = in.ids;
  std::vector<std::int64_t> lost;
  solver.sample(in, samples, lost);
  cosim::link::toWire(samples, *s.mutable_at_particles(), shared);
  s.mutable_lost_ids()->Assign(lost.begin(), lost.end());
  s.set_wall_seconds(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

ParticleData predictedAt(ParticleData at, double dt) {
  if (!at.has(field::position) || !at.has(field::velocity)) return at;
  auto& x = at.field(field::position);
  const auto& v = at.get(field::velocity);
  for (std::size_t i = 0; i < x.size() && i < v.size(); ++i) x[i] += v[i] * dt;
  return at;
}

namespace {

void writeBytes(const fs::path& file, const std::string& bytes, wire::CheckpointWritten& written) {
  if (bytes.empty()) return;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw Error(ErrorKind::resource, "could not write " + file.string());
  written.add_files(file.string());
}

std::optional<std::string> readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in.is_open()) return std::nullopt;
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The laws' history and where the gas was sampled ahead, beside the solver's part of a
// checkpoint (nothing when there is neither).
void savePeerTerms(ParticlePeer* peer, const fs::path& folder, wire::CheckpointWritten& written) {
  if (peer == nullptr) return;
  writeBytes(folder / kPeerTermsFile, peer->terms().saveState(), written);
  writeBytes(folder / kPeerAheadFile, peer->aheadBytes(), written);
  if (peer->keepsLedger()) writeBytes(folder / kPeerLedgerFile, peer->ledgerBytes(), written);
}

void restorePeerTerms(ParticlePeer* peer, const fs::path& folder) {
  if (peer == nullptr) return;
  if (auto bytes = readBytes(folder / kPeerTermsFile)) peer->terms().restoreState(*bytes);
  if (auto bytes = readBytes(folder / kPeerAheadFile)) peer->restoreAhead(*bytes);
  if (!peer->keepsLedger()) return;
  if (auto bytes = readBytes(folder / kPeerLedgerFile)) {
    peer->restoreLedger(*bytes);
  } else {
    throw InputError("the checkpoint " + folder.string() + " holds no " + kPeerLedgerFile +
                     ": it was written by an older cosim, whose orchestrator kept the coating "
                     "ledger on the peer path (coupling.data_path: peer); resume it with the "
                     "cosim that wrote it, or start a new run");
  }
}

// An Advance: the solver's step, or of zero length its state, and what the data path adds
// around it (the peer link's interval, the particles' ledger); `adv` is the reply.
void advanceSolver(Solver& solver, const wire::Advance& cmd, std::uint64_t step, double time,
                   FluidPeer* fluid_peer, ParticlePeer* particle_peer, const PeerWatch& watch,
                   wire::Advanced& adv) {
  ParticleData state;
  const bool interval = cmd.dt() > 0;
  if (particle_peer && !cmd.peer_connect().empty()) particle_peer->connect(cmd.peer_connect());
  if (fluid_peer && interval) {
    fluid_peer->interval(solver, cmd, step, time, adv, watch);
  } else if (particle_peer && interval) {
    particle_peer->interval(solver, cmd, step, time, adv, state, watch);
  } else if (particle_peer && cmd.pay_owed()) {  // the run's last uptake
    // in the Advance too, as on the central path (an adapter with several ranks
    // broadcasts the Advance as it is)
    const ParticleData owed = particle_peer->zeroLengthTerms(cmd);
    wire::Advance with_owed = cmd;
    cosim::link::toWire(owed, *with_owed.mutable_terms());
    solver.advance(with_owed, owed, adv, state);
  } else {
    solver.advance(cmd, cosim::link::fromWire(cmd.terms()), adv, state);
  }
  if (particle_peer && !interval) particle_peer->afterZeroLength(cmd, step, adv);
  if (particle_peer && cmd.state_changes_only()) {
    particle_peer->checkState(state);  // the checks the orchestrator cannot make
    adv.mutable_particles()->set_particle_count(state.size());
  } else if (particle_peer && cmd.state_ids_only()) {
    particle_peer->checkState(state);
    adv.mutable_state()->mutable_ids()->Assign(state.ids.begin(), state.ids.end());
  } else if (particle_peer) {  // as recorded: the coating owed on the parcels
    cosim::link::toWire(particle_peer->held(state), *adv.mutable_state());
  } else {
    cosim::link::toWire(state, *adv.mutable_state());
  }
  if (cmd.has_sample_ahead() && cmd.dt() > 0) {
    // Scheme `overlapped`: the next interval's Sample, where the particles will be
    sampleInto(solver, predictedAt(cosim::link::fromWire(cmd.sample_ahead()), cmd.dt()),
               *adv.mutable_ahead());
  }
  // Where the next interval samples the gas, as the orchestrator would from the same reply
  if (particle_peer) particle_peer->setState(std::move(state));
}

}  // namespace

int runParticipant(Solver& solver, const ParticipantOptions& options, PeerTerms* peer_terms) {
  Session session(options, solver.capabilities());
  session.exitProcessWhenOrphaned();
  try {
    const wire::Welcome welcome = session.handshake();
    solver.configure(welcome);
    // coupling.data_path: peer: the per-parcel data goes to and from the other participant
    std::unique_ptr<FluidPeer> fluid_peer;
    std::unique_ptr<ParticlePeer> particle_peer;
    if (welcome.has_peer()) {
      const PeerIdentity who{session.runId(), options.token, options.name};
      if (solver.capabilities().role == wire::FLUID) {
        fluid_peer = std::make_unique<FluidPeer>(welcome.peer(), who, options.command_timeout_ms,
                                                 options.endpoint);
        if (welcome.peer().bind() == "tcp") {  // say where the particles find it
          wire::Envelope ready;
          ready.mutable_peer_ready()->set_endpoint(fluid_peer->endpoint());
          session.reply(ready);
        }
      } else if (peer_terms == nullptr) {
        throw InputError("adapter '" + solver.capabilities().adapter +
                         "' cannot evaluate the coupling laws over its own parcels, which "
                         "coupling.data_path: peer needs; use coupling.data_path: central");
      } else {
        particle_peer = std::make_unique<ParticlePeer>(welcome.peer(), welcome, *peer_terms, who,
                                                       options.command_timeout_ms);
      }
    }
    const PeerWatch watch = [&session] { session.checkOrchestrator(); };
    if (!welcome.restart_from().empty()) {
      solver.restore(welcome.restart_from());
      restorePeerTerms(particle_peer.get(), welcome.restart_from());
    }
    while (true) {
      wire::Envelope cmd = session.nextCommand();
      wire::Envelope out;
      const auto t0 = std::chrono::steady_clock::now();
      switch (cmd.body_case()) {
        case wire::Envelope::kSample: {
          sampleInto(solver, cosim::link::fromWire(cmd.sample().particles()),
                     *out.mutable_samples());
          break;
        }
        case wire::Envelope::kAdvance: {
          auto* adv = out.mutable_advanced();
          advanceSolver(solver, cmd.advance(), session.step(), session.time(), fluid_peer.get(),
                        particle_peer.get(), watch, *adv);
          adv->set_wall_seconds(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
          break;
        }
        case wire::Envelope::kCheckpoint: {
          auto* w = out.mutable_checkpoint_written();
          if (options.workdir.empty()) {
            for (const auto& f : solver.checkpoint(cmd.checkpoint().path())) w->add_files(f);
            savePeerTerms(particle_peer.get(), cmd.checkpoint().path(), *w);
          } else {
            // A folder of its own: written there, then sent back to the run's checkpoint
            const fs::path here = fs::absolute(options.workdir) / "checkpoint";
            fs::remove_all(here);
            fs::create_directories(here);
            for (const auto& f : solver.checkpoint(here.string())) w->add_files(f);
            savePeerTerms(particle_peer.get(), here, *w);
            packFolder(here, *w->mutable_contents());
          }
          break;
        }
        case wire::Envelope::kShutdown: {
          solver.finish();
          out.mutable_goodbye()->set_message("done");
          session.reply(out);
          return 0;
        }
        default:
          throw ProtocolError(std::string("unexpected message from the orchestrator: ") +
                              bodyName(cmd));
      }
      session.reply(out);
    }
  } catch (const PeerError& e) {
    // The orchestrator is gone or refused us: nobody to tell
    std::cerr << "[" << options.name << "] " << e.what() << std::endl;
    return cosim::exit_code::peer;
  } catch (const std::exception& e) {
    std::cerr << "[" << options.name << "] error: " << e.what() << std::endl;
    session.sendError(e.what());
    // Give ZeroMQ a moment to flush the error before the process ends.
    std::this_thread::sleep_for(Millis(200));
    return cosim::exitCodeOf(cosim::kindOf(e, cosim::ErrorKind::solver));
  }
}

}  // namespace cosim::link
