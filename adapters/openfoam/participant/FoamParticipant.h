// cosimFoam's protocol side: implements cosim::link::Solver on rank 0 and forwards every
// command to the other ranks (RankBridge); serveRanks() is the loop of the other ranks.
// C++17, no OpenFOAM header: the gas lives behind GasDomain.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "AdapterSettings.h"
#include "GasDomain.h"
#include "RankBridge.h"
#include "cosim/link/session.h"

namespace cosim::foam {

class FoamParticipant : public cosim::link::Solver {
 public:
  // foamArgs: what Foam::argList gets (program name, -parallel, ...).
  FoamParticipant(const RankBridge& bridge, std::vector<std::string> foamArgs);

  cosim::link::Capabilities capabilities() const override;
  void configure(const cosim::wire::Welcome& welcome) override;
  void sample(const cosim::link::ParticleData& particles, cosim::link::ParticleData& out,
              std::vector<std::int64_t>& lost_ids) override;
  void advance(const cosim::wire::Advance& cmd, const cosim::link::ParticleData& terms,
               cosim::wire::Advanced& out, cosim::link::ParticleData& state) override;
  std::vector<std::string> checkpoint(const std::string& path) override;
  void restore(const std::string& path) override;
  void finish() override;

 private:
  const RankBridge& bridge_;
  std::vector<std::string> foamArgs_;
  std::unique_ptr<GasDomain> gas_;
  std::vector<std::string> send_;         // Welcome.send
  std::vector<std::int64_t> sampledIds_;  // ids of the last Sample, in its order
  bool species_ = false;
  double sampleSeconds_ = 0;   // wall time of the last Sample (reported with the Advance)
  std::size_t lostCount_ = 0;  // particles in no cell at the last Sample
};

// Other ranks: obey rank 0's commands until it says quit. Returns the exit code.
int serveRanks(const RankBridge& bridge, std::vector<std::string> foamArgs);

// Fields cosimFoam can send at particles.
const std::vector<std::string>& foamSampleFields();

}  // namespace cosim::foam
