// cosim-analytic-fluid: a prescribed fluid. Velocity uniform or a parabolic pipe profile; density,
// viscosity, voidage and precursor mass fraction given; hydrostatic pressure gradient. It does not
// react to the particles (one-way), which makes analytic reference solutions exact. With coating,
// it is an infinite precursor reservoir: each particle removes k * Y * dt per step, and the same
// mass is fed in, so the balance in - out - accumulation - removed closes exactly.
#include <cmath>
#include <iostream>

#include "analytic_main.h"
#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/session.h"
#include "cosim/util/adapter_options.h"
#include "cosim/util/errors.h"

namespace cosim::analytic {

class AnalyticFluid final : public link::Solver {
 public:
  link::Capabilities capabilities() const override {
    link::Capabilities c;
    c.role = wire::FLUID;
    c.adapter = "analytic-fluid";
    c.provides = {field::fluid_velocity,  field::voidage,           field::fluid_density,
                  field::fluid_viscosity, field::pressure_gradient, field::precursor_fraction,
                  field::cell_size,       field::precursor_removed};
    c.accepts = {field::position, field::radius, field::velocity, field::drag_coefficient,
                 field::transfer_coefficient};
    return c;
  }

  static const std::vector<util::OptionSpec>& optionSpecs() {
    static const std::vector<util::OptionSpec> s = {
        {"velocity", "[0, 0, 0]", "[m/s] the gas velocity (uniform), or on the pipe's axis"},
        {"profile", "uniform",
         "uniform | parabolic (a pipe's laminar profile, zero at pipe_radius from the axis "
         "through axis_origin along z)"},
        {"pipe_radius", "required with parabolic", "[m] the pipe's radius; > 0"},
        {"axis_origin", "[0, 0, 0]", "[m] a point of the pipe's axis (along z)"},
        {"density", "1.2", "[kg/m3] the gas density; > 0"},
        {"viscosity", "1.8e-5", "[Pa s] the gas viscosity; > 0"},
        {"voidage", "1", "the voidage every parcel sees; in (0, 1]"},
        {"precursor_fraction", "0",
         "the precursor mass fraction every parcel sees, in [0, 1]; a reservoir that never "
         "runs out (what the parcels take up is fed in again)"},
        {"pressure_gradient", "hydrostatic",
         "hydrostatic (density times gravity) | none | [x, y, z] in Pa/m"},
        {"gravity", "[0, 0, -9.81]", "[m/s2] for the hydrostatic pressure gradient"},
        {"cell_size", "0.004", "[m] the cell size the fluid reports (cell_size field); > 0"},
        {"domain_min", "unbounded",
         "[m] lower corner of the box the fluid fills; a parcel outside it is reported as lost "
         "(it left the domain)"},
        {"domain_max", "unbounded", "[m] upper corner of that box"},
    };
    return s;
  }

  void configure(const wire::Welcome& w) override {
    const util::AdapterOptions o(w.config_yaml(), "fluid", "cosim-analytic-fluid", optionSpecs(),
                                 "docs/analytic-adapters.md");
    send_ = {w.send().begin(), w.send().end()};
    u_ = o.vec3("velocity", {0, 0, 0});
    profile_ = o.choice("profile", "uniform", {"uniform", "parabolic"});
    if (profile_ == "parabolic") {
      if (!o.has("pipe_radius"))
        o.fail("pipe_radius", "missing; a parabolic profile needs the pipe's radius [m]");
      R_ = o.positive("pipe_radius", 0);
      axis_ = o.vec3("axis_origin", {0, 0, 0});
    }
    rho_ = o.positive("density", 1.2);
    mu_ = o.positive("viscosity", 1.8e-5);
    eps_ = o.number("voidage", 1.0);
    if (!(eps_ > 0 && eps_ <= 1)) o.fail("voidage", "expected a value in (0, 1]");
    Y_ = o.number("precursor_fraction", 0.0, 0.0, 1.0);
    const auto g = o.vec3("gravity", {0, 0, -9.81});
    if (o.isList("pressure_gradient")) {
      gradp_ = o.vec3("pressure_gradient", {0, 0, 0});
    } else {
      const std::string mode =
          o.choice("pressure_gradient", "hydrostatic", {"hydrostatic", "none"});
      // Still or uniformly moving fluid in gravity: grad p = rho_f g.
      for (std::size_t i = 0; i < 3; ++i) gradp_[i] = mode == "hydrostatic" ? rho_ * g[i] : 0.0;
    }
    cell_ = o.positive("cell_size", 0.004);
    if (o.has("domain_min") || o.has("domain_max")) {
      dmin_ = o.vec3("domain_min", {-1e300, -1e300, -1e300});
      dmax_ = o.vec3("domain_max", {1e300, 1e300, 1e300});
      bounded_ = true;
    }
  }

  std::array<double, 3> velocityAt(const double* x) const {
    if (profile_ == "uniform") return u_;
    const double dx = x[0] - axis_[0], dy = x[1] - axis_[1];
    const double r2 = (dx * dx + dy * dy) / (R_ * R_);
    const double f = r2 < 1.0 ? 2.0 * (1.0 - r2) : 0.0;  // mean velocity = u_
    return {u_[0] * f, u_[1] * f, u_[2] * f};
  }

  void sample(const link::ParticleData& p, link::ParticleData& out,
              std::vector<std::int64_t>& lost) override {
    const auto& x = p.get(field::position);
    positions_ = x;
    ids_ = p.ids;
    for (const auto& name : send_) {
      if (name == field::precursor_removed) continue;
      auto& v = out.field(name);
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (name == field::fluid_velocity) {
          auto u = velocityAt(&x[3 * i]);
          for (std::size_t c = 0; c < 3; ++c) v[3 * i + c] = u[c];
        } else if (name == field::pressure_gradient) {
          for (std::size_t c = 0; c < 3; ++c) v[3 * i + c] = gradp_[c];
        } else if (name == field::voidage) {
          v[i] = eps_;
        } else if (name == field::fluid_density) {
          v[i] = rho_;
        } else if (name == field::fluid_viscosity) {
          v[i] = mu_;
        } else if (name == field::precursor_fraction) {
          v[i] = Y_;
        } else if (name == field::cell_size) {
          v[i] = cell_;
        }
      }
    }
    if (bounded_) {
      for (std::size_t i = 0; i < p.size(); ++i) {
        for (std::size_t c = 0; c < 3; ++c) {
          if (x[3 * i + c] < dmin_[c] || x[3 * i + c] > dmax_[c]) {
            lost.push_back(p.ids[i]);
            break;
          }
        }
      }
    }
  }

  void advance(const wire::Advance& cmd, const link::ParticleData& terms, wire::Advanced& out,
               link::ParticleData& state) override {
    if (cmd.dt() == 0.0) return;
    if (terms.has(field::transfer_coefficient)) {
      if (terms.ids != ids_)
        throw link::ProtocolError("Advance terms are for other particles than the last Sample");
      const auto& k = terms.get(field::transfer_coefficient);
      state.ids = terms.ids;
      auto& removed = state.field(field::precursor_removed);
      double total = 0.0;
      for (std::size_t i = 0; i < k.size(); ++i) {
        removed[i] = k[i] * Y_ * cmd.dt();  // Y is held constant: exact integral of Eq. 7
        total += removed[i];
      }
      auto& species = *out.mutable_fluid()->mutable_species();
      species.set_precursor_in(total);
      species.set_precursor_out(0.0);
      species.set_precursor_held(0.0);
      species.set_precursor_removed_total(total);
    }
    out.mutable_fluid()->set_pressure_drop(0.0);
  }

  // A prescribed flow has no state of its own beyond its configuration.
  std::vector<std::string> checkpoint(const std::string& /*path*/) override { return {}; }
  void restore(const std::string& /*path*/) override {}

 private:
  std::vector<std::string> send_;
  std::array<double, 3> u_{}, axis_{}, gradp_{}, dmin_{}, dmax_{};
  std::string profile_ = "uniform";
  double R_ = 0, rho_ = 1.2, mu_ = 1.8e-5, eps_ = 1, Y_ = 0, cell_ = 0.004;
  bool bounded_ = false;
  std::vector<double> positions_;
  std::vector<std::int64_t> ids_;
};

}  // namespace cosim::analytic

int main(int argc, char** argv) {
  return cosim::analytic::analyticMain<cosim::analytic::AnalyticFluid>(
      argc, argv, "cosim-analytic-fluid",
      "a prescribed gas flow (a cosim fluid participant, normally started by `cosim run`)");
}
