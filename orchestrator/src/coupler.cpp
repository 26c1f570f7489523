#include "coupler.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "case_files.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/summary.h"
#include "cosim/analysis/time_series.h"
#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "coupling_terms.h"
#include "progress.h"
#include "stability.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

namespace {

// Time at the end of step k: start + k dt, rounded to 12 significant digits so that 2453 steps
// of 1e-4 s are recorded as 0.2453 s and not as 0.24530000000000002 (the product's round-off).
double stepTime(double start, double dt, std::uint64_t k) {
  const double t = start + static_cast<double>(k) * dt;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", t);
  return std::strtod(buf, nullptr);
}

}  // namespace
using Clock = std::chrono::steady_clock;

std::atomic<int> g_stop_signal{0};

struct Coupler::Peer {
  ParticipantSpec spec;
  std::optional<ChildProcess> process;
  fs::path log;
  fs::path workdir;
  Clock::time_point last_seen = Clock::now();
  bool connected = false;
  std::string adapter;
  std::vector<std::string> send, receive;
  double wall = 0.0;  // seconds spent computing, as reported
};

struct Coupler::Recorders {
  std::unique_ptr<analysis::ParticleRecorder> particles;
  std::unique_ptr<analysis::TimeSeriesRecorder> series;
  std::vector<std::string> columns;
};

namespace {

std::string newRunId() {
  std::random_device rd;
  std::ostringstream os;
  os << std::hex << std::setw(8) << std::setfill('0') << rd();
  return os.str();
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "(none)" : s;
}

const char* roleName(wire::Role r) { return r == wire::FLUID ? "fluid" : "particles"; }

}  // namespace

Coupler::Coupler(Scenario scenario, RunOptions options)
    : sc_(std::move(scenario)), opt_(std::move(options)) {
  models_ = makeModels(sc_);
  plan_ = makePlan(sc_, models_);
  run_id_ = newRunId();
}

Coupler::~Coupler() { shutdown(false); }

void Coupler::prepareFolder() {
  fs::path base = opt_.output.empty() ? sc_.output.folder : fs::absolute(opt_.output);
  folder_ = base;
  if (!opt_.overwrite && fs::exists(folder_) && !fs::is_empty(folder_)) {
    // Never overwrite a previous result: take the next free suffix.
    for (int i = 2;; ++i) {
      fs::path cand = base.string() + "-" + std::to_string(i);
      if (!fs::exists(cand)) {
        folder_ = cand;
        break;
      }
    }
  }
  fs::create_directories(folder_);
  {
    std::ofstream os(folder_ / "scenario.resolved.yaml");
    os << "# " << sc_.file.string() << " as run (parameters substituted, --set applied)\n";
    os << sc_.resolved << "\n";
  }
}

void Coupler::startParticipants() {
  std::string endpoint = sc_.transport.bind;
  if (endpoint.empty()) endpoint = "ipc:///tmp/cosim-" + run_id_ + ".ipc";
  hub_ = std::make_unique<link::Hub>(endpoint);
  std::string connect = sc_.transport.connect.empty() ? hub_->endpoint() : sc_.transport.connect;

  for (const auto& [name, spec] : sc_.participants) {
    const bool used = name == "particles" || (name == "fluid" && plan_.fluid);
    if (!used) continue;
    auto peer = std::make_unique<Peer>();
    peer->spec = spec;
    peer->workdir = folder_ / name;
    peer->log = folder_ / (name + ".log");
    fs::create_directories(peer->workdir);
    if (!spec.files.empty()) copyCaseFiles(spec.files, peer->workdir, sc_.parameters);
    if (spec.launch == "local") {
      auto exe = findExecutable(spec.command);
      if (!exe) {
        throw RunFailure(name, "cannot find the executable '" + spec.command + "' of adapter '" +
                                   spec.adapter +
                                   "' (looked next to cosim and in PATH; was it built?)");
      }
      std::vector<std::string> argv;
      if (spec.mpi > 1) {
        auto mpirun = findExecutable("mpirun");
        if (!mpirun)
          throw RunFailure(name, "mpi: " + std::to_string(spec.mpi) +
                                     " needs mpirun (apt-get install openmpi-bin)");
        argv = {mpirun->string(), "-np", std::to_string(spec.mpi)};
        if (geteuid() == 0) argv.push_back("--allow-run-as-root");
        argv.push_back("--oversubscribe");
      }
      argv.push_back(exe->string());
      for (const auto& a : {std::string("--endpoint"), connect, std::string("--name"), name,
                            std::string("--run-id"), run_id_}) {
        argv.push_back(a);
      }
      for (const auto& a : spec.args) argv.push_back(a);
      std::map<std::string, std::string> env;
      if (spec.mpi > 1 && geteuid() == 0) {
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1";
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1";
      }
      try {
        peer->process.emplace(argv, peer->workdir, peer->log, env);
      } catch (const std::exception& e) {
        throw RunFailure(name, e.what());
      }
      std::ofstream(folder_ / "cosim.log", std::ios::app)
          << "started " << name << ": " << join(argv) << "\n";
    }
    peers_[name] = std::move(peer);
  }
  if (!opt_.quiet) {
    std::cout << "cosim: run folder " << folder_.string() << "\n";
    for (const auto& n : plan_.notes) std::cout << "cosim: note: " << n << "\n";
    std::cout << "cosim: orchestrator at " << connect << "; participants: ";
    bool first = true;
    for (const auto& [n, p] : peers_) {
      std::cout << (first ? "" : ", ") << n << " (" << p->spec.adapter
                << (p->spec.mpi > 1 ? ", " + std::to_string(p->spec.mpi) + " MPI ranks" : "")
                << ")";
      first = false;
    }
    std::cout << std::endl;
  }
}

void Coupler::send(const std::string& peer, wire::Envelope& env) {
  auto* h = env.mutable_header();
  h->set_protocol_version(wire::PROTOCOL_VERSION);
  h->set_run_id(run_id_);
  h->set_participant(peer);
  h->set_step(step_);
  h->set_time(time_);
  try {
    hub_->send(peer, env);
  } catch (const std::exception& e) {
    // Usually the peer's process just died: say how, rather than only "unreachable".
    auto it = peers_.find(peer);
    if (it != peers_.end() && it->second->process) {
      auto& proc = *it->second->process;
      for (int i = 0; i < 40 && proc.running(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      if (!proc.running()) {
        throw RunFailure(peer, "the " + peer + " process (" + it->second->spec.adapter + ") " +
                                   proc.exitDescription() + " at step " + std::to_string(step_));
      }
    }
    throw RunFailure(peer, e.what());
  }
}

std::map<std::string, wire::Envelope> Coupler::await(
    const std::map<std::string, wire::Envelope::BodyCase>& expected, double timeout) {
  std::map<std::string, wire::Envelope> got;
  const auto start = Clock::now();
  while (got.size() < expected.size()) {
    if (g_stop_signal)
      throw RunFailure("", "interrupted (signal " + std::to_string(g_stop_signal.load()) + ")");
    auto in = hub_->receive(link::Millis(100));
    const auto now = Clock::now();
    if (in) {
      std::string who = in->peer;
      const bool hb = who.size() > 3 && who.compare(who.size() - 3, 3, "#hb") == 0;
      if (hb) who.resize(who.size() - 3);
      auto pit = peers_.find(who);
      if (pit == peers_.end()) {
        // Unknown sender: not part of this run. Ignore but keep a trace.
        std::ofstream(folder_ / "cosim.log", std::ios::app)
            << "ignored a message from unknown peer '" << in->peer << "'\n";
        continue;
      }
      pit->second->last_seen = now;
      if (!in->envelope) {
        throw RunFailure(who, "sent bytes that are not a cosim message: " + in->parse_error);
      }
      const auto& env = *in->envelope;
      if (env.has_heartbeat()) continue;
      if (env.header().protocol_version() != wire::PROTOCOL_VERSION) {
        throw RunFailure(who, "speaks protocol version " +
                                  std::to_string(env.header().protocol_version()) +
                                  ", the orchestrator " + std::to_string(wire::PROTOCOL_VERSION));
      }
      if (env.has_error()) {
        throw RunFailure(
            who, "reported an error: " + env.error().message() +
                     (env.error().where().empty() ? "" : " (at " + env.error().where() + ")"));
      }
      auto eit = expected.find(who);
      if (eit == expected.end() || got.count(who)) {
        throw RunFailure(who, "sent an unexpected message at step " + std::to_string(step_));
      }
      if (env.body_case() != eit->second) {
        throw RunFailure(who, "sent the wrong message type (body " +
                                  std::to_string(env.body_case()) + ", expected " +
                                  std::to_string(eit->second) + ") at step " +
                                  std::to_string(step_));
      }
      if (env.header().run_id() != run_id_) {
        throw RunFailure(
            who, "answered for run '" + env.header().run_id() + "', this run is '" + run_id_ + "'");
      }
      if (env.header().step() != step_) {
        throw RunFailure(who, "answered for step " + std::to_string(env.header().step()) +
                                  " while the run is at step " + std::to_string(step_) +
                                  " (out-of-order step)");
      }
      got[who] = env;
      continue;
    }
    // Nothing arrived: is everyone we wait for alive?
    for (const auto& [name, kind] : expected) {
      if (got.count(name)) continue;
      Peer& p = *peers_.at(name);
      if (p.process && !p.process->running()) {
        throw RunFailure(name, "the " + name + " process (" + p.spec.adapter + ") " +
                                   p.process->exitDescription() + " at step " +
                                   std::to_string(step_));
      }
      const double silent = std::chrono::duration<double>(now - p.last_seen).count();
      if (p.connected && silent > sc_.transport.heartbeat_timeout) {
        throw RunFailure(name, "silent for " + std::to_string(static_cast<int>(silent)) +
                                   " s (no heartbeat; hung, or its host is gone)");
      }
      if (std::chrono::duration<double>(now - start).count() > timeout) {
        throw RunFailure(name, "did not answer within " +
                                   std::to_string(static_cast<int>(timeout)) + " s at step " +
                                   std::to_string(step_) + " (participants." + name +
                                   ".timeout; raise it if a step is legitimately slow)");
      }
    }
  }
  return got;
}

void Coupler::handshake() {
  std::set<std::string> waiting;
  for (const auto& [n, p] : peers_) waiting.insert(n);
  const auto start = Clock::now();
  while (!waiting.empty()) {
    if (g_stop_signal) throw RunFailure("", "interrupted during start-up");
    auto in = hub_->receive(link::Millis(100));
    if (in) {
      std::string who = in->peer;
      if (who.size() > 3 && who.compare(who.size() - 3, 3, "#hb") == 0) continue;
      if (!peers_.count(who)) {
        std::ofstream(folder_ / "cosim.log", std::ios::app)
            << "ignored a connection from unknown participant '" << who << "'\n";
        continue;
      }
      Peer& p = *peers_.at(who);
      if (!in->envelope)
        throw RunFailure(who, "sent bytes that are not a cosim message: " + in->parse_error);
      const auto& env = *in->envelope;
      auto refuse = [&](const std::string& reason) {
        wire::Envelope r;
        r.mutable_refused()->set_reason(reason);
        send(who, r);
        throw RunFailure(who, "refused at handshake: " + reason);
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
      p.adapter = h.adapter();
      p.send = who == "fluid" ? plan_.fluid_send : plan_.particles_send;
      p.receive = who == "fluid" ? plan_.fluid_receive : plan_.particles_receive;
      const std::set<std::string> provides(h.provides().begin(), h.provides().end());
      const std::set<std::string> accepts(h.accepts().begin(), h.accepts().end());
      for (const auto& f : p.send) {
        if (!provides.count(f)) {
          refuse("this scene needs field '" + f + "' from the " + who +
                 " participant, but adapter '" + h.adapter() +
                 "' cannot provide it (it provides: " +
                 join({h.provides().begin(), h.provides().end()}) +
                 "); choose models that do not need it or another adapter");
        }
      }
      for (const auto& f : p.receive) {
        if (!accepts.count(f)) {
          refuse("this scene sends field '" + f + "' to the " + who +
                 " participant, but adapter '" + h.adapter() +
                 "' does not accept it (it accepts: " +
                 join({h.accepts().begin(), h.accepts().end()}) + ")");
        }
      }
      wire::Envelope w;
      auto* wel = w.mutable_welcome();
      for (const auto& f : p.send) wel->add_send(f);
      for (const auto& f : p.receive) wel->add_receive(f);
      YAML::Emitter em;
      em << p.spec.options;
      wel->set_config_yaml(em.c_str());
      wel->set_workdir(fs::absolute(p.workdir).string());
      wel->set_cfd_dt(sc_.coupling.dt);
      wel->set_dem_steps(sc_.coupling.dem_steps);
      wel->set_end_time(sc_.coupling.end_time);
      wel->set_start_time(sc_.coupling.start_time);
      for (const auto& [k, v] : sc_.parameters) (*wel->mutable_parameters())[k] = v;
      wel->set_species(plan_.coating);
      send(who, w);
      p.connected = true;
      p.last_seen = Clock::now();
      waiting.erase(who);
      std::ofstream(folder_ / "cosim.log", std::ios::app)
          << who << " connected: adapter " << h.adapter() << ", pid " << h.pid() << " on "
          << h.host() << "; sends " << join(p.send) << "; receives " << join(p.receive) << "\n";
      continue;
    }
    for (const auto& n : waiting) {
      Peer& p = *peers_.at(n);
      if (p.process && !p.process->running()) {
        throw RunFailure(n, "the " + n + " process (" + p.spec.adapter + ") " +
                                p.process->exitDescription() + " before connecting");
      }
    }
    if (std::chrono::duration<double>(Clock::now() - start).count() > sc_.transport.handshake_timeout) {
      std::string who = *waiting.begin();
      throw RunFailure(
          who,
          "did not connect within " + std::to_string(static_cast<int>(sc_.transport.handshake_timeout)) +
              " s (transport.handshake_timeout)" +
              (peers_.at(who)->spec.launch == "external"
                   ? "; start it with --endpoint " +
                         (sc_.transport.connect.empty() ? hub_->endpoint() : sc_.transport.connect) +
                         " --name " + who + " --run-id " + run_id_
                   : ""));
    }
  }
}

void Coupler::checkState(const link::ParticleData& s, const std::string& where) {
  for (const auto& name : s.names()) {
    const auto& v = s.get(name);
    const unsigned c = std::max(1U, field::components(name));
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!std::isfinite(v[i])) {
        const std::size_t p = i / c;
        std::ostringstream os;
        os << where << ": " << name << " of particle " << s.ids[p] << " is " << v[i] << " at step "
           << step_ << " (t = " << time_ << " s)";
        throw RunFailure(where, os.str());
      }
    }
  }
  if (s.has(field::velocity)) {
    const auto& v = s.get(field::velocity);
    for (std::size_t p = 0; p < s.size(); ++p) {
      const double speed = std::sqrt(v[3 * p] * v[3 * p] + v[3 * p + 1] * v[3 * p + 1] +
                                     v[3 * p + 2] * v[3 * p + 2]);
      if (speed > sc_.checks.max_particle_speed) {
        std::ostringstream os;
        os << where << ": particle " << s.ids[p] << " moves at " << speed << " m/s at step "
           << step_ << " (t = " << time_
           << " s), above checks.max_particle_speed = " << sc_.checks.max_particle_speed
           << " m/s: the run is unstable (DEM dt too large, or drag too stiff for the coupling "
              "interval?)";
        throw RunFailure(where, os.str());
      }
    }
  }
  if (s.has(field::voidage)) {
    const auto& e = s.get(field::voidage);
    for (std::size_t p = 0; p < s.size(); ++p) {
      if (e[p] <= 0.0 || e[p] > 1.0 + 1e-9) {
        std::ostringstream os;
        os << where << ": voidage " << e[p] << " at particle " << s.ids[p] << " (step " << step_
           << ") is outside (0, 1]";
        throw RunFailure(where, os.str());
      }
    }
  }
}

void Coupler::appendRow(double time, const std::vector<double>& row) {
  rec_->series->write(time, row);
  series_time_.push_back(time);
  for (std::size_t c = 0; c < row.size(); ++c) series_[rec_->columns[c]].push_back(row[c]);
}

void Coupler::record(double time, bool force) {
  if (!force && time + 1e-12 * std::max(1.0, std::fabs(time)) < next_output_) return;
  rec_->particles->write(time, heldState());
  next_output_ = time + sc_.output.interval;
}

link::ParticleData Coupler::heldState() const {
  if (pending_credit_.empty() || !state_.has(field::coating_mass)) return state_;
  link::ParticleData held = state_;
  auto& m = held.field(field::coating_mass);
  for (std::size_t i = 0; i < held.size(); ++i) {
    if (auto it = pending_credit_.find(held.ids[i]); it != pending_credit_.end())
      m[i] += it->second;
  }
  return held;
}

void Coupler::writeSummary(const RunResult& r, const std::string& status) {
  analysis::Summary s;
  s.scenario = sc_.name;
  s.run_id = run_id_;
  s.status = status;
  s.message = r.message;
  s.start_time = sc_.coupling.start_time;
  s.end_time = time_;
  s.steps = static_cast<std::int64_t>(r.steps);
  for (const auto& [k, v] : totals_) s.headline.emplace_back(k, v);
  s.headline.emplace_back("particle_count", static_cast<double>(state_.size()));
  s.timings.emplace_back("total", r.wall_seconds);
  for (const auto& [n, w] : wall_) s.timings.emplace_back(n + "_compute", w);
  for (const auto& [n, w] : phase_) s.timings.emplace_back("step_" + n, w);
  s.parameters.assign(sc_.parameters.begin(), sc_.parameters.end());
  s.coupling_dt = sc_.coupling.dt;
  s.dem_steps = static_cast<std::int64_t>(sc_.coupling.dem_steps);
  s.cg = sc_.constants.cg;
  s.coating = plan_.coating;
  s.observables = observables_;
  try {
    analysis::writeSummary(folder_ / analysis::kSummaryFile, s);
  } catch (const std::exception& e) {
    std::cerr << "cosim: could not write the summary: " << e.what() << "\n";
  }
}

void Coupler::shutdown(bool clean) {
  if (hub_ && clean) {
    std::map<std::string, wire::Envelope::BodyCase> bye;
    for (const auto& [n, p] : peers_) {
      if (!p->connected || (p->process && !p->process->running())) continue;
      wire::Envelope e;
      e.mutable_shutdown()->set_reason("end of run");
      send(n, e);
      bye[n] = wire::Envelope::kGoodbye;
    }
    try {
      await(bye, 60.0);
    } catch (const std::exception& e) {
      std::cerr << "cosim: warning: " << e.what() << "\n";
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
    wall_[n] = p->wall;
  }
  peers_.clear();
  if (hub_) {
    // An ipc:// endpoint is a socket file that zmq leaves behind: remove it with the hub.
    const std::string ep = hub_->endpoint();
    hub_.reset();
    if (ep.rfind("ipc://", 0) == 0) {
      std::error_code ec;
      fs::remove(ep.substr(6), ec);
    }
  }
}

RunResult Coupler::run() {
  RunResult result;
  const auto wall0 = Clock::now();
  time_ = sc_.coupling.start_time;
  next_output_ = sc_.coupling.start_time;
  prepareFolder();
  result.folder = folder_;
  const auto nsteps =
      static_cast<std::uint64_t>(std::llround((sc_.coupling.end_time - sc_.coupling.start_time) / sc_.coupling.dt));
  Progress progress(sc_.coupling.start_time, sc_.coupling.end_time, opt_.quiet);
  std::string status = "completed";
  try {
    rec_ = std::make_unique<Recorders>();
    std::vector<std::string> pfields = plan_.particles_send;
    rec_->particles = std::make_unique<analysis::ParticleRecorder>(folder_, pfields);
    rec_->columns = timeSeriesColumns(plan_);
    rec_->series = std::make_unique<analysis::TimeSeriesRecorder>(
        folder_ / analysis::kTimeSeriesFile, rec_->columns);

    startParticipants();
    handshake();

    // Initial state.
    step_ = 0;
    {
      wire::Envelope e;
      e.mutable_advance()->set_dt(0.0);
      send("particles", e);
      auto r =
          await({{"particles", wire::Envelope::kAdvanced}}, peers_.at("particles")->spec.timeout);
      state_ = link::ParticleData::fromWire(r.at("particles").advanced().state());
      checkState(state_, "particles");
    }
    double coating_initial = 0.0;
    if (plan_.coating) {
      for (double m : state_.get(field::coating_mass)) coating_initial += m;
    }
    record(time_, true);
    double in = 0, out = 0, removed = 0, credited = 0, held = 0;
    StepMonitor monitor(sc_);
    auto refuseOrWarn = [&](const StabilityReport& rep) {
      for (const auto& line : rep.lines) {
        if (!opt_.quiet) std::cout << "cosim: check: " << line << "\n";
        std::ofstream(folder_ / "cosim.log", std::ios::app) << "check: " << line << "\n";
      }
      if (!rep.refusals.empty() && sc_.checks.stability == "refuse") {
        std::string msg = "unstable settings refused:";
        for (const auto& r : rep.refusals) msg += "\n  - " + r;
        msg += "\n  (set checks.stability: warn to run anyway)";
        throw RunFailure("", msg);
      }
    };
    refuseOrWarn(checkBeforeRun(sc_, models_, plan_, state_));
    double held_start = 0.0, deleted_coating = 0.0;
    bool initial_row_written = false;
    // Credit what the fluid removed in the last step to the particles that took it up (the
    // fluid reports removal after a step; particles receive it with the next step's terms, so
    // the last step's removal needs an Advance of zero length of its own).
    auto flushCredit = [&] {
      wire::Envelope e;
      auto* a = e.mutable_advance();
      a->set_dt(0.0);
      link::ParticleData flush;
      flush.ids = state_.ids;
      auto& inc = flush.field(field::coating_increment);
      for (std::size_t i = 0; i < flush.size(); ++i) {
        auto it = pending_credit_.find(flush.ids[i]);
        if (it != pending_credit_.end()) {
          inc[i] = it->second;
          credited += it->second;
          pending_credit_.erase(it);
        }
      }
      flush.toWire(*a->mutable_terms());
      send("particles", e);
      auto r =
          await({{"particles", wire::Envelope::kAdvanced}}, peers_.at("particles")->spec.timeout);
      state_ = link::ParticleData::fromWire(r.at("particles").advanced().state());
      checkState(state_, "particles");
    };
    const std::size_t initial_count = state_.size();
    std::vector<char> lost;
    for (std::uint64_t k = 0; k < nsteps; ++k) {
      step_ = k + 1;
      time_ = stepTime(sc_.coupling.start_time, sc_.coupling.dt, k);
      link::ParticleData samples;
      lost.assign(state_.size(), 0);
      auto tick = Clock::now();
      auto lap = [&](const char* phase) {
        const auto now = Clock::now();
        phase_[phase] += std::chrono::duration<double>(now - tick).count();
        tick = now;
      };
      if (plan_.fluid) {
        wire::Envelope e;
        state_.select(plan_.fluid_receive).toWire(*e.mutable_sample()->mutable_particles());
        send("fluid", e);
        auto r = await({{"fluid", wire::Envelope::kSamples}}, peers_.at("fluid")->spec.timeout);
        const auto& sm = r.at("fluid").samples();
        samples = link::ParticleData::fromWire(sm.at_particles());
        if (samples.ids != state_.ids) {
          throw RunFailure("fluid",
                           "returned samples for other particles than it was sent (ids differ)");
        }
        if (sm.lost_ids_size() > 0) {
          auto idx = state_.index();
          for (auto id : sm.lost_ids()) {
            auto it = idx.find(id);
            if (it != idx.end()) lost[it->second] = 1;
          }
        }
        checkState(samples, "fluid");
        lap("fluid_sample");
      }
      CouplingTerms terms = evaluateTerms(models_, plan_, sc_.constants, state_, samples, lost);
      checkState(terms.forcing, "models (forcing)");
      if (k == 0) refuseOrWarn(checkFirstStep(sc_, state_, samples, terms.forcing));
      if (plan_.coating) {
        auto& inc = terms.forcing.field(field::coating_increment);
        for (std::size_t i = 0; i < terms.forcing.size(); ++i) {
          auto it = pending_credit_.find(terms.forcing.ids[i]);
          if (it != pending_credit_.end()) {
            inc[i] = it->second;
            credited += it->second;
            pending_credit_.erase(it);
          }
        }
      }
      lap("models");
      // Particles and fluid advance at the same time.
      std::map<std::string, wire::Envelope::BodyCase> wait;
      double timeout = 0;
      {
        wire::Envelope e;
        auto* a = e.mutable_advance();
        a->set_dt(sc_.coupling.dt);
        a->set_substeps(sc_.coupling.dem_steps);
        terms.forcing.select(plan_.particles_receive).toWire(*a->mutable_terms());
        send("particles", e);
        wait["particles"] = wire::Envelope::kAdvanced;
        timeout = peers_.at("particles")->spec.timeout;
      }
      if (plan_.fluid) {
        wire::Envelope e;
        auto* a = e.mutable_advance();
        a->set_dt(sc_.coupling.dt);
        a->set_substeps(1);
        terms.exchange.select(plan_.fluid_receive).toWire(*a->mutable_terms());
        send("fluid", e);
        wait["fluid"] = wire::Envelope::kAdvanced;
        timeout = std::max(timeout, peers_.at("fluid")->spec.timeout);
      }
      auto replies = await(wait, timeout);
      lap("advance");
      time_ = stepTime(sc_.coupling.start_time, sc_.coupling.dt, k + 1);
      const auto& pa = replies.at("particles").advanced();
      peers_.at("particles")->wall += pa.wall_seconds();
      {
        std::vector<std::int64_t> before = state_.ids;
        state_ = link::ParticleData::fromWire(pa.state());
        try {
          monitor.checkParticleLedger(
              before, state_.ids, {pa.inserted_ids().begin(), pa.inserted_ids().end()},
              {pa.deleted_ids().begin(), pa.deleted_ids().end()}, step_, time_);
        } catch (const std::exception& e) {
          throw RunFailure("particles", e.what());
        }
      }
      checkState(state_, "particles");
      if (plan_.fluid) {
        const auto& fa = replies.at("fluid").advanced();
        peers_.at("fluid")->wall += fa.wall_seconds();
        if (plan_.coating) {
          const auto fr = link::ParticleData::fromWire(fa.state());
          checkState(fr, "fluid");
          if (fr.has(field::precursor_removed)) {
            const auto& rm = fr.get(field::precursor_removed);
            for (std::size_t i = 0; i < fr.size(); ++i) {
              if (rm[i] != 0.0) {
                pending_credit_[fr.ids[i]] += rm[i];
                removed += rm[i];
              }
            }
          }
          auto scalar = [&](const char* n) {
            auto it = fa.scalars().find(n);
            return it == fa.scalars().end() ? 0.0 : it->second;
          };
          in += scalar("precursor_in");
          out += scalar("precursor_out");
          held = scalar("precursor_held");
          if (auto hs = fa.scalars().find("precursor_held_start");
              k == 0 && hs != fa.scalars().end()) {
            held_start = hs->second;
            monitor.setHeldAtStart(held_start);
          }
          try {
            monitor.checkMassBalance(in, out, held, removed, step_, time_);
          } catch (const std::exception& e) {
            throw RunFailure("fluid", e.what());
          }
        }
        if (auto it = fa.scalars().find("max_courant"); it != fa.scalars().end()) {
          try {
            if (auto w = monitor.checkCourant(it->second, step_, time_)) {
              progress.abort();
              if (!opt_.quiet) std::cout << "cosim: " << *w << "\n";
              std::ofstream(folder_ / "cosim.log", std::ios::app) << *w << "\n";
            }
          } catch (const std::exception& e) {
            throw RunFailure("fluid", e.what());
          }
        }
      }
      // Particles that left take their pending credit with them: count it as coating that left.
      for (auto id : pa.deleted_ids()) {
        auto it = pending_credit_.find(id);
        if (it != pending_credit_.end()) {
          totals_["coating_left_domain_kg"] += it->second;
          credited += it->second;
          pending_credit_.erase(it);
        }
      }
      if (auto it = pa.scalars().find("deleted_coating_mass"); it != pa.scalars().end())
        deleted_coating += it->second;
      if (plan_.coating && k + 1 == nsteps) flushCredit();
      if (!pa.inserted_ids().empty()) totals_["particles_inserted"] += pa.inserted_ids_size();
      if (!pa.deleted_ids().empty()) totals_["particles_deleted"] += pa.deleted_ids_size();

      if (plan_.coating && !initial_row_written) {
        // The state at the start for the mass balance, written once the fluid has said what it
        // holds at the start. Quantities that only exist over a step (pressure drop) are NaN.
        std::vector<double> row0;
        for (const auto& c : rec_->columns) {
          if (c == "particle_count")
            row0.push_back(static_cast<double>(initial_count));
          else if (c == analysis::column::precursor_held)
            row0.push_back(held_start);
          else if (c == "pressure_drop")
            row0.push_back(std::numeric_limits<double>::quiet_NaN());
          else
            row0.push_back(0.0);
        }
        appendRow(sc_.coupling.start_time, row0);
        initial_row_written = true;
      }
      // The row and the snapshot at time_ hold what the particles have at time_: the coating of
      // the step that ends at time_ is still pending (the particle participant receives it with
      // the next Advance, or with the final flush), so it is added here as the ledger will pay it.
      double credited_at_t = credited;
      for (const auto& [id, dm] : pending_credit_) credited_at_t += dm;
      std::vector<double> row;
      for (const auto& c : rec_->columns) {
        if (c == "particle_count")
          row.push_back(static_cast<double>(state_.size()));
        else if (c == "wall_seconds")
          row.push_back(std::chrono::duration<double>(Clock::now() - wall0).count());
        else if (c == analysis::column::precursor_in)
          row.push_back(in);
        else if (c == analysis::column::precursor_out)
          row.push_back(out);
        else if (c == analysis::column::precursor_held)
          row.push_back(held);
        else if (c == analysis::column::precursor_removed)
          row.push_back(removed);
        else if (c == analysis::column::coated_mass)
          row.push_back(credited_at_t);
        else if (c == "pressure_drop") {
          const auto& sc = replies.at("fluid").advanced().scalars();
          auto it = sc.find("pressure_drop");
          row.push_back(it == sc.end() ? 0.0 : it->second);
        } else
          row.push_back(0.0);
      }
      appendRow(time_, row);
      record(time_, k + 1 == nsteps);
      if (on_step) on_step(time_, heldState());
      lap("bookkeeping");
      progress.update(time_, k + 1, state_.size());
      result.steps = k + 1;
    }
    totals_["particles_inserted"] += 0.0;
    totals_["particles_deleted"] += 0.0;
    if (plan_.coating) {
      double coating_final = 0.0;
      for (double m : state_.get(field::coating_mass)) coating_final += m;
      totals_["precursor_in_kg"] = in;
      totals_["precursor_out_kg"] = out;
      totals_["precursor_held_start_kg"] = held_start;
      totals_["precursor_held_kg"] = held;
      totals_["precursor_removed_kg"] = removed;
      totals_["coating_credited_kg"] = credited;
      totals_["coating_on_particles_kg"] = coating_final - coating_initial + deleted_coating;
      if (deleted_coating != 0.0) totals_["coating_on_deleted_particles_kg"] = deleted_coating;
    }
    progress.finish(time_, result.steps);
    shutdown(true);
  } catch (const RunFailure& f) {
    status = g_stop_signal ? "interrupted" : "failed";
    std::ostringstream os;
    os << (f.participant.empty() ? std::string("cosim") : "participant '" + f.participant + "'")
       << ": " << f.what();
    auto pit = peers_.find(f.participant);
    if (pit != peers_.end()) {
      os << "\n  last lines of " << pit->second->log.string() << ":\n"
         << tailOfFile(pit->second->log, 15);
    }
    result.message = os.str();
    result.exit_code = g_stop_signal ? 130 : 2;
    progress.abort();
    shutdown(false);
  } catch (const std::exception& e) {
    status = "failed";
    result.message = std::string("cosim: ") + e.what();
    result.exit_code = 2;
    progress.abort();
    shutdown(false);
  }
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - wall0).count();
  result.final_state = state_;
  result.totals = totals_;
  if (result.exit_code == 0) {
    for (const auto& spec : sc_.observables) {
      ObservableValue v;
      v.name = spec.name;
      try {
        v.value =
            evaluateQuantity(spec.quantity, state_, series_time_, series_, totals_, spec.after);
      } catch (const UndefinedQuantity& e) {
        v.value = std::numeric_limits<double>::quiet_NaN();
        v.undefined = e.what();
      } catch (const std::exception& e) {
        result.exit_code = 2;
        result.message = std::string("cosim: observables.") + spec.name + ": " + e.what();
        status = "failed";
        break;
      }
      v.reference = spec.reference;
      if (v.undefined.empty()) v.relative_error = relativeError(v.value, v.reference);
      result.observables.push_back(v);
    }
  }
  observables_ = result.observables;
  writeSummary(result, status);
  if (!result.message.empty()) {
    std::ofstream(folder_ / "cosim.log", std::ios::app) << result.message << "\n";
    result.message += "\n  everything recorded so far is in " + folder_.string();
  }
  return result;
}

}  // namespace cosim::orchestrator
