#include "participants.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <set>
#include <thread>

#include "case_files.h"
#include "cosim/analysis/files.h"
#include "cosim/link/curve_keys.h"
#include "cosim/link/errors.h"
#include "cosim/link/file_transfer.h"
#include "cosim/link/models_wire.h"
#include "cosim/link/session.h"
#include "cosim/link/shared_arrays.h"
#include "cosim/util/cpu_binding.h"
#include "launchers.h"
#include "link_security.h"
#include "processes.h"
#include "run_token.h"
#include "socket_folder.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

using Clock = std::chrono::steady_clock;

struct Participants::Peer {
  ParticipantSpec spec;
  std::optional<ChildProcess> process;
  fs::path log;
  fs::path workdir;
  Clock::time_point last_seen = Clock::now();
  bool connected = false;
  std::string route;  // ZeroMQ routing id of the socket its Hello came from; empty before
  std::vector<std::string> send, receive;
  link::CurveKeyPair keys;  // issued for this run when the link is CurveZMQ
  // Step and time of the last message sent to it; its replies must be for that step. A peer
  // that idled (cosim bench runs one solver alone) gets its Shutdown at its own step.
  std::uint64_t step = 0;
  double time = 0.0;
};

namespace {

// A participant's process that ended on its own: how, and when ("at step 7", "before
// connecting"); of the kind its exit code says (cosim/util/errors.h).
RunFailure processEnded(const std::string& name, const std::string& adapter,
                        const util::ChildProcess& p, const std::string& when) {
  return RunFailure(
      name, "the " + name + " process (" + adapter + ") " + p.exitDescription() + " " + when,
      kindOfExitCode(p.exitCode()));
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "(none)" : s;
}

const char* roleName(wire::Role r) { return r == wire::FLUID ? "fluid" : "particles"; }

// A name a peer claims, as it may appear in cosim.log: printable, at most 40 characters.
std::string shown(const std::string& claimed) {
  std::string out;
  for (char c : claimed.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return out;
}

// At most this many lines in cosim.log about dropped messages, whatever a stranger sends.
constexpr std::size_t kMaxIgnoredLines = 20;

// Open MPI's shared-memory transport (btl vader) keeps a backing file a rank in /dev/shm, and
// ranks that are killed leave theirs behind, run after run.
constexpr const char* kVaderFolderVariable = "OMPI_MCA_btl_vader_backing_directory";

// The command line that starts a participant cosim launches itself.
std::vector<std::string> commandLine(const std::string& name, const ParticipantSpec& spec,
                                     const std::string& endpoint, const std::string& run_id,
                                     long command_timeout_s) {
  auto exe = findExecutable(spec.command);
  if (!exe) {
    throw RunFailure(name,
                     "cannot find the executable '" + spec.command + "' of adapter '" +
                         spec.adapter + "' (looked next to cosim and in PATH; was it built?)",
                     ErrorKind::resource);
  }
  std::vector<std::string> argv = launcherPrefix(name, spec);
  argv.push_back(exe->string());
  for (const auto& a :
       {std::string("--endpoint"), endpoint, std::string("--name"), name, std::string("--run-id"),
        run_id, std::string("--command-timeout"), std::to_string(command_timeout_s)}) {
    argv.push_back(a);
  }
  if (!spec.workdir.empty()) {
    argv.push_back("--workdir");
    argv.push_back((fs::path(spec.workdir) / run_id / name).string());
  }
  for (const auto& a : spec.args) argv.push_back(a);
  return argv;
}

// How long a participant waits for the orchestrator's next command before it gives up: while
// it waits, the orchestrator may wait for the slowest other participant (its timeout, e.g. a DEM
// settling thousands of parcels before its first step) and then for itself. A gone orchestrator
// is noticed within seconds anyway (the connection watch, docs/when-things-go-wrong.md).
long commandTimeout(const std::map<std::string, ParticipantSpec>& participants) {
  double longest = 0.0;
  for (const auto& [name, spec] : participants) longest = std::max(longest, spec.timeout);
  return static_cast<long>(std::ceil(2.0 * longest)) + 60;
}

}  // namespace

std::optional<fs::path> Participants::mpiShmFolder(const ParticipantSpec& spec) {
  // Only for ranks mpirun starts on this host (a host file's other nodes have no such folder;
  // under Slurm the job's own cleanup applies), and not against the user's own choice
  const bool here = spec.launch != "slurm" && spec.launch != "external" && spec.hostfile.empty() &&
                    (spec.mpi > 1 || spec.launch == "mpirun");
  if (!here || std::getenv(kVaderFolderVariable) != nullptr) return std::nullopt;
  if (mpi_shm_folder_.empty()) {
    std::error_code ec;
    if (!fs::is_directory("/dev/shm", ec)) return std::nullopt;
    const fs::path folder =
        fs::path("/dev/shm") / ("cosim-" + std::to_string(getuid()) + "-" + run_id_ + "-mpi");
    if (!fs::create_directory(folder, ec) && ec) return std::nullopt;  // Open MPI's default then
    fs::permissions(folder, fs::perms::owner_all, fs::perm_options::replace, ec);
    mpi_shm_folder_ = folder;
  }
  return mpi_shm_folder_;
}

Participants::Participants(const Scenario& sc, const Plan& plan, std::string run_id, RunLog& log,
                           const util::StopRequest& stop)
    : sc_(sc),
      plan_(plan),
      run_id_(std::move(run_id)),
      log_(log),
      stop_(stop),
      token_(newRunToken()) {}

Participants::~Participants() { shutdown(false); }

std::string Participants::connectEndpoint() const {
  return sc_.transport.connect.empty() ? hub_->endpoint() : sc_.transport.connect;
}

std::map<std::string, std::vector<int>> Participants::cpuLayout() {
  // from the CPUs cosim was given, not those an earlier run of this process bound it to (the
  // stages of a bench, the variants of a study): its children inherit its mask
  const std::vector<int> allowed = util::initialCpus();
  if (sc_.coupling.cpus != "auto") {
    if (!allowed.empty() && util::allowedCpus() != allowed) util::bindThisProcess(allowed);
    return {};
  }
  std::string why;
  if (allowed.size() < 2) why = "this process may use " + std::to_string(allowed.size()) + " CPU";
  for (const auto& [name, peer] : peers_) {
    if (!why.empty()) break;
    if (peer->spec.launch != "local" || peer->spec.mpi > 1)
      why = name + " is not a single process started here (" + describeLaunch(peer->spec) +
            "): bind it with its launcher";
  }
  if (!why.empty()) {
    log_.show("coupling.cpus auto: not applied, " + why);
    return {};
  }
  const std::vector<int> first{allowed.front()};
  const std::vector<int> rest(allowed.begin() + 1, allowed.end());
  std::map<std::string, std::vector<int>> layout;
  for (const auto& [name, peer] : peers_) {
    layout[name] = peer->spec.role == wire::FLUID ? rest : first;
  }
  try {
    util::bindThisProcess(first);
  } catch (const std::exception& e) {
    log_.warn(std::string("coupling.cpus auto: ") + e.what() + "; the processes run unbound");
    return {};
  }
  std::string text = "coupling.cpus auto: orchestrator on CPU " + util::cpuListText(first);
  for (const auto& [name, cpus] : layout) text += ", " + name + " on " + util::cpuListText(cpus);
  log_.show(text);
  return layout;
}

void Participants::start(const fs::path& run_folder) {
  std::string endpoint = sc_.transport.bind;
  std::optional<link::CurveKeyPair> server_keys;
  try {
    if (endpoint.empty())
      endpoint = "ipc://" + (privateSocketFolder() / (run_id_ + ".ipc")).string();
    else
      endpoint = bindAddress(endpoint);
    server_keys = orchestratorKeys(sc_.transport, endpoint);
  } catch (const RunFailure&) {
    throw;
  } catch (const std::exception& e) {
    throw RunFailure("", e.what(), kindOf(e, ErrorKind::input));  // transport.bind, the keys
  }

  // Every participant's keys for this run, before the hub exists: it accepts these and no other.
  link::HubSecurity security;
  for (const auto& [name, spec] : sc_.participants) {
    const bool used = name == "particles" || (name == "fluid" && plan_.fluid);
    if (!used) continue;
    auto peer = std::make_unique<Peer>();
    peer->spec = spec;
    peer->workdir = run_folder / name;
    // Only the processes cosim starts write there; an external one's output stays where it
    // was started.
    if (spec.launch != "external") peer->log = run_folder / (name + ".log");
    if (server_keys) {
      peer->keys = link::newCurveKeyPair();
      security.clients.insert(peer->keys.public_key);
    }
    peers_[name] = std::move(peer);
  }
  if (server_keys) {
    security.server = *server_keys;
    orchestrator_public_ = server_keys->public_key;
  } else if (isTcp(endpoint)) {
    log_.warn("transport.insecure: the link at " + endpoint +
              " is neither encrypted nor authenticated: anyone who reaches the port can read "
              "the particle data (and, with the run token, which is sent in the clear, join the "
              "run); use it only on a network you trust");
  }
  try {
    hub_ = std::make_unique<link::Hub>(endpoint, security);
  } catch (const std::exception& e) {
    throw RunFailure(
        "",
        "cannot bind the orchestrator's socket " + endpoint + ": " + e.what() + " (transport.bind)",
        ErrorKind::resource);
  }
  const std::string connect = connectEndpoint();
  const std::map<std::string, std::vector<int>> cpus = cpuLayout();

  for (auto& [name, peer] : peers_) {
    const ParticipantSpec& spec = peer->spec;
    const bool resuming = !restart_from_.empty();
    if (resuming && !fs::is_directory(peer->workdir))
      throw RunFailure(name, "cannot resume: its folder " + peer->workdir.string() + " is gone",
                       ErrorKind::input);
    fs::create_directories(peer->workdir);
    if (!resuming && !spec.files.empty()) copyCaseFiles(spec.files, peer->workdir, sc_.parameters);
    const link::CurveClientKeys keys{orchestrator_public_, peer->keys};
    if (spec.launch != "external") {
      const auto argv = commandLine(name, spec, connect, run_id_, commandTimeout(sc_.participants));
      // The secrets through the environment, which only the user (and root) can read, never on
      // the command line, which everyone can (ps).
      std::map<std::string, std::string> env{{link::kRunTokenVariable, token_}};
      if (!keys.empty()) env[link::kCurveKeysVariable] = link::curveKeysVariableText(keys);
      if (spec.mpi > 1 && geteuid() == 0) {
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1";
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1";
      }
      if (const auto folder = mpiShmFolder(spec)) env[kVaderFolderVariable] = folder->string();
      try {
        const auto bound = cpus.find(name);
        peer->process.emplace(argv, peer->workdir, peer->log, env,
                              bound == cpus.end() ? std::vector<int>{} : bound->second);
      } catch (const std::exception& e) {
        throw RunFailure(name, e.what(), ErrorKind::resource);  // fork, exec, the log file
      }
      log_.file("started " + name + " (" + describeLaunch(spec) + "): " + join(argv));
    } else {
      try {
        if (token_file_.empty()) token_file_ = writeRunTokenFile(run_folder, token_);
        if (!keys.empty()) {
          const fs::path file = participantKeyFile(run_folder, name);
          link::writeParticipantKeyFile(file, keys, run_id_, name);
          key_files_[name] = file;
        }
      } catch (const std::exception& e) {
        throw RunFailure(name, e.what(), kindOf(e, ErrorKind::resource));
      }
      log_.show("waiting for " + name + " (launch: external): start it with " +
                externalStart(name));
      log_.show("  (on a node that does not see " + run_folder.string() +
                ": add --workdir DIR, a folder of its own there; its files then travel over the "
                "link)");
      if (!keys.empty()) {
        log_.show("  " + name + "'s CurveZMQ keys for this run are in " +
                  key_files_[name].string() +
                  " (mode 0600): on a node that does not share the run folder, copy it and " +
                  token_file_.filename().string() +
                  " there (scp -p) and give their paths to --key-file and --token-file");
      }
    }
  }
  log_.console("run folder " + run_folder.string());
  for (const auto& n : plan_.notes) log_.console("note: " + n);
  std::string who;
  for (const auto& [n, p] : peers_) {
    who += (who.empty() ? "" : ", ") + n + " (" + p->spec.adapter +
           (p->spec.mpi > 1 ? ", " + std::to_string(p->spec.mpi) + " MPI ranks" : "") +
           (p->spec.launch == "slurm" || p->spec.launch == "mpirun" ? ", " + p->spec.launch : "") +
           ")";
  }
  log_.show("orchestrator at " + connect +
            (server_keys       ? " (CurveZMQ)"
             : isTcp(endpoint) ? " (NOT encrypted: transport.insecure)"
                               : "") +
            "; participants: " + who);
}

std::string Participants::externalStart(const std::string& name) const {
  std::string s = "--endpoint " + connectEndpoint() + " --name " + name + " --run-id " + run_id_ +
                  " --command-timeout " + std::to_string(commandTimeout(sc_.participants)) +
                  " --token-file " + token_file_.string();
  if (auto it = key_files_.find(name); it != key_files_.end())
    s += " --key-file " + it->second.string();
  return s;
}

void Participants::logRefusals() {
  if (!hub_) return;
  for (const auto& line : hub_->takeRefusals()) {
    log_.file(line);
    if (refusal_seen_.empty()) refusal_seen_ = line;
  }
}

void Participants::setClock(std::uint64_t step, double time) {
  step_ = step;
  time_ = time;
}

void Participants::send(const std::string& name, wire::Envelope& env, bool own_clock) {
  auto* h = env.mutable_header();
  h->set_protocol_version(wire::PROTOCOL_VERSION);
  h->set_run_id(run_id_);
  h->set_participant(name);
  if (auto it = peers_.find(name); it != peers_.end()) {
    if (!own_clock) {
      it->second->step = step_;
      it->second->time = time_;
    }
    h->set_step(it->second->step);
    h->set_time(it->second->time);
  } else {
    h->set_step(step_);
    h->set_time(time_);
  }
  try {
    const auto it = peers_.find(name);
    if (it == peers_.end() || it->second->route.empty())
      throw link::PeerError("it has not connected");
    hub_->send(it->second->route, env);
  } catch (const std::exception& e) {
    // Usually the peer's process just died: say how, rather than only "unreachable".
    auto it = peers_.find(name);
    if (it != peers_.end() && it->second->process) {
      auto& proc = *it->second->process;
      for (int i = 0; i < 40 && proc.running(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      if (!proc.running()) {
        throw processEnded(name, it->second->spec.adapter, proc,
                           "at step " + std::to_string(step_));
      }
    }
    throw RunFailure(name, e.what(), ErrorKind::peer);
  }
}

Replies Participants::exchange(std::map<std::string, wire::Envelope> messages,
                               wire::Envelope::BodyCase reply) {
  if (reply == wire::Envelope::kAdvanced) {
    std::map<std::string, MessageBuilder> build;
    for (auto& [name, env] : messages)
      build[name] = [&message = env] { return std::move(message); };
    return advance(build);
  }
  std::map<std::string, wire::Envelope::BodyCase> expected;
  double timeout = 0.0;
  for (auto& [name, env] : messages) {
    send(name, env);
    expected[name] = reply;
    timeout = std::max(timeout, peers_.at(name)->spec.timeout);
  }
  return await(expected, timeout);
}

Replies Participants::advance(const std::map<std::string, MessageBuilder>& build) {
  const auto t0 = Clock::now();
  std::vector<std::string> order;
  order.reserve(build.size());
  for (const auto& [name, b] : build) order.push_back(name);
  auto waited = [this](const std::string& n) {
    const auto it = last_reply_.find(n);
    return it == last_reply_.end() ? 0.0 : it->second;
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](const auto& a, const auto& b) { return waited(a) > waited(b); });
  std::map<std::string, wire::Envelope::BodyCase> expected;
  double timeout = 0.0;
  arrived_.clear();
  // Every message is built before the first leaves. Building the next one while the first
  // participant computes showed no gain on 2 cores, where it takes a core from a solver
  // (docs/performance.md, "The wire and the wake-ups"); the builders leave that choice here.
  std::map<std::string, wire::Envelope> messages;
  for (const auto& name : order) messages[name] = build.at(name)();
  for (const auto& name : order) {
    send(name, messages.at(name));
    expected[name] = wire::Envelope::kAdvanced;
    timeout = std::max(timeout, peers_.at(name)->spec.timeout);
  }
  const auto sent = Clock::now();
  Replies replies = await(expected, timeout);
  advance_wire_["send"] += std::chrono::duration<double>(sent - t0).count();
  for (const auto& [name, at] : arrived_) {
    last_reply_[name] = std::chrono::duration<double>(at - t0).count();
    advance_wire_[name + "_reply"] += last_reply_[name];
  }
  return replies;
}

wire::Envelope Participants::request(const std::string& name, wire::Envelope message,
                                     wire::Envelope::BodyCase reply) {
  Replies replies = exchange({{name, std::move(message)}}, reply);
  return std::move(replies.at(name));
}

void Participants::checkpoint(const fs::path& folder) {
  std::map<std::string, wire::Envelope> messages;
  for (const auto& [name, p] : peers_) {
    messages[name].mutable_checkpoint()->set_path(fs::absolute(folder / name).string());
  }
  const Replies written = exchange(std::move(messages), wire::Envelope::kCheckpointWritten);
  // A participant with a folder of its own sent its files; the others wrote them here
  for (const auto& [name, reply] : written) {
    try {
      link::unpackFiles(reply.checkpoint_written().contents(), folder / name);
    } catch (const std::exception& e) {
      throw RunFailure(name, std::string("its checkpoint: ") + e.what(),
                       kindOf(e, ErrorKind::resource));
    }
  }
}

std::vector<std::string> Participants::names() const {
  std::vector<std::string> n;
  for (const auto& [name, p] : peers_) n.push_back(name);
  return n;
}

void Participants::addComputeSeconds(const std::string& name, double seconds) {
  compute_[name] += seconds;
}

fs::path Participants::logOf(const std::string& name) const {
  auto it = peers_.find(name);
  return it == peers_.end() ? fs::path() : it->second->log;
}

Replies Participants::await(const std::map<std::string, wire::Envelope::BodyCase>& expected,
                            double timeout) {
  Replies got;
  auto start = Clock::now();
  // Wake-ups come every 100 ms at most; a longer gap, or a longer time since the last wait
  // ended, is time the orchestrator did not listen: busy between two waits (a large record), or
  // not running at all (the job suspended: SIGSTOP, Slurm's scontrol suspend, Ctrl-Z; a virtual
  // machine paused). Nobody can have been heard then: it counts neither against the heartbeats
  // nor the wait's timeout.
  const auto unwatched_after = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(std::min(5.0, sc_.transport.heartbeat_timeout / 2)));
  auto watched = last_listened_.value_or(start);  // the last time the orchestrator listened
  const auto notListening = [&](Clock::time_point now) {
    if (now - watched <= unwatched_after) return;
    const auto gap = now - watched;
    start += std::min(gap, now - start);  // only what fell in this wait
    for (auto& [name, p] : peers_) p->last_seen += gap;
    log_.file("the orchestrator did not listen for " +
              analysis::formatShortest(std::chrono::duration<double>(gap).count()) +
              " s (busy, or suspended): not counted as the participants' silence");
  };
  notListening(start);
  watched = start;
  while (got.size() < expected.size()) {
    if (stop_.count() >= 2)
      throw RunFailure("", "interrupted (signal " + std::to_string(stop_.signal()) + ")");
    // Before the first answer (a participant's own start-up: LIGGGHTS pouring and settling the
    // bed, OpenFOAM reading its case) there is no step to finish: stop now
    if (stop_.requested() && !answered_once_)
      throw RunFailure("", "interrupted during start-up (signal " + std::to_string(stop_.signal()) +
                               "), before the first step: no step was done in this run");
    if (stop_.requested() && !stop_noted_) {
      stop_noted_ = true;
      log_.show("signal " + std::to_string(stop_.signal()) +
                ": stopping after this step with a checkpoint (send it again to stop at once)");
    }
    if (auto in = hub_->receive(link::Millis(100))) {
      if (const auto who = admit(*in)) take(*who, *in->envelope, expected, got);
    }
    logRefusals();
    notListening(Clock::now());
    watched = Clock::now();
    // On every wake-up, message or not: no stream of messages may hide a dead or silent peer.
    checkAlive(expected, got, start, timeout);
    noteLongFirstWait(expected, got, start, timeout);
  }
  answered_once_ = true;
  last_listened_ = Clock::now();
  return got;
}

// The first answers of a run come after each participant's own start-up (a LIGGGHTS script's
// settling, a mesh being made), which may take minutes with nothing on the screen: say who is
// awaited and where its log is, after 15 s and then every minute.
void Participants::noteLongFirstWait(
    const std::map<std::string, wire::Envelope::BodyCase>& expected, const Replies& got,
    Clock::time_point start, double timeout) {
  if (answered_once_) return;
  const double waited = std::chrono::duration<double>(Clock::now() - start).count();
  if (waited < next_wait_note_) return;
  next_wait_note_ = waited < 60 ? 60 : next_wait_note_ + 60;
  std::string who, keys;
  for (const auto& [name, kind] : expected) {
    if (got.count(name)) continue;
    const auto log = logOf(name);
    who +=
        (who.empty() ? "" : ", ") + name + (log.empty() ? "" : " (its log: " + log.string() + ")");
    keys += (keys.empty() ? "" : ", ") + ("participants." + name + ".timeout");
  }
  if (who.empty()) return;
  log_.show("waiting " + std::to_string(static_cast<int>(waited)) + " s for the first answer of " +
            who +
            ": its own start-up before the first step (a script's settling, a mesh) can "
            "take minutes; the run gives up after " +
            std::to_string(static_cast<int>(timeout)) + " s (" + keys + ")");
}

void Participants::take(const std::string& who, wire::Envelope& env,
                        const std::map<std::string, wire::Envelope::BodyCase>& expected,
                        Replies& got) {
  if (env.has_heartbeat()) return;
  if (env.header().protocol_version() != wire::PROTOCOL_VERSION) {
    throw RunFailure(who,
                     "speaks protocol version " + std::to_string(env.header().protocol_version()) +
                         ", the orchestrator " + std::to_string(wire::PROTOCOL_VERSION),
                     ErrorKind::peer);
  }
  if (env.has_error()) {
    throw RunFailure(who,
                     "reported an error: " + env.error().message() +
                         (env.error().where().empty() ? "" : " (at " + env.error().where() + ")"));
  }
  if (env.has_hello()) return;  // a copy sent before its Welcome arrived
  auto eit = expected.find(who);
  if (eit == expected.end() || got.count(who)) {
    throw RunFailure(who, "sent an unexpected message at step " + std::to_string(step_),
                     ErrorKind::peer);
  }
  if (env.body_case() != eit->second) {
    throw RunFailure(who,
                     "sent the wrong message type (body " + std::to_string(env.body_case()) +
                         ", expected " + std::to_string(eit->second) + ") at step " +
                         std::to_string(step_),
                     ErrorKind::peer);
  }
  if (env.header().run_id() != run_id_) {
    throw RunFailure(
        who, "answered for run '" + env.header().run_id() + "', this run is '" + run_id_ + "'",
        ErrorKind::peer);
  }
  const std::uint64_t at = peers_.at(who)->step;
  if (env.header().step() != at) {
    throw RunFailure(who,
                     "answered for step " + std::to_string(env.header().step()) +
                         " while the run is at step " + std::to_string(at) + " (out-of-order step)",
                     ErrorKind::peer);
  }
  got[who] = std::move(env);
  arrived_[who] = Clock::now();
}

std::optional<std::string> Participants::admit(const link::Hub::Incoming& in) {
  const std::string claimed = in.envelope ? in.envelope->header().participant() : "";
  auto drop = [&](const std::string& why) -> std::optional<std::string> {
    const std::string who = in.envelope ? "'" + shown(claimed) + "'" : "an unknown sender";
    if (ignored_.size() < kMaxIgnoredLines && ignored_.emplace(shown(claimed), why).second) {
      log_.file("ignored messages from " + who + ": " + why +
                (ignored_.size() == kMaxIgnoredLines ? " (further ones are not logged)" : ""));
    }
    return std::nullopt;
  };
  if (!in.envelope) return drop(in.parse_error);
  const auto& env = *in.envelope;
  const auto pit = peers_.find(claimed);
  if (pit == peers_.end()) return drop("not a participant of this run");
  Peer& p = *pit->second;
  if (!sameToken(env.header().token(), token_)) {
    if (env.has_hello()) {
      // Tell it, so that a participant of another run (or of an older cosim) stops waiting.
      wire::Envelope r;
      r.mutable_header()->set_protocol_version(wire::PROTOCOL_VERSION);
      r.mutable_header()->set_participant(claimed);
      r.mutable_refused()->set_reason(
          "this Hello does not carry the run's token: a participant proves it belongs to the run "
          "with the token cosim hands to the processes it starts (environment variable " +
          std::string(link::kRunTokenVariable) + ") and writes to " + kRunTokenFile +
          " in the run folder for those of launch: external (--token-file)");
      try {
        hub_->send(in.peer, r);
      } catch (const std::exception&) {
      }
    }
    return drop(env.header().token().empty()
                    ? "a message without a run token (not from this run, or from an adapter "
                      "older than protocol version 3)"
                    : "a message with a wrong run token (not from this run)");
  }
  // The participant's own: its heartbeats come from a socket of their own; everything else
  // from the socket its (first) Hello came from.
  if (!env.has_heartbeat() && !p.route.empty() && in.peer != p.route)
    return drop("a second connection with this run's token (is the participant started twice?)");
  p.last_seen = Clock::now();
  return claimed;
}

std::string Participants::ignoredNote(const std::string& name) const {
  if (auto it = ignored_.find(name); it != ignored_.end())
    return "; messages under its name were ignored: " + it->second;
  return "";
}

void Participants::checkAlive(const std::map<std::string, wire::Envelope::BodyCase>& expected,
                              const Replies& got, Clock::time_point start, double timeout) {
  const auto now = Clock::now();
  {
    for (const auto& [name, kind] : expected) {
      if (got.count(name)) continue;
      Peer& p = *peers_.at(name);
      if (p.process && !p.process->running()) {
        throw processEnded(name, p.spec.adapter, *p.process, "at step " + std::to_string(step_));
      }
      const double silent = std::chrono::duration<double>(now - p.last_seen).count();
      if (p.connected && silent > sc_.transport.heartbeat_timeout) {
        throw RunFailure(name,
                         "silent for " + std::to_string(static_cast<int>(silent)) + " s at step " +
                             std::to_string(step_) +
                             ": not even a heartbeat (transport.heartbeat_timeout " +
                             analysis::formatShortest(sc_.transport.heartbeat_timeout) +
                             " s); its process hung, its host went down, or the network "
                             "between it and the orchestrator is cut",
                         ErrorKind::peer);
      }
      if (std::chrono::duration<double>(now - start).count() > timeout) {
        throw RunFailure(name,
                         "did not answer within " + std::to_string(static_cast<int>(timeout)) +
                             " s at step " + std::to_string(step_) + " (participants." + name +
                             ".timeout; raise it if a step is legitimately slow)",
                         ErrorKind::peer);
      }
    }
  }
}

// coupling.data_path: peer: on one machine the fluid binds the particles' link beside the run's
// socket; across nodes (the orchestrator's link is tcp://) it binds a port of its own and says
// where (PeerReady), with a CurveZMQ key pair for each side when the orchestrator's link has them.
void Participants::preparePeerLink() {
  if (!isTcp(hub_->endpoint())) {
    peer_.bind = "ipc://" + (privateSocketFolder() / (run_id_ + "-peer.ipc")).string();
    peer_.shared_memory = link::sharedArraysPrefix(run_id_);
    return;
  }
  peer_.bind = "tcp";
  if (!orchestrator_public_.empty()) {
    peer_.fluid = link::newCurveKeyPair();
    peer_.particles = link::newCurveKeyPair();
  }
}

// Waiting for the fluid's PeerReady: it configures its solver first (participants.fluid.timeout).
void Participants::checkPeerReady(Clock::time_point start) {
  Peer& fluid = *peers_.at("fluid");
  if (fluid.process && !fluid.process->running())
    throw processEnded("fluid", fluid.spec.adapter, *fluid.process,
                       "before it said where its peer link listens");
  if (std::chrono::duration<double>(Clock::now() - start).count() > fluid.spec.timeout)
    throw RunFailure("fluid",
                     "did not say where its peer link listens (PeerReady) within " +
                         std::to_string(static_cast<int>(fluid.spec.timeout)) +
                         " s of the start (participants.fluid.timeout; coupling.data_path: peer "
                         "needs an adapter built with this cosim)",
                     ErrorKind::peer);
}

void Participants::handshake() {
  std::set<std::string> waiting;
  for (const auto& [n, p] : peers_) waiting.insert(n);
  const auto start = Clock::now();
  // Over tcp the fluid says where its peer socket listens once it has configured
  bool peer_ready_due = plan_.peer && isTcp(hub_->endpoint()) && peer_address_.empty();
  while (!waiting.empty() || peer_ready_due) {
    if (stop_.requested()) throw RunFailure("", "interrupted during start-up");
    if (auto in = hub_->receive(link::Millis(100))) {
      if (const auto who = admit(*in)) {
        const auto& env = *in->envelope;
        if (env.has_error()) {
          // e.g. a participant already welcomed whose configuration failed
          const auto& err = env.error();
          throw RunFailure(*who, "reported an error: " + err.message() +
                                     (err.where().empty() ? "" : " (at " + err.where() + ")"));
        }
        if (env.has_peer_ready() && *who == "fluid") {
          peer_address_ = env.peer_ready().endpoint();
          peer_ready_due = false;
          log_.file("fluid's peer link at " + peer_address_);
        }
        // Heartbeats and copies of a Hello already answered are passed over.
        if (!env.has_heartbeat() && waiting.count(*who)) {
          welcome(*who, env, in->peer);
          waiting.erase(*who);
        }
      }
    }
    logRefusals();
    // On every wake-up, message or not: no stream of messages may hide a dead participant.
    for (const auto& n : waiting) {
      Peer& p = *peers_.at(n);
      if (p.process && !p.process->running()) {
        throw processEnded(n, p.spec.adapter, *p.process, "before connecting" + ignoredNote(n));
      }
    }
    if (waiting.empty() && peer_ready_due) {
      checkPeerReady(start);
      continue;
    }
    if (std::chrono::duration<double>(Clock::now() - start).count() >
        sc_.transport.handshake_timeout) {
      const std::string who = *waiting.begin();
      throw RunFailure(
          who,
          "did not connect within " +
              std::to_string(static_cast<int>(sc_.transport.handshake_timeout)) +
              " s (transport.handshake_timeout)" + ignoredNote(who) +
              (refusal_seen_.empty() ? std::string()
                                     : "; connections were refused at the security handshake "
                                       "meanwhile ('" +
                                           refusal_seen_ +
                                           "' in cosim.log): a participant started with the key "
                                           "file of another run, or without keys?") +
              (peers_.at(who)->spec.launch == "external" ? "; start it with " + externalStart(who)
                                                         : ""),
          ErrorKind::peer);
    }
  }
}

namespace {
// coupling.data_path: peer: the fluid binds `keys.bind`; the particles connect to it and get the
// laws, the constants and the fields of each peer message.
wire::PeerLink peerLinkFor(const Scenario& sc, const Plan& plan, const std::string& who,
                           const PeerKeys& keys) {
  wire::PeerLink link;
  link.set_fluid_public(keys.fluid.public_key);
  link.set_particles_public(keys.particles.public_key);
  if (who == "fluid") {
    link.set_bind(keys.bind);
    link.set_shared_memory(keys.shared_memory);
    link.set_fluid_secret(keys.fluid.secret_key);
    return link;
  }
  link.set_particles_secret(keys.particles.secret_key);
  if (keys.bind != "tcp") link.set_connect(keys.bind);
  link.set_shared_memory(keys.shared_memory);
  link::toWire(sc.models.choices(), sc.constants, *link.mutable_models());
  for (const auto& f : plan.sample_state) link.add_sample_state(f);
  for (const auto& f : plan.fluid_advance_terms) link.add_exchange(f);
  link.set_coating(plan.coating);
  // the particles keep the coating ledger and, with a zone, the zone passes (coupler.h)
  link.set_zone_passes(plan.coating && sc.models.choices().coating_zone.has_value());
  link.set_max_particle_speed(sc.checks.max_particle_speed);
  link.set_sample_ahead(sc.coupling.scheme == "overlapped");
  return link;
}
}  // namespace

wire::Welcome welcomeFor(const Scenario& sc, const Plan& plan, const ParticipantSpec& spec,
                         const fs::path& workdir, const fs::path& restart_from,
                         const PeerKeys& peer) {
  wire::Welcome wel;
  const bool fluid = spec.name == "fluid";
  for (const auto& f : fluid ? plan.fluid_send : plan.particles_send) wel.add_send(f);
  for (const auto& f : fluid ? plan.fluid_receive : plan.particles_receive) wel.add_receive(f);
  YAML::Emitter em;
  em << spec.options;
  wel.set_config_yaml(em.c_str());
  wel.set_workdir(fs::absolute(workdir).string());
  wel.set_cfd_dt(sc.coupling.dt);
  wel.set_dem_steps(sc.coupling.dem_steps);
  wel.set_end_time(sc.coupling.end_time);
  wel.set_start_time(sc.coupling.start_time);
  for (const auto& [k, v] : sc.parameters) (*wel.mutable_parameters())[k] = v;
  wel.set_species(plan.coating);
  if (!restart_from.empty()) wel.set_restart_from(fs::absolute(restart_from).string());
  if (plan.peer) *wel.mutable_peer() = peerLinkFor(sc, plan, spec.name, peer);
  return wel;
}

// Checks one Hello against what the scene needs and answers with the Welcome.
void Participants::welcome(const std::string& who, const wire::Envelope& env,
                           const std::string& route) {
  Peer& p = *peers_.at(who);
  p.route = route;
  auto refuse = [&](const std::string& reason) {
    wire::Envelope r;
    r.mutable_refused()->set_reason(reason);
    send(who, r);
    throw RunFailure(who, "refused at handshake: " + reason, ErrorKind::peer);
  };
  if (env.header().protocol_version() != wire::PROTOCOL_VERSION) {
    refuse("protocol version " + std::to_string(env.header().protocol_version()) +
           " but the orchestrator speaks version " + std::to_string(wire::PROTOCOL_VERSION) +
           "; rebuild the adapter from the same cosim version");
  }
  if (!env.has_hello()) refuse("the first message must be Hello");
  const auto& h = env.hello();
  if (h.role() != p.spec.role) {
    refuse("adapter '" + h.adapter() + "' says it simulates " + roleName(h.role()) +
           " but is configured as participant '" + who + "'");
  }
  p.send = who == "fluid" ? plan_.fluid_send : plan_.particles_send;
  p.receive = who == "fluid" ? plan_.fluid_receive : plan_.particles_receive;
  const std::set<std::string> provides(h.provides().begin(), h.provides().end());
  const std::set<std::string> accepts(h.accepts().begin(), h.accepts().end());
  for (const auto& f : p.send) {
    if (!provides.count(f)) {
      refuse("this scene needs field '" + f + "' from the " + who + " participant, but adapter '" +
             h.adapter() + "' cannot provide it (it provides: " +
             join({h.provides().begin(), h.provides().end()}) +
             "); choose models that do not need it or another adapter");
    }
  }
  for (const auto& f : p.receive) {
    if (!accepts.count(f)) {
      refuse("this scene sends field '" + f + "' to the " + who + " participant, but adapter '" +
             h.adapter() + "' does not accept it (it accepts: " +
             join({h.accepts().begin(), h.accepts().end()}) + ")");
    }
  }
  if (plan_.peer && peer_.bind.empty()) preparePeerLink();
  wire::Envelope w;
  *w.mutable_welcome() =
      welcomeFor(sc_, plan_, p.spec, p.workdir,
                 restart_from_.empty() ? fs::path() : restart_from_ / who, peer_);
  if (clock_start_) w.mutable_welcome()->set_start_time(*clock_start_);
  if (h.own_folder()) {
    // No shared filesystem: the case files and the restart travel with the Welcome
    try {
      link::packFolder(p.workdir, *w.mutable_welcome()->mutable_case_files());
      if (!restart_from_.empty())
        link::packFolder(restart_from_ / who, *w.mutable_welcome()->mutable_restart_files());
    } catch (const std::exception& e) {
      refuse(e.what());
    }
  }
  send(who, w);
  p.connected = true;
  p.last_seen = Clock::now();
  log_.file(
      who + " connected: adapter " + h.adapter() + ", pid " + std::to_string(h.pid()) + " on " +
      h.host() + "; sends " + join(p.send) + "; receives " + join(p.receive) +
      (h.own_folder() ? "; a folder of its own: case files and checkpoints over the link" : ""));
}

void Participants::shutdown(bool clean) {
  if (hub_ && clean) {
    std::map<std::string, wire::Envelope::BodyCase> bye;
    for (const auto& [n, p] : peers_) {
      if (!p->connected || (p->process && !p->process->running())) continue;
      wire::Envelope e;
      e.mutable_shutdown()->set_reason("end of run");
      send(n, e, true);
      bye[n] = wire::Envelope::kGoodbye;
    }
    try {
      await(bye, 60.0);
    } catch (const std::exception& e) {
      log_.warn(e.what());
    }
  } else if (hub_) {
    for (const auto& [n, p] : peers_) {
      if (!p->connected || (p->process && !p->process->running())) continue;
      wire::Envelope e;
      e.mutable_error()->set_message("run aborted by the orchestrator");
      try {
        send(n, e);
      } catch (...) {
      }
    }
  }
  for (auto& [n, p] : peers_) {
    if (p->process) p->process->stop(clean ? 10.0 : 2.0);
    compute_[n] += 0.0;  // every participant appears in the summary's timings
  }
  peers_.clear();
  logRefusals();
  hub_.reset();  // the hub removes the ipc:// socket file it created
  if (peer_.bind.rfind("ipc://", 0) == 0) {
    // the fluid's peer socket, which it leaves behind when it is killed
    std::error_code ec;
    fs::remove(peer_.bind.substr(std::string("ipc://").size()), ec);
  }
  if (!peer_.shared_memory.empty()) link::removeSharedArrays(peer_.shared_memory);
  if (!mpi_shm_folder_.empty()) {
    // Open MPI's backing files, which ranks that were killed leave behind
    std::error_code ec;
    fs::remove_all(mpi_shm_folder_, ec);
    mpi_shm_folder_.clear();
  }
  if (!token_file_.empty()) {
    std::error_code ec;
    fs::remove(token_file_, ec);
    token_file_.clear();
  }
  for (const auto& [name, file] : key_files_) {
    std::error_code ec;
    fs::remove(file, ec);
  }
  key_files_.clear();
}

}  // namespace cosim::orchestrator
