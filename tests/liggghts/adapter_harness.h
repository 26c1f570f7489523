// Plays the orchestrator for one cosim-liggghts process: binds a Hub, starts the adapter
// (under mpirun for more than one rank) in a scratch folder, answers its Hello and sends
// commands. The adapter is killed if the test ends early.
#pragma once

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cosim.pb.h"
#include "cosim/link/particle_data.h"
#include "cosim/link/particle_wire.h"
#include "cosim/link/transport.h"

namespace cosim::liggghts::test {

class AdapterRun {
 public:
  // workdir: the participant folder (scripts already copied in). ranks: MPI ranks.
  AdapterRun(const std::filesystem::path& workdir, int ranks) : workdir_(workdir) {
    static int counter = 0;
    endpoint_ = "ipc:///tmp/cosim-liggghts-test-" + std::to_string(::getpid()) + "-" +
                std::to_string(counter++) + ".ipc";
    hub_ = std::make_unique<link::Hub>(endpoint_);
    std::vector<std::string> args;
    if (ranks > 1) {
      args = {COSIM_MPIEXEC, "-np", std::to_string(ranks), "--oversubscribe",
              "--allow-run-as-root"};
    }
    for (const auto& a : {std::string(COSIM_LIGGGHTS_EXE), std::string("--endpoint"), endpoint_,
                          std::string("--name"), std::string("particles"), std::string("--run-id"),
                          std::string("test-run")})
      args.push_back(a);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::setpgid(0, 0);
      if (::chdir(workdir_.c_str()) != 0) ::_exit(127);
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  ~AdapterRun() {
    if (pid_ > 0 && !exited_) {
      ::kill(-pid_, SIGKILL);
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    std::error_code ec;
    std::filesystem::remove(endpoint_.substr(6), ec);
  }

  // Next non-heartbeat message from the adapter; fails the test on timeout.
  wire::Envelope receive(int timeout_s = 120) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
    while (std::chrono::steady_clock::now() < until) {
      auto in = hub_->receive(link::Millis(200));
      if (!in) continue;
      if (!in->envelope) throw std::runtime_error("undecodable message: " + in->parse_error);
      if (in->envelope->has_heartbeat()) continue;
      if (in->envelope->has_hello() && !peer_.empty()) continue;  // a copy sent before the Welcome
      peer_ = in->peer;  // the adapter's routing id (ZeroMQ makes one up per connection)
      return *in->envelope;
    }
    throw std::runtime_error("adapter silent for " + std::to_string(timeout_s) + " s");
  }

  // Hello -> Welcome. Returns the Hello.
  // restart_from: resume from this checkpoint folder (a Checkpoint's path); "" starts afresh.
  wire::Hello handshake(const std::string& config_yaml, double cfd_dt, unsigned dem_steps,
                        const std::vector<std::string>& send,
                        const std::vector<std::string>& receive_fields,
                        const std::string& restart_from = "") {
    auto hello = receive(60);
    if (!hello.has_hello()) throw std::runtime_error("expected Hello");
    wire::Envelope w;
    header(w);
    auto* welcome = w.mutable_welcome();
    for (const auto& s : send) welcome->add_send(s);
    for (const auto& r : receive_fields) welcome->add_receive(r);
    welcome->set_config_yaml(config_yaml);
    welcome->set_workdir(workdir_.string());
    welcome->set_cfd_dt(cfd_dt);
    welcome->set_dem_steps(dem_steps);
    welcome->set_end_time(1.0);
    welcome->set_restart_from(restart_from);
    hub_->send(peer_, w);
    return hello.hello();
  }

  // Advance; returns the reply (Advanced or Error).
  wire::Envelope advance(double dt, unsigned substeps, const link::ParticleData& terms) {
    wire::Envelope e;
    header(e);
    auto* a = e.mutable_advance();
    a->set_dt(dt);
    a->set_substeps(substeps);
    cosim::link::toWire(terms, *a->mutable_terms());
    hub_->send(peer_, e);
    auto reply = receive();
    if (reply.has_advanced()) {
      ++step_;
      time_ += dt;
    }
    return reply;
  }
  wire::Envelope checkpoint(const std::string& path) {
    wire::Envelope e;
    header(e);
    e.mutable_checkpoint()->set_path(path);
    hub_->send(peer_, e);
    return receive();
  }
  wire::Envelope shutdown() {
    wire::Envelope e;
    header(e);
    e.mutable_shutdown()->set_reason("test done");
    hub_->send(peer_, e);
    return receive();
  }
  // Exit code of the adapter (-1 if it is still running after timeout_s; -2 if killed by signal).
  int waitExit(int timeout_s = 30) {
    for (int waited = 0; waited < timeout_s * 20; ++waited) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return -1;
  }

 private:
  void header(wire::Envelope& e) const {
    auto* h = e.mutable_header();
    h->set_protocol_version(wire::PROTOCOL_VERSION);
    h->set_run_id("test-run");
    h->set_participant("particles");
    h->set_step(step_);
    h->set_time(time_);
  }
  std::filesystem::path workdir_;
  std::string endpoint_;
  std::unique_ptr<link::Hub> hub_;
  std::string peer_;  // routing id of the adapter's socket, from its messages
  pid_t pid_ = -1;
  bool exited_ = false;
  std::uint64_t step_ = 0;
  double time_ = 0;
};

}  // namespace cosim::liggghts::test
