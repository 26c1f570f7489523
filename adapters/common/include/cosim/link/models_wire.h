// A scene's coupling laws and constants to and from their wire form (wire::SceneModels,
// cosim.proto): how the orchestrator hands a participant what it needs to evaluate the coupling
// terms over its own parcels (cosim/models/coupling_terms.h) exactly as it would itself. A
// library of its own (cosim_models_wire), so that the protocol library needs no model.
#pragma once

#include "cosim/models/parcels.h"
#include "cosim/models/scene_models.h"

namespace cosim::wire {
class SceneModels;
}

namespace cosim::link {

void toWire(const models::SceneModelChoices& choices, const models::SceneConstants& constants,
            wire::SceneModels& out);

// What a participant reads back; ProtocolError names the field a peer got wrong.
struct ReceivedModels {
  models::SceneModelChoices choices;
  models::SceneConstants constants;
};
ReceivedModels fromWire(const wire::SceneModels& in);

}  // namespace cosim::link
