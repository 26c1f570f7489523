#include "cosim/link/peer_terms.h"

#include <cstring>

#include "cosim/link/errors.h"
#include "cosim/link/models_wire.h"
#include "cosim/models/coupling_terms.h"
#include "cosim/models/registry.h"

namespace cosim::link {

namespace {

// The wake history's byte form: a tag, the modes per parcel, the parcel count, then per parcel
// its id and its doubles in WakeBuildup::Parcel's order (the machine's own byte order: a
// checkpoint is read back by the same build).
constexpr char kWakeTag[8] = {'c', 'o', 's', 'w', 'a', 'k', 'e', '1'};
constexpr std::size_t kDoublesPerParcel = 3 + 3 * models::WakeKernel::kModes + 1 + 3 + 1;

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <class T>
T get(const std::string& in, std::size_t& at) {
  if (at + sizeof(T) > in.size())
    throw ProtocolError(std::string(kPeerTermsFile) + " ends early: the checkpoint is damaged");
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

}  // namespace

void ScenePeerTerms::configure(const wire::PeerLink& link) {
  ReceivedModels received = fromWire(link.models());
  for (const auto& plugin : received.choices.plugins)
    models::Registry::instance().loadPlugin(plugin);
  models_ = models::makeSceneModels(received.choices);
  constants_ = received.constants;
  coating_ = link.coating();
}

PeerTerms::Terms ScenePeerTerms::evaluate(const ParticleData& state, const ParticleData& samples,
                                          const std::vector<char>& lost, double dt) {
  models::CouplingTerms t =
      models::evaluateTerms(models_, coating_, constants_, state, samples, lost, dt);
  return {std::move(t.forcing), std::move(t.exchange), std::move(t.in_zone)};
}

std::string ScenePeerTerms::saveState() const {
  if (!models_.wake) return {};
  std::string out(kWakeTag, sizeof(kWakeTag));
  put<std::uint64_t>(out, models::WakeKernel::kModes);
  put<std::uint64_t>(out, models_.wake->state().size());
  for (const auto& [id, p] : models_.wake->state()) {
    put(out, id);
    for (double v : p.anchor) put(out, v);
    for (double v : p.y) put(out, v);
    put(out, p.K);
    for (double v : p.v) put(out, v);
    put(out, p.dt);
  }
  return out;
}

void ScenePeerTerms::restoreState(const std::string& bytes) {
  if (!models_.wake) return;
  if (bytes.size() < sizeof(kWakeTag) ||
      bytes.compare(0, sizeof(kWakeTag), kWakeTag, sizeof(kWakeTag)) != 0)
    throw ProtocolError(std::string(kPeerTermsFile) +
                        " is not a wake history written by this cosim: start a new run");
  std::size_t at = sizeof(kWakeTag);
  if (get<std::uint64_t>(bytes, at) != models::WakeKernel::kModes)
    throw ProtocolError(std::string(kPeerTermsFile) +
                        " holds another number of wake modes per parcel (written by another "
                        "version of undisturbed_velocity 'self_disturbance_transient'): start a "
                        "new run");
  const auto n = get<std::uint64_t>(bytes, at);
  if (n > (bytes.size() - at) / (sizeof(std::int64_t) + kDoublesPerParcel * sizeof(double)))
    throw ProtocolError(std::string(kPeerTermsFile) + " ends early: the checkpoint is damaged");
  models::WakeBuildup::State s;
  for (std::uint64_t k = 0; k < n; ++k) {
    auto& p = s[get<std::int64_t>(bytes, at)];
    for (double& v : p.anchor) v = get<double>(bytes, at);
    for (double& v : p.y) v = get<double>(bytes, at);
    p.K = get<double>(bytes, at);
    for (double& v : p.v) v = get<double>(bytes, at);
    p.dt = get<double>(bytes, at);
  }
  if (at != bytes.size())
    throw ProtocolError(std::string(kPeerTermsFile) + " is longer than its parcels: damaged");
  models_.wake->restore(std::move(s));
}

}  // namespace cosim::link
