#include "cosim/link/peer_link.h"

#include <arpa/inet.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/particle_wire.h"
#include "cosim/link/session.h"

namespace cosim::link {

namespace {

using Clock = std::chrono::steady_clock;
constexpr Millis kSlice{200};  // how often a wait for the peer looks at the orchestrator

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void fillHeader(wire::Header* h, const PeerIdentity& who, std::uint64_t step, double time) {
  h->set_protocol_version(wire::PROTOCOL_VERSION);
  h->set_run_id(who.run_id);
  h->set_participant(who.name);
  h->set_step(step);
  h->set_time(time);
  h->set_token(who.token);
}

// A message of this run (version, run id, token): anything else is not from the peer and is
// dropped unread, as the orchestrator drops it.
bool fromThisRun(const wire::Envelope& e, const PeerIdentity& who) {
  const auto& h = e.header();
  return h.protocol_version() == wire::PROTOCOL_VERSION && h.run_id() == who.run_id &&
         h.token() == who.token;
}

// The peer's message for this step, of the expected kind; ProtocolError otherwise.
void checkPeerMessage(const wire::Envelope& e, wire::Envelope::BodyCase expected,
                      std::uint64_t step, const std::string& from) {
  if (e.has_error())
    throw PeerError("the " + from + " participant stopped: " + e.error().message());
  if (e.header().step() != step)
    throw ProtocolError("the " + from + " participant sent a message for step " +
                        std::to_string(e.header().step()) + " during step " + std::to_string(step) +
                        " (coupling.data_path: peer)");
  if (expected != wire::Envelope::BODY_NOT_SET && e.body_case() != expected)
    throw ProtocolError("the " + from + " participant sent an unexpected message during step " +
                        std::to_string(step) + " (coupling.data_path: peer)");
}

std::string silence(const std::string& from, int timeout_ms) {
  return "the " + from + " participant sent nothing over the peer link for " +
         std::to_string(timeout_ms / 1000) + " s; giving up";
}

// The first parcel and field of `d` that is not a finite number, as an error, or "".
std::string firstNonFinite(const ParticleData& d) {
  for (const auto& [name, v] : d.fields()) {
    const unsigned c = field::components(name);
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i]))
        return "field '" + name + "' of parcel " + std::to_string(d.ids[i / c]) + " is " +
               std::to_string(v[i]);
  }
  return {};
}

// The parcels of `d` with any value that is not 0, in their order: of the fluid's per-parcel
// results (precursor_removed) only the parcels the coating sink acted on, a few per cent of the
// bed. A value that is not a number is kept, for the particles' check to name.
ParticleData nonzeroParcels(const ParticleData& d) {
  std::vector<char> keep(d.size(), 0);
  for (const auto& [name, v] : d.fields()) {
    const unsigned c = field::components(name);
    for (std::size_t i = 0; i < v.size(); ++i)
      if (v[i] != 0.0) keep[i / c] = 1;
  }
  ParticleData out;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (keep[i] != 0) out.ids.push_back(d.ids[i]);
  for (const auto& [name, v] : d.fields()) {
    const unsigned c = field::components(name);
    std::vector<double> kept;
    kept.reserve(out.size() * c);
    for (std::size_t i = 0; i < d.size(); ++i)
      if (keep[i] != 0) kept.insert(kept.end(), v.begin() + i * c, v.begin() + (i + 1) * c);
    out.put(name, std::move(kept));
  }
  return out;
}

}  // namespace

// The local IPv4 address this host reaches `endpoint` (tcp://HOST:PORT) from: the address of the
// network the orchestrator is on, which the particles reach too (no packet is sent).
static std::string localAddressToward(const std::string& endpoint) {
  const std::string rest = endpoint.substr(std::string("tcp://").size());
  const auto colon = rest.rfind(':');
  if (colon == std::string::npos)
    throw ProtocolError("the orchestrator's address " + endpoint + " has no port");
  const std::string host = rest.substr(0, colon), port = rest.substr(colon + 1);
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  if (getaddrinfo(host.c_str(), port.c_str(), &hints, &found) != 0 || found == nullptr)
    throw ProtocolError("cannot resolve the orchestrator's host '" + host +
                        "' to an IPv4 address for the peer link (coupling.data_path: peer)");
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in local{};
  socklen_t length = sizeof(local);
  const bool ok = fd >= 0 && ::connect(fd, found->ai_addr, found->ai_addrlen) == 0 &&
                  getsockname(fd, reinterpret_cast<sockaddr*>(&local), &length) == 0;
  const int err = errno;
  if (fd >= 0) close(fd);
  freeaddrinfo(found);
  if (!ok)
    throw ProtocolError("cannot find the local address toward " + endpoint +
                        " for the peer link: " + std::strerror(err));
  char text[INET_ADDRSTRLEN] = {0};
  inet_ntop(AF_INET, &local.sin_addr, text, sizeof(text));
  return text;
}

// ---- the fluid's side ---------------------------------------------------------------------------

FluidPeer::FluidPeer(const wire::PeerLink& link, PeerIdentity who, int timeout_ms,
                     const std::string& orchestrator)
    : who_(std::move(who)), timeout_ms_(timeout_ms) {
  HubSecurity security;
  if (!link.fluid_secret().empty()) {
    security.server = {link.fluid_public(), link.fluid_secret()};
    security.clients.insert(link.particles_public());
  }
  if (link.bind() == "tcp") {
    if (orchestrator.rfind("tcp://", 0) != 0)
      throw ProtocolError("Welcome.peer.bind 'tcp' but the orchestrator is at " + orchestrator);
    hub_ = std::make_unique<Hub>("tcp://" + localAddressToward(orchestrator) + ":*", security);
  } else if (link.bind().rfind("ipc://", 0) == 0) {
    hub_ = std::make_unique<Hub>(link.bind(), security);
    if (!link.shared_memory().empty())  // the per-parcel values through shared memory
      shared_ = std::make_unique<SharedArrays>(link.shared_memory(), "fluid");
  } else {
    throw ProtocolError("Welcome.peer.bind '" + link.bind() +
                        "': expected an ipc:// address or 'tcp' (coupling.data_path: peer)");
  }
}

wire::Envelope FluidPeer::await(wire::Envelope::BodyCase expected, std::uint64_t step,
                                const PeerWatch& watch) {
  const auto deadline = Clock::now() + Millis(timeout_ms_);
  while (Clock::now() < deadline) {
    auto in = hub_->receive(kSlice);
    if (!in) {
      watch();
      continue;
    }
    if (!in->envelope || !fromThisRun(*in->envelope, who_)) continue;
    if (!route_.empty() && in->peer != route_) continue;  // one particle rank: the first one
    route_ = in->peer;
    checkPeerMessage(*in->envelope, expected, step, "particles");
    if (shared_) shared_->received();
    return std::move(*in->envelope);
  }
  throw TimeoutError(silence("particles", timeout_ms_));
}

void FluidPeer::send(wire::Envelope& env, std::uint64_t step, double time) {
  fillHeader(env.mutable_header(), who_, step, time);
  hub_->send(route_, env);
}

void FluidPeer::interval(Solver& solver, const wire::Advance& cmd, std::uint64_t step, double time,
                         wire::Advanced& out, const PeerWatch& watch) {
  // The gas at the parcels, unless the particles use the samples of the last interval's end
  wire::Envelope sample = await(wire::Envelope::BODY_NOT_SET, step, watch);
  if (!sample.has_sample() && !sample.has_advance())
    throw ProtocolError("the particles participant sent an unexpected message during step " +
                        std::to_string(step) + " (coupling.data_path: peer)");
  if (sample.has_sample()) {
    wire::Envelope samples;
    sampleInto(solver, fromWire(sample.sample().particles(), sharedIn()),
               *samples.mutable_samples(), sharedOut());
    send(samples, step, time);
  }
  // The exchange terms (the particles sent them at once when they had the gas sampled ahead)
  wire::Envelope terms =
      sample.has_advance() ? std::move(sample) : await(wire::Envelope::kAdvance, step, watch);
  // The solver gets the terms as on the central path: in the Advance (which an adapter with
  // several ranks broadcasts as it is) and as ParticleData; moved into the Advance, not copied,
  // when they came in the message
  const ParticleData exchange = fromWire(terms.advance().terms(), sharedIn());
  wire::Advance with_terms = cmd;
  if (shared_)  // the values came through shared memory: into the Advance, as the wire has them
    toWire(exchange, *with_terms.mutable_terms());
  else
    with_terms.mutable_terms()->Swap(terms.mutable_advance()->mutable_terms());
  ParticleData results;
  solver.advance(with_terms, exchange, out, results);
  wire::Envelope advanced;
  toWire(nonzeroParcels(results), *advanced.mutable_advanced()->mutable_state(), sharedOut());
  if (terms.advance().has_sample_ahead())  // the next interval's samples, where they will be
    sampleInto(solver, predictedAt(fromWire(terms.advance().sample_ahead(), sharedIn()), cmd.dt()),
               *advanced.mutable_advanced()->mutable_ahead(), sharedOut());
  send(advanced, step, time);
}

// ---- the particles' side ------------------------------------------------------------------------

ParticlePeer::ParticlePeer(const wire::PeerLink& link, const wire::Welcome& welcome,
                           PeerTerms& terms, PeerIdentity who, int timeout_ms)
    : link_(link),
      sample_fields_(link.sample_state().begin(), link.sample_state().end()),
      forcing_fields_(welcome.receive().begin(), welcome.receive().end()),
      terms_(terms),
      who_(std::move(who)),
      timeout_ms_(timeout_ms),
      start_time_(welcome.start_time()),
      dt_(welcome.cfd_dt()) {
  terms_.configure(link_);
  if (link_.coating() && link_.zone_passes()) passes_.emplace();
  if (!link_.shared_memory().empty() && !link_.connect().empty())  // one machine: ipc://
    shared_ = std::make_unique<SharedArrays>(link_.shared_memory(), "particles");
  if (!link.connect().empty()) connect(link.connect());
}

void ParticlePeer::checkState(const ParticleData& state) const {
  if (const auto bad = firstNonFinite(state); !bad.empty())
    throw ProtocolError("the particles' state after the interval: " + bad);
  const double limit = link_.max_particle_speed();
  if (limit <= 0 || !state.has(field::velocity)) return;
  const auto& v = state.get(field::velocity);
  for (std::size_t i = 0; i < state.size(); ++i) {
    const double speed =
        std::sqrt(v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
    if (speed > limit)
      throw ProtocolError("parcel " + std::to_string(state.ids[i]) + " moves at " +
                          std::to_string(speed) + " m/s, faster than checks.max_particle_speed " +
                          std::to_string(limit) +
                          " m/s: the DEM is unstable (its time step or the coupling forces); "
                          "see docs/when-things-go-wrong.md");
  }
}

std::string ParticlePeer::aheadBytes() const {
  if (!ahead_ || !ahead_sent_) return {};
  wire::FieldSet sent = *ahead_sent_;
  for (auto& f : *sent.mutable_fields()) {  // values this side put in its shared memory
    if (!f.has_shared()) continue;
    const std::size_t n = static_cast<std::size_t>(sent.ids_size()) * f.components();
    const double* v = shared_ ? shared_->out.at(f.shared(), n) : nullptr;
    if (v == nullptr)
      throw ProtocolError("the parcels the gas was sampled ahead at are no longer in " +
                          f.shared().region() + " (a bug: report it with the scenario)");
    f.mutable_values()->Assign(v, v + n);
    f.clear_shared();
  }
  wire::FieldSet at;
  toWire(predictedAt(fromWire(sent), ahead_dt_), at);
  return at.SerializeAsString();
}

void ParticlePeer::restoreAhead(const std::string& bytes) {
  wire::FieldSet at;
  if (!at.ParseFromString(bytes))
    throw ProtocolError(std::string(kPeerAheadFile) +
                        " is not a FieldSet: the checkpoint is "
                        "damaged");
  resume_at_ = fromWire(at);
}

void ParticlePeer::connect(const std::string& endpoint) {
  if (endpoint == connected_to_) return;
  if (endpoint.rfind("ipc://", 0) != 0 && endpoint.rfind("tcp://", 0) != 0)
    throw ProtocolError("the fluid's peer address '" + endpoint +
                        "' is neither ipc:// nor tcp:// (coupling.data_path: peer)");
  CurveClientKeys keys;
  if (!link_.particles_secret().empty())
    keys = {link_.fluid_public(), {link_.particles_public(), link_.particles_secret()}};
  channel_ = std::make_unique<Channel>(endpoint, "", keys);
  connected_to_ = endpoint;
}

wire::Envelope ParticlePeer::request(wire::Envelope& env, wire::Envelope::BodyCase expected,
                                     std::uint64_t step, double time, const PeerWatch& watch) {
  if (env.body_case() != wire::Envelope::BODY_NOT_SET) {
    fillHeader(env.mutable_header(), who_, step, time);
    channel_->send(env);
  }
  if (expected == wire::Envelope::BODY_NOT_SET) return {};
  const auto deadline = Clock::now() + Millis(timeout_ms_);
  while (Clock::now() < deadline) {
    auto in = channel_->receive(kSlice);
    if (!in) {
      watch();
      continue;
    }
    if (!fromThisRun(*in, who_)) continue;
    checkPeerMessage(*in, expected, step, "fluid");
    if (shared_) shared_->received();
    return std::move(*in);
  }
  throw TimeoutError(silence("fluid", timeout_ms_));
}

wire::Samples ParticlePeer::gasAtParcels(std::uint64_t step, double time, const PeerWatch& watch) {
  auto sampleAt = [&](const ParticleData& at) {
    wire::Envelope sample;
    toWire(at, *sample.mutable_sample()->mutable_particles(), sample_fields_, sharedOut());
    return std::move(
        *request(sample, wire::Envelope::kSamples, step, time, watch).mutable_samples());
  };
  if (resume_at_) {  // the first interval after a resume: the gas where it was sampled ahead
    ahead_ = sampleAt(*resume_at_);
    resume_at_.reset();
  }
  std::optional<wire::Samples> got;
  if (ahead_ && ahead_->lost_ids_size() == 0 &&
      static_cast<std::size_t>(ahead_->at_particles().ids_size()) == state_.ids.size() &&
      std::equal(state_.ids.begin(), state_.ids.end(), ahead_->at_particles().ids().begin()))
    got = std::move(ahead_);
  ahead_.reset();
  return got ? std::move(*got) : sampleAt(state_);
}

void ParticlePeer::payOwed(ParticleData& forcing) {
  auto& inc = forcing.field(field::coating_increment);
  const ParticleData owed = ledger_.payOwed();  // in id order, as the orchestrator's would be
  if (owed.ids.empty()) return;
  // No index of every parcel built on every step: the owed parcels (a few per cent) look
  // themselves up among the parcels when these are in id order (LIGGGHTS' state is), else each
  // parcel among the owed ones
  const auto& m = owed.get(field::coating_increment);
  const auto& ids = forcing.ids;
  if (std::is_sorted(ids.begin(), ids.end())) {
    for (std::size_t j = 0; j < owed.size(); ++j) {
      const auto it = std::lower_bound(ids.begin(), ids.end(), owed.ids[j]);
      if (it != ids.end() && *it == owed.ids[j])
        inc[static_cast<std::size_t>(it - ids.begin())] = m[j];
    }
    return;
  }
  for (std::size_t i = 0; i < forcing.size(); ++i) {
    const auto it = std::lower_bound(owed.ids.begin(), owed.ids.end(), ids[i]);
    if (it != owed.ids.end() && *it == ids[i])
      inc[i] = m[static_cast<std::size_t>(it - owed.ids.begin())];
  }
}

ParticleData ParticlePeer::removal(const wire::Advanced& results) const {
  ParticleData taken;
  const ParticleData fr = fromWire(results.state(), sharedIn());
  if (!fr.has(field::precursor_removed)) return taken;
  // The parcels that took any (the fluid sends no zeros), in the order they were sent
  std::size_t j = 0;
  for (const auto id : fr.ids) {
    while (j < state_.ids.size() && state_.ids[j] != id) ++j;
    if (j == state_.ids.size())
      throw ProtocolError("the fluid returned results for parcel " + std::to_string(id) +
                          ", which it was not sent, or not in the order it was sent "
                          "(coupling.data_path: peer)");
    ++j;
  }
  const auto& rm = fr.get(field::precursor_removed);
  std::vector<double> values;
  for (std::size_t i = 0; i < fr.size(); ++i) {
    if (rm[i] == 0.0) continue;
    if (!std::isfinite(rm[i]))
      throw ProtocolError("the fluid's precursor_removed of parcel " + std::to_string(fr.ids[i]) +
                          " is " + std::to_string(rm[i]));
    taken.ids.push_back(fr.ids[i]);
    values.push_back(rm[i]);
  }
  taken.put(field::precursor_removed, std::move(values));
  return taken;
}

// The order of the orchestrator's central path: the membership at the interval's start, the
// payment delivered, the uptake owed and added to the passes, then the parcels that left.
void ParticlePeer::book(const std::vector<char>& in_zone, const ParticleData& taken,
                        const wire::Advanced& out, double start, double end) {
  if (passes_) passes_->update(start, state_.ids, in_zone);
  ledger_.delivered();
  ledger_.owe(taken);
  if (passes_) passes_->credit(taken);
  const std::vector<std::int64_t> deleted(out.deleted_ids().begin(), out.deleted_ids().end());
  ledger_.leave(deleted, out.particles().deleted_coating_mass());
  if (passes_ && !deleted.empty()) passes_->leave(deleted, end);
}

void ParticlePeer::totals(wire::PeerLedger& l) const {
  const auto& b = ledger_.balance();
  l.set_removed(b.removed);
  l.set_credited(b.credited);
  l.set_credited_including_owed(ledger_.creditedIncludingOwed());
  l.set_left_domain(b.left_domain);
  l.set_any_left(b.any_left);
  if (passes_) l.set_coating_outside(passes_->coatingOutsidePasses());
}

void ParticlePeer::report(wire::PeerInterval& account) {
  auto* l = account.mutable_ledger();
  totals(*l);
  if (!passes_) return;
  for (const auto& p : passes_->takeClosed()) toWire(p, *l->add_passes());
}

ParticleData ParticlePeer::zeroLengthTerms(const wire::Advance& cmd) {
  ParticleData terms;
  if (!link_.coating() || !cmd.pay_owed()) return terms;
  terms.ids = state_.ids;
  payOwed(terms);
  return terms;
}

void ParticlePeer::afterZeroLength(const wire::Advance& cmd, std::uint64_t step,
                                   wire::Advanced& out) {
  if (!link_.coating()) return;
  if (cmd.pay_owed()) ledger_.delivered();
  if (cmd.close_passes() && passes_) passes_->close(stepTime(start_time_, dt_, step));
  report(*out.mutable_peer());
}

std::string ParticlePeer::ledgerBytes() const {
  wire::PeerLedgerState s;
  totals(*s.mutable_totals());
  for (const auto& [id, m] : ledger_.pending()) {
    s.add_owed_ids(id);
    s.add_owed(m);
  }
  if (passes_) {
    const auto st = passes_->state();
    for (const auto& [id, p] : st.open)
      toWire(ZonePass{id, p.entry_time, p.entry_time, p.coating, p.at_start, ZonePass::Exit::left},
             *s.add_open());
    s.set_passes_started(st.started);
  }
  return s.SerializeAsString();
}

void ParticlePeer::restoreLedger(const std::string& bytes) {
  wire::PeerLedgerState s;
  if (!s.ParseFromString(bytes) || s.owed_ids_size() != s.owed_size())
    throw ProtocolError(std::string(kPeerLedgerFile) +
                        " is not a PeerLedgerState: the checkpoint is damaged");
  std::map<std::int64_t, double> owed;
  for (int i = 0; i < s.owed_ids_size(); ++i) owed[s.owed_ids(i)] = s.owed(i);
  ledger_.restore(fromWire(s.totals()), std::move(owed));
  if (passes_) {
    ZonePassTracker::State st;
    for (const auto& r : s.open()) {
      const ZonePass p = fromWire(r);
      st.open[p.parcel_id] = {p.entry_time, p.coating, p.at_start};
    }
    st.coating_outside = s.totals().coating_outside();
    st.started = s.passes_started();
    passes_->restore(std::move(st));
  }
}

void ParticlePeer::interval(Solver& solver, const wire::Advance& cmd, std::uint64_t step,
                            double time, wire::Advanced& out, ParticleData& state,
                            const PeerWatch& watch) {
  if (!channel_)
    throw ProtocolError(
        "an interval of coupling.data_path: peer before the fluid's peer address came "
        "(Advance.peer_connect)");
  auto* account = out.mutable_peer();
  // The gas at the parcels
  auto t0 = Clock::now();
  const wire::Samples answer = gasAtParcels(step, time, watch);
  const ParticleData samples = fromWire(answer.at_particles(), sharedIn());
  if (samples.ids != state_.ids)
    throw ProtocolError(
        "the fluid returned samples for other parcels than it was sent (ids differ; "
        "coupling.data_path: peer)");
  if (const auto bad = firstNonFinite(samples); !bad.empty())
    throw ProtocolError("the fluid's samples: " + bad);
  std::vector<char> lost(state_.size(), 0);
  if (answer.lost_ids_size() > 0) {
    const auto idx = state_.index();
    for (auto id : answer.lost_ids())
      if (auto it = idx.find(id); it != idx.end()) lost[it->second] = 1;
    account->mutable_lost_ids()->Assign(answer.lost_ids().begin(), answer.lost_ids().end());
  }
  account->set_sample_seconds(secondsSince(t0));

  // The laws; the coating the orchestrator says is owed joins the forcing
  t0 = Clock::now();
  PeerTerms::Terms terms = terms_.evaluate(state_, samples, lost, cmd.dt());
  if (link_.coating()) payOwed(terms.forcing);
  if (const auto bad = firstNonFinite(terms.forcing); !bad.empty())
    throw ProtocolError("the coupling laws' forcing: " + bad);
  account->set_models_seconds(secondsSince(t0));

  // The fluid's terms, then both advance
  wire::Envelope fluid_terms;
  auto* fa = fluid_terms.mutable_advance();
  fa->set_dt(cmd.dt());
  fa->set_substeps(1);
  toWire(terms.exchange, *fa->mutable_terms(),
         std::vector<std::string>(link_.exchange().begin(), link_.exchange().end()), sharedOut());
  ahead_sent_.reset();
  if (link_.sample_ahead())  // the gas where the parcels will be, sampled in the fluid's step
    toWire(state_, *fa->mutable_sample_ahead(), sample_fields_, sharedOut());
  request(fluid_terms, wire::Envelope::BODY_NOT_SET, step, time, watch);
  if (fa->has_sample_ahead()) {  // kept, not copied, for a checkpoint's aheadBytes()
    ahead_sent_.emplace();
    ahead_sent_->Swap(fa->mutable_sample_ahead());
    ahead_dt_ = cmd.dt();
  }
  if (cmd.report_terms()) {
    toWire(samples, *account->mutable_samples());
    toWire(terms.forcing, *account->mutable_forcing());
  }
  // The solver gets the forcing as on the central path: in the Advance (which an adapter with
  // several ranks broadcasts as it is) and as its terms, moved out of the laws' result
  wire::Advance with_forcing = cmd;
  with_forcing.clear_report_terms();
  toWire(terms.forcing, *with_forcing.mutable_terms(), forcing_fields_);
  const ParticleData forcing = std::move(terms.forcing).select(forcing_fields_);
  solver.advance(with_forcing, forcing, out, state);

  // What the fluid's step took from the gas, parcel by parcel
  t0 = Clock::now();
  wire::Envelope none;
  wire::Envelope results = request(none, wire::Envelope::kAdvanced, step, time, watch);
  account->set_fluid_seconds(secondsSince(t0));
  if (results.advanced().has_ahead())  // kept for the next interval: taken, not copied
    ahead_ = std::move(*results.mutable_advanced()->mutable_ahead());
  if (link_.coating()) {
    book(terms.in_zone, removal(results.advanced()), out, stepTime(start_time_, dt_, step - 1),
         stepTime(start_time_, dt_, step));
    report(*account);
  }
}

}  // namespace cosim::link
