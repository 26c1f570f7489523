#include "cosim/link/particle_wire.h"

#include <algorithm>

#include "cosim.pb.h"
#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/shared_arrays.h"

namespace cosim::link {

using field::componentsOrOne;

namespace {

// The fields `keep` lets through, their values to `shared` when it can take them, else inline
template <class Keep>
void putFields(const ParticleData& d, wire::FieldSet& out, Keep keep, SharedArrayWriter* shared) {
  out.Clear();
  out.mutable_ids()->Assign(d.ids.begin(), d.ids.end());
  for (const auto& [name, v] : d.fields()) {  // in the map's order, as select() then toWire()
    if (!keep(name)) continue;
    auto* f = out.add_fields();
    f->set_name(name);
    f->set_components(componentsOrOne(name));
    if (shared == nullptr || !shared->put(v.data(), v.size(), *f->mutable_shared())) {
      f->clear_shared();
      f->mutable_values()->Assign(v.begin(), v.end());
    }
  }
}

}  // namespace

void toWire(const ParticleData& d, wire::FieldSet& out) { toWire(d, out, nullptr); }

void toWire(const ParticleData& d, wire::FieldSet& out, SharedArrayWriter* shared) {
  putFields(
      d, out, [](const std::string&) { return true; }, shared);
}

void toWire(const ParticleData& d, wire::FieldSet& out, const std::vector<std::string>& names) {
  toWire(d, out, names, nullptr);
}

void toWire(const ParticleData& d, wire::FieldSet& out, const std::vector<std::string>& names,
            SharedArrayWriter* shared) {
  putFields(
      d, out,
      [&](const std::string& name) {
        return std::find(names.begin(), names.end(), name) != names.end();
      },
      shared);
}

ParticleData fromWire(const wire::FieldSet& in) { return fromWire(in, nullptr); }

ParticleData fromWire(const wire::FieldSet& in, SharedArrayReader* shared) {
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
    const std::size_t expected = d.ids.size() * known;
    if (f.has_shared()) {
      if (f.values_size() != 0 || shared == nullptr)
        throw ProtocolError("particle field '" + f.name() + "' has its values in shared memory" +
                            (shared == nullptr ? ", which this link does not use"
                                               : " and in the message, which are two answers"));
      const double* v = shared->at(f.shared(), expected);
      d.put(f.name(), std::vector<double>(v, v + expected));
      continue;
    }
    if (static_cast<std::size_t>(f.values_size()) != expected) {
      throw ProtocolError("particle field '" + f.name() + "' has " +
                          std::to_string(f.values_size()) + " values for " +
                          std::to_string(d.ids.size()) + " particles (expected " +
                          std::to_string(expected) + ")");
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
