#include "cosim/link/particle_wire.h"

#include <algorithm>

#include "cosim.pb.h"
#include "cosim/link/errors.h"
#include "cosim/link/fields.h"

namespace cosim::link {

using field::componentsOrOne;

void toWire(const ParticleData& d, wire::FieldSet& out) {
  out.Clear();
  out.mutable_ids()->Assign(d.ids.begin(), d.ids.end());
  for (const auto& [name, v] : d.fields()) {
    auto* f = out.add_fields();
    f->set_name(name);
    f->set_components(componentsOrOne(name));
    f->mutable_values()->Assign(v.begin(), v.end());
  }
}

void toWire(const ParticleData& d, wire::FieldSet& out, const std::vector<std::string>& names) {
  out.Clear();
  out.mutable_ids()->Assign(d.ids.begin(), d.ids.end());
  for (const auto& [name, v] : d.fields()) {  // in the map's order, as select() then toWire()
    if (std::find(names.begin(), names.end(), name) == names.end()) continue;
    auto* f = out.add_fields();
    f->set_name(name);
    f->set_components(componentsOrOne(name));
    f->mutable_values()->Assign(v.begin(), v.end());
  }
}

ParticleData fromWire(const wire::FieldSet& in) {
  ParticleData d;
  d.ids.assign(in.ids().begin(), in.ids().end());
  for (const auto& f : in.fields()) {
    const unsigned known = field::components(f.name());
    if (known == 0) {
      throw ProtocolError("unknown particle field '" + f.name() + "'");
    }
    if (f.components() != known) {
      throw ProtocolError("particle field '" + f.name() + "' has " +
                          std::to_string(f.components()) + " components, expected " +
                          std::to_string(known));
    }
    if (static_cast<std::size_t>(f.values_size()) != d.ids.size() * known) {
      throw ProtocolError("particle field '" + f.name() + "' has " +
                          std::to_string(f.values_size()) + " values for " +
                          std::to_string(d.ids.size()) + " particles (expected " +
                          std::to_string(d.ids.size() * known) + ")");
    }
    d.put(f.name(), std::vector<double>(f.values().begin(), f.values().end()));
  }
  return d;
}

void toWire(const ZonePass& p, wire::ZonePass& out) {
  out.set_parcel_id(p.parcel_id);
  out.set_entry_time(p.entry_time);
  out.set_exit_time(p.exit_time);
  out.set_coating(p.coating);
  out.set_at_start(p.at_start);
  out.set_exit(p.exit == ZonePass::Exit::left      ? wire::ZonePass::LEFT
               : p.exit == ZonePass::Exit::run_end ? wire::ZonePass::RUN_END
                                                   : wire::ZonePass::DELETED);
}

ZonePass fromWire(const wire::ZonePass& in) {
  return {in.parcel_id(),
          in.entry_time(),
          in.exit_time(),
          in.coating(),
          in.at_start(),
          in.exit() == wire::ZonePass::RUN_END   ? ZonePass::Exit::run_end
          : in.exit() == wire::ZonePass::DELETED ? ZonePass::Exit::deleted
                                                 : ZonePass::Exit::left};
}

CoatingLedger::Balance fromWire(const wire::PeerLedger& in) {
  CoatingLedger::Balance b;
  b.removed = in.removed();
  b.credited = in.credited();
  b.left_domain = in.left_domain();
  b.any_left = in.any_left();
  return b;
}

}  // namespace cosim::link
