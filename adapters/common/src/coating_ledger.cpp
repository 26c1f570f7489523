#include "cosim/link/coating_ledger.h"

#include "cosim/link/fields.h"

namespace cosim::link {

namespace {
double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}
}  // namespace

void CoatingLedger::start(const ParticleData& initial) {
  b_.coating_initial = sum(initial.get(field::coating_mass));
}

void CoatingLedger::owe(const ParticleData& fr) {
  if (!fr.has(field::precursor_removed)) return;
  const auto& rm = fr.get(field::precursor_removed);
  for (std::size_t i = 0; i < fr.size(); ++i) {
    if (rm[i] != 0.0) {
      pending_[fr.ids[i]] += rm[i];
      b_.removed += rm[i];
    }
  }
}

void CoatingLedger::addFlows(double in, double out) {
  b_.in += in;
  b_.out += out;
}

void CoatingLedger::pay(ParticleData& forcing) {
  auto& inc = forcing.field(field::coating_increment);
  for (std::size_t i = 0; i < forcing.size(); ++i) {
    auto it = pending_.find(forcing.ids[i]);
    if (it != pending_.end()) {
      inc[i] = it->second;
      b_.credited += it->second;
      in_flight_[it->first] += it->second;
      pending_.erase(it);
    }
  }
}

ParticleData CoatingLedger::payOwed() {
  ParticleData owed;
  std::vector<double> increment;
  owed.ids.reserve(pending_.size());
  increment.reserve(pending_.size());
  for (const auto& [id, m] : pending_) {
    owed.ids.push_back(id);
    increment.push_back(m);
    b_.credited += m;
  }
  if (in_flight_.empty()) {  // the usual case: what is paid is in flight as it was owed
    in_flight_.swap(pending_);
  } else {
    for (const auto& [id, m] : pending_) in_flight_[id] += m;
  }
  pending_.clear();
  owed.put(field::coating_increment, std::move(increment));
  return owed;
}

void CoatingLedger::undelivered() {
  for (const auto& [id, m] : in_flight_) {
    pending_[id] += m;
    b_.credited -= m;
  }
  in_flight_.clear();
}

void CoatingLedger::leave(const std::vector<std::int64_t>& deleted_ids,
                          double deleted_coating_mass) {
  for (auto id : deleted_ids) {
    auto it = pending_.find(id);
    if (it != pending_.end()) {
      b_.left_domain += it->second;
      b_.any_left = true;
      b_.credited += it->second;
      pending_.erase(it);
    }
  }
  b_.deleted_coating += deleted_coating_mass;
}

void CoatingLedger::takeParticleTotals(const Balance& particles, double credited_including_owed) {
  b_.removed = particles.removed;
  b_.credited = particles.credited;
  b_.left_domain = particles.left_domain;
  b_.any_left = particles.any_left;
  reported_including_owed_ = credited_including_owed;
}

double CoatingLedger::creditedIncludingOwed() const {
  if (reported_including_owed_) return *reported_including_owed_;
  double c = b_.credited;
  for (const auto& [id, dm] : pending_) c += dm;
  return c;
}

ParticleData CoatingLedger::held(const ParticleData& state) const {
  if (pending_.empty() || !state.has(field::coating_mass)) return state;
  ParticleData h = state;
  auto& m = h.field(field::coating_mass);
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (auto it = pending_.find(h.ids[i]); it != pending_.end()) m[i] += it->second;
  }
  return h;
}

void CoatingLedger::totals(const ParticleData& final_state,
                           std::map<std::string, double>& out) const {
  if (b_.any_left) out["coating_left_domain_kg"] = b_.left_domain;
  out["precursor_in_kg"] = b_.in;
  out["precursor_out_kg"] = b_.out;
  out["precursor_held_start_kg"] = b_.held_start;
  out["precursor_held_kg"] = b_.held;
  out["precursor_removed_kg"] = b_.removed;
  out["coating_credited_kg"] = b_.credited;
  out["coating_on_particles_kg"] =
      sum(final_state.get(field::coating_mass)) - b_.coating_initial + b_.deleted_coating;
  if (b_.deleted_coating != 0.0) out["coating_on_deleted_particles_kg"] = b_.deleted_coating;
}

void CoatingLedger::restore(const Balance& b, std::map<std::int64_t, double> pending) {
  b_ = b;
  pending_ = std::move(pending);
}

}  // namespace cosim::link
