// ParticleData, a zone pass and the particles' ledger totals to and from their wire forms
// (cosim.proto): the link's side of the contract, kept out of cosim_contract so that what only
// reads particles needs no protobuf.
#pragma once

#include <string>
#include <vector>

#include "cosim/link/coating_ledger.h"
#include "cosim/link/particle_data.h"
#include "cosim/link/zone_pass_tracker.h"

namespace cosim::wire {
class FieldSet;
class PeerLedger;
class ZonePass;
}  // namespace cosim::wire

namespace cosim::link {

class SharedArrayWriter;
class SharedArrayReader;

void toWire(const ParticleData& d, wire::FieldSet& out);
// Only the named fields (those it holds), as toWire(d.select(names), out) without the copy.
void toWire(const ParticleData& d, wire::FieldSet& out, const std::vector<std::string>& names);
// Validates lengths and component counts; throws ProtocolError with the field name.
ParticleData fromWire(const wire::FieldSet& in);

// The same through shared memory (the peers of one machine, shared_arrays.h): the values go to
// `shared` (in the message when it has none to give), and come from it where a field says so.
void toWire(const ParticleData& d, wire::FieldSet& out, SharedArrayWriter* shared);
void toWire(const ParticleData& d, wire::FieldSet& out, const std::vector<std::string>& names,
            SharedArrayWriter* shared);
ParticleData fromWire(const wire::FieldSet& in, SharedArrayReader* shared);

// One pass through the coating zone (a row of zone_passes.csv) and its wire form.
void toWire(const ZonePass& p, wire::ZonePass& out);
ZonePass fromWire(const wire::ZonePass& in);
// The particles' ledger totals (removed, credited, left_domain, any_left) of a PeerLedger.
CoatingLedger::Balance fromWire(const wire::PeerLedger& in);

}  // namespace cosim::link
