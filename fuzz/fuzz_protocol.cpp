// Fuzzes the decoding of incoming protocol messages, as the orchestrator and the adapters do it
// (link/): any bytes must give an Envelope or a ProtocolError from parse(), and every per-particle
// field set in a decoded Envelope a ParticleData or a ProtocolError from fromWire(); never a
// crash, undefined behaviour or another exception. Seeds: fuzz_protocol_seeds writes one
// message of every kind.
#include <cstddef>
#include <cstdint>

#include "cosim.pb.h"
#include "cosim/link/errors.h"
#include "cosim/link/particle_data.h"
#include "cosim/link/particle_wire.h"
#include "cosim/link/transport.h"

namespace {

void decodeFields(const cosim::wire::FieldSet& fields) {
  try {
    const auto d = cosim::link::fromWire(fields);
    cosim::wire::FieldSet back;
    cosim::link::toWire(d, back);  // what a reply built from it would carry
  } catch (const cosim::link::ProtocolError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cosim::wire::Envelope env;
  try {
    env = cosim::link::parse(data, size);
  } catch (const cosim::link::ProtocolError&) {
    return 0;
  }
  if (env.has_sample()) decodeFields(env.sample().particles());
  if (env.has_samples()) decodeFields(env.samples().at_particles());
  if (env.has_advance()) decodeFields(env.advance().terms());
  if (env.has_advanced()) decodeFields(env.advanced().state());
  (void)cosim::link::serialize(env);
  return 0;
}
