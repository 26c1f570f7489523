#include "cosim/models/registry.h"

#include <dlfcn.h>

#include <sstream>

#include "cosim/models/drag/undisturbed_velocity.h"

namespace cosim::models {

void registerBuiltins(Registry& r);  // builtins.cpp

Registry& Registry::instance() {
  static Registry r;
  return r;
}

Registry::Registry() { registerBuiltins(*this); }

namespace {
template <class M>
std::vector<std::string> namesOf(const M& m) {
  std::vector<std::string> v;
  v.reserve(m.size());
  for (const auto& [k, f] : m) v.push_back(k);
  return v;
}

template <class T, class M>
std::unique_ptr<T> make(const M& m, const std::string& kind, const std::string& name,
                        const Parameters& p) {
  auto it = m.find(name);
  if (it == m.end()) {
    std::ostringstream os;
    os << "unknown " << kind << " '" << name << "'; known: ";
    bool first = true;
    for (const auto& [k, f] : m) {
      os << (first ? "" : ", ") << k;
      first = false;
    }
    os << " (or load a plugin that provides it: models.plugins)";
    throw ModelError(os.str());
  }
  return it->second(p);
}
}  // namespace

// `undisturbed_velocity` is handled here, for every law (built-in or plugin): the law itself
// never sees the key.
std::unique_ptr<DragLaw> Registry::makeDrag(const std::string& n, const Parameters& p) const {
  const std::string key = "undisturbed_velocity";
  const std::string gain = "self_disturbance_gain", offset = "self_disturbance_offset";
  // The calibration describes the gas solver, so an explicit `none` keeps it (a scene calibrated
  // once can be run without the correction from the command line); given without any choice it
  // is refused: the correction it calibrates is off by default.
  if (!p.has(key) && (p.has(gain) || p.has(offset))) {
    throw ModelError(p.owner() + ": " + (p.has(gain) ? gain : offset) +
                     " calibrates the undisturbed gas velocity, which is off unless " + key +
                     " is 'self_disturbance' or 'self_disturbance_transient': set one of them "
                     "(or 'none' to keep the calibration and run without it), or remove the key");
  }
  if (!p.has(key)) return make<DragLaw>(drag_, "drag law", n, p);
  const std::string choice = p.text(key);
  const double gamma =
      p.has(gain) ? p.number(gain, CalibrationBounds::kMinGain, CalibrationBounds::kMaxGain) : 1.0;
  const double beta =
      p.has(offset) ? p.number(offset, CalibrationBounds::kMinOffset, CalibrationBounds::kMaxOffset)
                    : 0.0;
  auto law =
      make<DragLaw>(drag_, "drag law", n,
                    p.without(key, p.owner()).without(gain, p.owner()).without(offset, p.owner()));
  if (choice == "none") return law;
  if (choice == "self_disturbance") {
    return std::make_unique<UndisturbedVelocityDrag>(
        std::move(law), UndisturbedVelocityDrag::Estimate::steady, gamma, beta);
  }
  if (choice == "self_disturbance_transient") {
    return std::make_unique<UndisturbedVelocityDrag>(
        std::move(law), UndisturbedVelocityDrag::Estimate::transient, gamma, beta);
  }
  std::string known;
  for (const auto& k : undisturbedVelocityNames()) known += (known.empty() ? "" : ", ") + k;
  throw ModelError(p.owner() + ": " + key + " '" + choice + "' is not known (known: " + known +
                   ")");
}
std::unique_ptr<ForceModel> Registry::makeForce(const std::string& n, const Parameters& p) const {
  return make<ForceModel>(force_, "force model", n, p);
}
std::unique_ptr<MassTransferLaw> Registry::makeMassTransfer(const std::string& n,
                                                            const Parameters& p) const {
  return make<MassTransferLaw>(mass_, "mass transfer law", n, p);
}
std::unique_ptr<CoatingZone> Registry::makeZone(const std::string& n, const Parameters& p) const {
  return make<CoatingZone>(zone_, "coating zone shape", n, p);
}

std::vector<std::string> Registry::dragNames() const { return namesOf(drag_); }
std::vector<std::string> Registry::forceNames() const { return namesOf(force_); }
std::vector<std::string> Registry::massTransferNames() const { return namesOf(mass_); }
std::vector<std::string> Registry::zoneNames() const { return namesOf(zone_); }

void Registry::loadPlugin(const std::string& path) {
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    throw ModelError("cannot load model plugin '" + path + "': " + dlerror());
  }
  using Fn = void (*)(Registry&);
  auto* fn = reinterpret_cast<Fn>(dlsym(handle, "cosim_register_models"));
  if (fn == nullptr) {
    throw ModelError("model plugin '" + path +
                     "' has no function cosim_register_models (declare it extern \"C\")");
  }
  fn(*this);
}

}  // namespace cosim::models
