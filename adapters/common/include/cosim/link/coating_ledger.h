// The coating ledger (docs/physics.md, "coating credit"): the fluid reports after each interval
// how much precursor every parcel removed; that mass is owed to the parcel as coating and paid
// with the next Advance (or a final flush of zero length). The ledger keeps what is owed, the
// precursor balance of the run (in, out, held, removed, credited) and the credit that leaves with
// deleted particles. Its whole state is in Balance and the pending map: saved and restored as is.
//
// Who keeps it: on the central data path the orchestrator, parcel by parcel. On the peer path
// (coupling.data_path: peer) the particle session keeps the parcels' part (what is owed to
// each, paid and taken up: the same class, the same sums in the same order) and reports its
// running totals; the orchestrator's ledger then holds the gas's flows and those totals
// (takeParticleTotals), so that its work does not grow with the parcels in the zone.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cosim/link/particle_data.h"

namespace cosim::link {

class CoatingLedger {
 public:
  struct Balance {
    double in = 0.0;               // precursor into the gas through the inlets [kg]
    double out = 0.0;              // through the outlets [kg]
    double held = 0.0;             // in the gas now [kg]
    double held_start = 0.0;       // in the gas at the start [kg]
    double removed = 0.0;          // taken up by parcels (owed or paid) [kg]
    double credited = 0.0;         // paid to parcels, or left with deleted ones [kg]
    double left_domain = 0.0;      // owed to parcels that were deleted before payment [kg]
    bool any_left = false;         // a deleted parcel took credit with it
    double deleted_coating = 0.0;  // coating carried out by deleted parcels [kg]
    double coating_initial = 0.0;  // coating on the parcels at the start [kg]
  };

  // The parcels' coating at the start.
  void start(const ParticleData& initial);
  // The fluid's per-parcel results of one interval: precursor_removed is now owed.
  void owe(const ParticleData& fluid_results);
  // The fluid's precursor balance after an interval (running totals for in/out, the current
  // mass for held).
  void addFlows(double in, double out);
  void setHeld(double held) { b_.held = held; }
  void setHeldAtStart(double held) { b_.held_start = held; }
  // Pays what is owed to the parcels in `forcing` into its coating_increment field. The payment
  // is in flight until the particles confirm the step (delivered()); a step that never completes
  // (the particle solver gone) gives it back to what is owed (undelivered()).
  void pay(ParticleData& forcing);
  // The same payment for the peer data path, where the particles evaluate their own forcing:
  // everything owed, as a coating_increment of only the parcels owed any (in id order). Equal to
  // pay() over the parcels' state, since what is owed belongs to parcels that are there (a
  // deleted parcel's credit leaves with it, leave()).
  ParticleData payOwed();
  void delivered() { in_flight_.clear(); }
  void undelivered();
  // Parcels that left the domain take what they were owed with them.
  void leave(const std::vector<std::int64_t>& deleted_ids, double deleted_coating_mass);
  // Coating paid plus owed: what the parcels hold once the ledger is settled.
  double creditedIncludingOwed() const;
  // The particle state with what is owed added: what the parcels hold at this time.
  ParticleData held(const ParticleData& state) const;

  // The balance totals for the summary, with the coating now on `final_state`.
  void totals(const ParticleData& final_state, std::map<std::string, double>& out) const;

  // The peer path: the particles' running totals of their part of the ledger (removed,
  // credited, left_domain, any_left) and their coating paid plus owed, which
  // creditedIncludingOwed() then returns. The orchestrator's own pending stays empty.
  void takeParticleTotals(const Balance& particles, double credited_including_owed);
  // The peer path: the coating carried out by parcels deleted in an interval (the particles'
  // report), which the orchestrator adds up as on the central path.
  void addDeletedCoating(double mass) { b_.deleted_coating += mass; }

  const Balance& balance() const { return b_; }
  const std::map<std::int64_t, double>& pending() const { return pending_; }
  // Restores a saved state.
  void restore(const Balance& b, std::map<std::int64_t, double> pending);

 private:
  Balance b_;
  std::map<std::int64_t, double> pending_;    // parcel id -> precursor removed, not yet paid
  std::map<std::int64_t, double> in_flight_;  // paid with the step under way, not yet delivered
  std::optional<double> reported_including_owed_;  // the peer path: the particles' figure
};

}  // namespace cosim::link
