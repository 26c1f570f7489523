#include "plan.h"

#include <algorithm>
#include <set>
#include <sstream>

#include "cosim/analysis/time_series.h"
#include "cosim/link/fields.h"
#include "cosim/models/registry.h"

namespace cosim::orchestrator {

models::SceneModels makeModels(const Scenario& sc) {
  return models::makeSceneModels(sc.models.choices());
}

Plan makePlan(const Scenario& sc, const models::SceneModels& m) {
  Plan p;
  std::set<std::string> needed;
  auto add = [&](const models::Model& model) {
    for (const auto& f : model.requiredFields()) needed.insert(f);
  };
  if (m.drag) add(*m.drag);
  for (const auto& f : m.forces) add(*f);
  if (m.mass_transfer) add(*m.mass_transfer);
  if (m.zone) add(*m.zone);

  p.coating = static_cast<bool>(m.mass_transfer);
  p.fluid = m.drag || !m.forces.empty() || m.mass_transfer;

  // Particle state: always position, velocity, radius (monitors, recording, locating).
  p.particles_send = {field::position, field::velocity, field::radius};
  if (p.coating) p.particles_send.push_back(field::coating_mass);

  if (m.drag) {
    p.particles_receive.push_back(field::drag_coefficient);
    p.particles_receive.push_back(field::fluid_velocity);
    needed.insert(field::fluid_velocity);
  }
  if (!m.forces.empty()) p.particles_receive.push_back(field::explicit_force);
  if (p.coating) p.particles_receive.push_back(field::coating_increment);

  if (p.fluid) {
    static const std::vector<std::string> fluid_side = {
        field::fluid_velocity,  field::voidage,           field::fluid_density,
        field::fluid_viscosity, field::pressure_gradient, field::precursor_fraction,
        field::cell_size};
    for (const auto& f : fluid_side) {
      if (needed.count(f)) p.sample_returns.push_back(f);
    }
    if (p.coating) p.fluid_advance_returns.push_back(field::precursor_removed);
    p.sample_state = {field::position, field::radius, field::velocity};
    if (m.drag) p.fluid_advance_terms.push_back(field::drag_coefficient);
    if (p.coating) p.fluid_advance_terms.push_back(field::transfer_coefficient);
    p.fluid_send = p.sample_returns;
    p.fluid_send.insert(p.fluid_send.end(), p.fluid_advance_returns.begin(),
                        p.fluid_advance_returns.end());
    p.fluid_receive = p.sample_state;
    p.fluid_receive.insert(p.fluid_receive.end(), p.fluid_advance_terms.begin(),
                           p.fluid_advance_terms.end());
  }

  if (!p.fluid && sc.participants.count("fluid")) {
    p.notes.push_back(
        "participant 'fluid' is configured but no model needs the fluid (no drag, forces or mass "
        "transfer): it is not started");
  }
  if (p.fluid && !p.coating) {
    p.notes.push_back("no mass transfer configured: no precursor species is solved or sent");
  }
  if (sc.coupling.data_path == "peer") {
    if (!p.fluid) {
      p.notes.push_back(
          "coupling.data_path: peer: no fluid participant, so no per-parcel data to exchange; the "
          "central path is used");
    } else {
      p.peer = true;
      p.notes.push_back(
          "coupling.data_path: peer: the particles sample the gas from the fluid and evaluate the "
          "laws over their parcels; cosim sends the schedule and the coating owed");
    }
  }
  checkObservables(sc, p);
  return p;
}

std::vector<std::string> timeSeriesColumns(const Plan& plan) {
  std::vector<std::string> columns = {"particle_count", "wall_seconds"};
  if (plan.coating) {
    for (const char* c : {analysis::column::precursor_in, analysis::column::precursor_out,
                          analysis::column::precursor_held, analysis::column::precursor_removed,
                          analysis::column::coated_mass}) {
      columns.push_back(c);
    }
  }
  if (plan.fluid) columns.push_back("pressure_drop");
  return columns;
}

std::vector<std::string> runTotals(const Plan& plan) {
  std::vector<std::string> totals = {"particles_inserted", "particles_deleted"};
  if (plan.coating) {
    for (const char* t :
         {"precursor_in_kg", "precursor_out_kg", "precursor_held_start_kg", "precursor_held_kg",
          "precursor_removed_kg", "coating_credited_kg", "coating_on_particles_kg",
          "coating_on_deleted_particles_kg", "coating_left_domain_kg"}) {
      totals.push_back(t);
    }
  }
  return totals;
}

void checkObservables(const Scenario& sc, const Plan& plan) {
  auto join = [](const std::vector<std::string>& v) {
    std::string out;
    for (const auto& x : v) out += (out.empty() ? "" : ", ") + x;
    return out;
  };
  for (const auto& o : sc.observables) {
    // checkQuantity has vetted the grammar: <kind>.<name>[...].
    const auto dot = o.quantity.find('.');
    const std::string kind = o.quantity.substr(0, dot);
    const auto end = o.quantity.find('.', dot + 1);
    const std::string name =
        o.quantity.substr(dot + 1, end == std::string::npos ? std::string::npos : end - dot - 1);
    std::vector<std::string> known;
    std::string what;
    if (kind == "series") {
      known = timeSeriesColumns(plan);
      what = "the run's time series has no column '" + name + "' (this scene records: ";
    } else if (kind == "totals") {
      known = runTotals(plan);
      what = "the run has no total '" + name + "' (this scene has: ";
    } else {
      known = plan.particles_send;
      what = "the particles report no field '" + name + "' in this scene (they report: ";
    }
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::ostringstream msg;
    msg << (o.where.empty() ? sc.file.string() : o.where) << ": observables." << o.name
        << ".quantity: '" << o.quantity << "': " << what << join(known) << "); check the spelling";
    throw ScenarioError(msg.str());
  }
}

}  // namespace cosim::orchestrator
