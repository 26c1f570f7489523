#include "foam_harness.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "cosim/link/particle_wire.h"

namespace cosim::test {
namespace fs = std::filesystem;

namespace {

std::string substituted(std::string text, const std::map<std::string, std::string>& subst) {
  for (const auto& [key, value] : subst) {
    const std::string token = "${" + key + "}";
    for (auto pos = text.find(token); pos != std::string::npos; pos = text.find(token, pos)) {
      text.replace(pos, token.size(), value);
      pos += value.size();
    }
  }
  if (const auto pos = text.find("${"); pos != std::string::npos) {
    throw std::runtime_error("test case file keeps an unreplaced " +
                             text.substr(pos, text.find('}', pos) - pos + 1));
  }
  return text;
}

void copyCase(const fs::path& from, const fs::path& to,
              const std::map<std::string, std::string>& subst) {
  for (const auto& e : fs::recursive_directory_iterator(from)) {
    const fs::path target = to / fs::relative(e.path(), from);
    if (e.is_directory()) {
      fs::create_directories(target);
      continue;
    }
    std::ifstream in(e.path());
    std::stringstream ss;
    ss << in.rdbuf();
    std::ofstream(target) << substituted(ss.str(), subst);
  }
}

}  // namespace

FoamRun::FoamRun(const FoamRunConfig& config) {
  static int counter = 0;
  const std::string tag = std::to_string(getpid()) + "-" + std::to_string(counter++);
  dir_ = (fs::temp_directory_path() / ("cosimfoam-test-" + tag)).string();
  fs::remove_all(dir_);
  fs::create_directories(dir_);
  copyCase(fs::path(COSIM_FOAM_CASES) / config.case_name, dir_, config.substitute);
  for (const auto& edit : config.edits) {
    const fs::path file = fs::path(dir_) / edit.file;
    std::ifstream in(file);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    const auto pos = text.find(edit.from);
    if (pos == std::string::npos) {
      throw std::runtime_error("test edit: '" + edit.from + "' not in " + file.string());
    }
    text.replace(pos, edit.from.size(), edit.to);
    std::ofstream(file) << text;
  }

  run_id_ = "test-" + tag;
  // The socket file is this process's own (pid in the name): one left by an earlier process with
  // the same pid is stale, and the Hub refuses to bind over an existing file.
  const fs::path socket = fs::path("/tmp") / ("cosimfoam-" + tag + ".ipc");
  std::error_code ec;
  fs::remove(socket, ec);
  const std::string endpoint = "ipc://" + socket.string();
  hub_ = std::make_unique<cosim::link::Hub>(endpoint);

  std::vector<std::string> args;
  if (config.ranks > 1) {
    args = {"mpirun", "--oversubscribe", "--allow-run-as-root", "-np",
            std::to_string(config.ranks)};
  }
  args.insert(args.end(),
              {COSIM_FOAM_EXE, "--endpoint", endpoint, "--name", "fluid", "--run-id", run_id_});
  if (config.ranks > 1) args.push_back("-parallel");

  child_ = fork();
  if (child_ == 0) {
    if (chdir(dir_.c_str()) != 0) _exit(126);
    setenv("PWD", dir_.c_str(), 1);
    const int log = open("log.cosimFoam", O_CREAT | O_WRONLY | O_TRUNC, 0644);
    dup2(log, 1);
    dup2(log, 2);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    _exit(127);
  }

  // Hello -> Welcome
  const auto hello = receive("Hello");
  if (!hello.has_hello()) throw std::runtime_error("cosimFoam did not say Hello first");
  if (hello.hello().role() != cosim::wire::FLUID) {
    throw std::runtime_error("cosimFoam did not announce itself as FLUID");
  }
  cosim::wire::Envelope welcome;
  fillHeader(welcome.mutable_header());
  auto* w = welcome.mutable_welcome();
  for (const auto& s : config.send) w->add_send(s);
  for (const auto& r : config.receive) w->add_receive(r);
  w->set_config_yaml(config.options_yaml);
  w->set_workdir(dir_);
  w->set_cfd_dt(1e-3);
  w->set_end_time(1.0);
  w->set_species(config.species);
  hub_->send(peer_, welcome);
}

FoamRun::~FoamRun() {
  if (child_ > 0) {
    int status = 0;
    if (waitpid(child_, &status, WNOHANG) == 0) {
      // SIGTERM first: mpirun forwards it to its ranks (it cannot forward SIGKILL)
      kill(child_, SIGTERM);
      bool gone = false;
      for (int i = 0; i < 50 && !gone; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        gone = waitpid(child_, &status, WNOHANG) == child_;
      }
      if (!gone) {
        kill(child_, SIGKILL);
        waitpid(child_, &status, 0);
      }
    }
  }
  std::error_code ec;
  if (std::getenv("COSIM_KEEP_TEST_CASES") == nullptr) fs::remove_all(dir_, ec);
}

void FoamRun::fillHeader(cosim::wire::Header* h) const {
  h->set_protocol_version(cosim::wire::PROTOCOL_VERSION);
  h->set_run_id(run_id_);
  h->set_participant("fluid");
  h->set_step(step_);
  h->set_time(time_);
}

cosim::wire::Envelope FoamRun::receive(const char* expecting) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(180);
  while (std::chrono::steady_clock::now() < deadline) {
    auto in = hub_->receive(cosim::link::Millis(200));
    if (!in) {
      int status = 0;
      if (child_ > 0 && waitpid(child_, &status, WNOHANG) == child_) {
        child_ = -1;
        throw std::runtime_error(std::string("cosimFoam exited while the test waited for ") +
                                 expecting + " (see " + dir_ + "/log.cosimFoam)");
      }
      continue;
    }
    if (!in->envelope) throw std::runtime_error("undecodable message: " + in->parse_error);
    if (in->envelope->has_heartbeat()) continue;
    if (in->envelope->has_hello() && !peer_.empty()) continue;  // a copy sent before the Welcome
    peer_ = in->peer;  // the adapter's routing id (ZeroMQ makes one up per connection)
    if (in->envelope->has_error()) {
      throw std::runtime_error("cosimFoam error: " + in->envelope->error().message());
    }
    return *in->envelope;
  }
  throw std::runtime_error(std::string("no ") + expecting + " from cosimFoam within 180 s");
}

cosim::wire::Envelope FoamRun::request(cosim::wire::Envelope env) {
  fillHeader(env.mutable_header());
  hub_->send(peer_, env);
  return receive(env.has_sample() ? "Samples" : env.has_advance() ? "Advanced" : "Goodbye");
}

FoamRun::SampleReply FoamRun::sample(const cosim::link::ParticleData& particles) {
  cosim::wire::Envelope env;
  cosim::link::toWire(particles, *env.mutable_sample()->mutable_particles());
  const auto reply = request(env);
  if (!reply.has_samples()) throw std::runtime_error("expected Samples");
  SampleReply r;
  r.at = cosim::link::fromWire(reply.samples().at_particles());
  r.lost.assign(reply.samples().lost_ids().begin(), reply.samples().lost_ids().end());
  return r;
}

cosim::wire::Advanced FoamRun::advance(double dt, const cosim::link::ParticleData& terms,
                                       const cosim::link::ParticleData* ahead) {
  cosim::wire::Envelope env;
  env.mutable_advance()->set_dt(dt);
  cosim::link::toWire(terms, *env.mutable_advance()->mutable_terms());
  if (ahead != nullptr) cosim::link::toWire(*ahead, *env.mutable_advance()->mutable_sample_ahead());
  const auto reply = request(env);
  if (!reply.has_advanced()) throw std::runtime_error("expected Advanced");
  ++step_;
  time_ += dt;
  return reply.advanced();
}

std::vector<std::string> FoamRun::checkpoint(const std::string& path) {
  cosim::wire::Envelope env;
  env.mutable_checkpoint()->set_path(path);
  fillHeader(env.mutable_header());
  hub_->send(peer_, env);
  const auto reply = receive("CheckpointWritten");
  if (!reply.has_checkpoint_written()) throw std::runtime_error("expected CheckpointWritten");
  return {reply.checkpoint_written().files().begin(), reply.checkpoint_written().files().end()};
}

int FoamRun::shutdown() {
  cosim::wire::Envelope env;
  env.mutable_shutdown()->set_reason("test done");
  const auto reply = request(env);
  if (!reply.has_goodbye()) throw std::runtime_error("expected Goodbye");
  int status = 0;
  for (int i = 0; i < 300 && child_ > 0; ++i) {
    if (waitpid(child_, &status, WNOHANG) == child_) {
      child_ = -1;
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return -1;
}

std::vector<double> readLatestCellField(const std::string& caseDir, const std::string& field) {
  double newest = -1;
  fs::path folder;
  for (const auto& e : fs::directory_iterator(caseDir)) {
    if (!e.is_directory()) continue;
    try {
      std::size_t used = 0;
      const std::string name = e.path().filename().string();
      const double t = std::stod(name, &used);
      if (used == name.size() && t > newest && fs::exists(e.path() / field)) {
        newest = t;
        folder = e.path();
      }
    } catch (const std::exception&) {
    }
  }
  if (newest < 0) throw std::runtime_error("no time folder with " + field + " in " + caseDir);
  std::ifstream in(folder / field);
  std::string word;
  while (in >> word && word != "internalField") {
  }
  in >> word;
  if (word == "uniform") {
    throw std::runtime_error(field + " is uniform in " + folder.string());
  }
  in >> word;  // List<scalar>
  std::size_t n = 0;
  char paren = 0;
  in >> n >> paren;
  std::vector<double> values(n);
  for (auto& v : values) in >> v;
  if (!in) throw std::runtime_error("cannot read " + (folder / field).string());
  return values;
}

cosim::link::ParticleData makeParticles(const std::vector<double>& xyz, double radius) {
  cosim::link::ParticleData p;
  const std::size_t n = xyz.size() / 3;
  for (std::size_t i = 0; i < n; ++i) p.ids.push_back(static_cast<std::int64_t>(i + 1));
  p.field("position") = xyz;
  p.field("radius").assign(n, radius);
  p.field("velocity").assign(3 * n, 0.0);
  return p;
}

}  // namespace cosim::test
