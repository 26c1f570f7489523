// The scene's coupling laws as a particle participant evaluates them on the peer data path
// (coupling.data_path: peer, peer_link.h): built from the laws and constants the orchestrator
// sends (Welcome.peer.models), evaluated over this participant's parcels with the same function
// the orchestrator uses over all of them (cosim::models::evaluateTerms), so both paths give the
// same terms bit for bit. Part of cosim_models_wire.
#pragma once

#include <string>
#include <vector>

#include "cosim/link/peer_link.h"
#include "cosim/models/parcels.h"
#include "cosim/models/scene_models.h"

namespace cosim::link {

class ScenePeerTerms final : public PeerTerms {
 public:
  // Loads the plugins the scene names, builds its laws; ProtocolError or ModelError names what
  // the orchestrator sent wrong.
  void configure(const wire::PeerLink& link) override;
  Terms evaluate(const ParticleData& state, const ParticleData& samples,
                 const std::vector<char>& lost, double dt) override;
  // The transient wake's force history, parcel by parcel (empty without it).
  std::string saveState() const override;
  void restoreState(const std::string& bytes) override;

 private:
  models::SceneModels models_;
  models::SceneConstants constants_;
  bool coating_ = false;
};

}  // namespace cosim::link
