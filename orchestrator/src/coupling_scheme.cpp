#include "coupling_scheme.h"

#include <algorithm>
#include <stdexcept>

#include "cosim/link/fields.h"
#include "cosim/link/particle_wire.h"
#include "cosim/link/session.h"

namespace cosim::orchestrator {

namespace {

wire::Envelope particleAdvance(const Scenario& sc, const Plan& plan,
                               const models::CouplingTerms& terms) {
  wire::Envelope e;
  auto* a = e.mutable_advance();
  a->set_dt(sc.coupling.dt);
  a->set_substeps(sc.coupling.dem_steps);
  cosim::link::toWire(terms.forcing, *a->mutable_terms(), plan.particles_receive);
  return e;
}

wire::Envelope fluidAdvance(const Scenario& sc, const Plan& plan,
                            const models::CouplingTerms& terms) {
  wire::Envelope e;
  auto* a = e.mutable_advance();
  a->set_dt(sc.coupling.dt);
  a->set_substeps(1);
  cosim::link::toWire(terms.exchange, *a->mutable_terms(), plan.fluid_advance_terms);
  return e;
}

// `from` restricted to (and ordered as) `ids`; particles it does not hold get zero terms.
link::ParticleData onIds(const link::ParticleData& from, const std::vector<std::int64_t>& ids) {
  if (from.ids == ids) return from;
  const auto where = from.index();
  link::ParticleData out;
  out.ids = ids;
  for (const auto& name : from.names()) {
    const unsigned c = field::components(name);
    const auto& src = from.get(name);
    auto& dst = out.field(name);
    dst.assign(ids.size() * c, 0.0);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const auto it = where.find(ids[i]);
      if (it == where.end()) continue;
      for (unsigned d = 0; d < c; ++d) dst[i * c + d] = src[it->second * c + d];
    }
  }
  return out;
}

}  // namespace

AdvanceReplies ParallelScheme::advance(Participants& participants,
                                       const link::ParticleData& /*state*/,
                                       const models::CouplingTerms& terms) {
  std::map<std::string, Participants::MessageBuilder> build;
  build["particles"] = [&] { return particleAdvance(sc_, plan_, terms); };
  if (plan_.fluid) build["fluid"] = [&] { return fluidAdvance(sc_, plan_, terms); };
  auto replies = participants.advance(build);
  AdvanceReplies r;
  r.particles = std::move(*replies.at("particles").mutable_advanced());
  if (plan_.fluid) r.fluid = std::move(*replies.at("fluid").mutable_advanced());
  return r;
}

AdvanceReplies PeerScheme::advance(Participants& participants, const link::ParticleData& /*state*/,
                                   const models::CouplingTerms& terms) {
  std::map<std::string, Participants::MessageBuilder> build;
  build["particles"] = [&] {
    wire::Envelope e;
    auto* a = e.mutable_advance();
    a->set_dt(sc_.coupling.dt);
    a->set_substeps(sc_.coupling.dem_steps);
    if (terms.forcing.has(field::coating_increment))
      cosim::link::toWire(terms.forcing, *a->mutable_terms(), {field::coating_increment});
    a->set_report_terms(report_);
    a->set_state_changes_only(true);  // the orchestrator asks for the state when it records it
    return e;
  };
  build["fluid"] = [&] {
    wire::Envelope e;
    e.mutable_advance()->set_dt(sc_.coupling.dt);
    e.mutable_advance()->set_substeps(1);
    return e;
  };
  auto replies = participants.advance(build);
  report_ = false;
  AdvanceReplies r;
  r.particles = std::move(*replies.at("particles").mutable_advanced());
  r.fluid = std::move(*replies.at("fluid").mutable_advanced());
  if (!r.particles->has_peer())
    throw RunFailure("particles",
                     "answered an interval of coupling.data_path: peer without its account "
                     "(Advanced.peer): the adapter does not run the peer path",
                     ErrorKind::peer);
  return r;
}

AdvanceReplies OverlappedScheme::advance(Participants& participants,
                                         const link::ParticleData& state,
                                         const models::CouplingTerms& terms) {
  std::map<std::string, Participants::MessageBuilder> build;
  build["particles"] = [&] { return particleAdvance(sc_, plan_, terms); };
  if (plan_.fluid) {
    build["fluid"] = [&] {
      auto fluid = fluidAdvance(sc_, plan_, terms);
      cosim::link::toWire(state, *fluid.mutable_advance()->mutable_sample_ahead(),
                          plan_.sample_state);
      sent_.ids.assign(state.ids.begin(), state.ids.end());  // for a checkpoint (samplingAhead)
      for (const auto& name : plan_.sample_state)
        if (state.has(name))
          sent_.field(name).assign(state.get(name).begin(), state.get(name).end());
      return fluid;
    };
  }
  auto replies = participants.advance(build);
  AdvanceReplies r;
  r.particles = std::move(*replies.at("particles").mutable_advanced());
  ahead_.reset();
  if (plan_.fluid) {
    r.fluid = std::move(*replies.at("fluid").mutable_advanced());
    if (r.fluid->has_ahead()) {
      ahead_ = std::move(*r.fluid->mutable_ahead());
      participants.addComputeSeconds("fluid_sample_ahead", ahead_->wall_seconds());
    }
  }
  return r;
}

std::optional<link::ParticleData> OverlappedScheme::samplingAhead() const {
  if (!ahead_) return std::nullopt;
  return link::predictedAt(sent_, sc_.coupling.dt);  // what the fluid computed from the same bits
}

std::optional<wire::Samples> OverlappedScheme::samplesAhead(Participants& participants,
                                                            const link::ParticleData& state) {
  if (resume_at_) {  // the first interval after a resume: the gas where it was sampled ahead
    wire::Envelope e;
    cosim::link::toWire(*resume_at_, *e.mutable_sample()->mutable_particles());
    resume_at_.reset();
    auto r = participants.request("fluid", std::move(e), wire::Envelope::kSamples);
    participants.addComputeSeconds("fluid_sample_ahead", r.samples().wall_seconds());
    ahead_ = std::move(*r.mutable_samples());
  }
  if (!ahead_) return std::nullopt;
  std::optional<wire::Samples> s = std::move(ahead_);
  ahead_.reset();
  const auto& ids = s->at_particles().ids();
  if (static_cast<std::size_t>(ids.size()) != state.ids.size() ||
      !std::equal(ids.begin(), ids.end(), state.ids.begin()))
    return std::nullopt;  // particles appeared or left: sample them where they are
  // A parcel predicted outside the mesh (moving towards a wall it will bounce off) would lose
  // its drag and its volume for a step: sample them all where they are instead
  if (s->lost_ids_size() > 0) return std::nullopt;
  return s;
}

std::optional<models::CouplingTerms> FrozenScheme::replay(const link::ParticleData& state) {
  const std::size_t k = interval_++;
  // The fluid places the exchange terms in the cells it found the parcels in, so the fluid
  // alone samples them once, at the first interval (the same terms as the recording's first).
  if (k == 0 && alone_ == Alone::fluid) return std::nullopt;
  if (recording_ && k < recording_->size()) {
    const models::CouplingTerms recorded = (*recording_)[k];
    models::CouplingTerms t;  // only what the solver alone is sent
    if (alone_ == Alone::particles)
      t.forcing = onIds(recorded.forcing, state.ids);
    else
      t.exchange = recorded.exchange;
    ++replayed_;
    if (k + 1 == recording_->size()) {  // past the end: the last interval's terms, held
      frozen_ = recorded;
      if (frozen_->forcing.has(field::coating_increment))
        frozen_->forcing.field(field::coating_increment).assign(frozen_->forcing.size(), 0.0);
    }
    return t;
  }
  if (!frozen_) return std::nullopt;
  models::CouplingTerms t;
  t.forcing = onIds(frozen_->forcing, state.ids);
  t.exchange = frozen_->exchange;
  return t;
}

AdvanceReplies FrozenScheme::advance(Participants& participants,
                                     const link::ParticleData& /*state*/,
                                     const models::CouplingTerms& terms) {
  if (!frozen_) {
    frozen_ = terms;
    // The coating owed is paid once, with the first interval.
    if (frozen_->forcing.has(field::coating_increment))
      frozen_->forcing.field(field::coating_increment).assign(frozen_->forcing.size(), 0.0);
  }
  AdvanceReplies r;
  if (alone_ == Alone::particles) {
    auto reply = participants.request("particles", particleAdvance(sc_, plan_, terms),
                                      wire::Envelope::kAdvanced);
    r.particles = std::move(*reply.mutable_advanced());
  } else if (plan_.fluid) {
    auto reply =
        participants.request("fluid", fluidAdvance(sc_, plan_, terms), wire::Envelope::kAdvanced);
    r.fluid = std::move(*reply.mutable_advanced());
  }
  return r;
}

std::unique_ptr<CouplingScheme> makeCouplingScheme(const Scenario& sc, const Plan& plan,
                                                   const std::string& name,
                                                   std::shared_ptr<const TermsRecording> recording,
                                                   bool fresh) {
  if ((name == "parallel" || name == "overlapped") && plan.peer)
    return std::make_unique<PeerScheme>(sc, plan, fresh);  // the particles sample the gas
  if (name == "parallel") return std::make_unique<ParallelScheme>(sc, plan);
  if (name == "overlapped") return std::make_unique<OverlappedScheme>(sc, plan);
  if (name == "frozen-fluid")
    return std::make_unique<FrozenScheme>(sc, plan, FrozenScheme::Alone::particles, recording);
  if (name == "frozen-particles")
    return std::make_unique<FrozenScheme>(sc, plan, FrozenScheme::Alone::fluid, recording);
  throw std::invalid_argument("unknown coupling scheme '" + name +
                              "' (parallel, overlapped, frozen-fluid, frozen-particles)");
}

}  // namespace cosim::orchestrator
