// Plays the orchestrator for cosimFoam in tests: copies a test case (replacing ${key} from a
// map), binds a Hub, starts cosimFoam (optionally under mpirun), answers its Hello and sends
// Sample / Advance / Shutdown. The child is killed if the test fails or throws.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cosim.pb.h"
#include "cosim/link/particle_data.h"
#include "cosim/link/transport.h"

namespace cosim::test {

struct FoamRunConfig {
  std::string case_name = "column";               // folder under tests/openfoam/cases
  std::map<std::string, std::string> substitute;  // ${key} -> value in every case file
  struct Edit {
    std::string file, from, to;  // replace text `from` by `to` in the copied case's file
  };
  std::vector<Edit> edits;
  std::string options_yaml;  // Welcome.config_yaml
  bool species = false;
  std::vector<std::string> send;     // Welcome.send
  std::vector<std::string> receive;  // Welcome.receive
  int ranks = 1;                     // > 1: mpirun -np ranks ... -parallel
};

class FoamRun {
 public:
  explicit FoamRun(const FoamRunConfig& config);
  ~FoamRun();
  FoamRun(const FoamRun&) = delete;
  FoamRun& operator=(const FoamRun&) = delete;

  struct SampleReply {
    cosim::link::ParticleData at;
    std::vector<std::int64_t> lost;
  };
  // Starts coupling step k (k = number of Advance calls so far).
  SampleReply sample(const cosim::link::ParticleData& particles);
  // Advances the gas by dt with the exchange terms; ends the step. `ahead`: the particles at the
  // start of the step, sent as Advance.sample_ahead (coupling scheme overlapped).
  cosim::wire::Advanced advance(double dt, const cosim::link::ParticleData& terms,
                                const cosim::link::ParticleData* ahead = nullptr);
  // Checkpoint{path} -> CheckpointWritten; returns the files/folders written.
  std::vector<std::string> checkpoint(const std::string& path);
  // Shutdown -> Goodbye; returns the process exit code.
  int shutdown();

  const std::string& caseDir() const { return dir_; }
  double time() const { return time_; }

 private:
  cosim::wire::Envelope request(cosim::wire::Envelope env);
  cosim::wire::Envelope receive(const char* expecting);
  void fillHeader(cosim::wire::Header* h) const;

  std::string dir_;
  std::string run_id_;
  std::unique_ptr<cosim::link::Hub> hub_;
  std::string peer_;  // routing id of the adapter's socket, from its messages
  pid_t child_ = -1;
  std::uint64_t step_ = 0;
  double time_ = 0;
};

// Values of a volScalarField's internalField in the newest time folder of a (serial) case.
std::vector<double> readLatestCellField(const std::string& caseDir, const std::string& field);

// A particle set with position, radius and velocity filled.
cosim::link::ParticleData makeParticles(const std::vector<double>& xyz, double radius);

}  // namespace cosim::test
