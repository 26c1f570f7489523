// ParticleData to and from its wire form (wire::FieldSet, cosim.proto): the link's side of the
// contract, kept out of cosim_contract so that what only reads particles needs no protobuf.
#pragma once

#include <string>
#include <vector>

#include "cosim/link/particle_data.h"

namespace cosim::wire {
class FieldSet;
}

namespace cosim::link {

void toWire(const ParticleData& d, wire::FieldSet& out);
// Only the named fields (those it holds), as toWire(d.select(names), out) without the copy.
void toWire(const ParticleData& d, wire::FieldSet& out, const std::vector<std::string>& names);
// Validates lengths and component counts; throws ProtocolError with the field name.
ParticleData fromWire(const wire::FieldSet& in);

}  // namespace cosim::link
