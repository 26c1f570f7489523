// cosim-free-particles: non-colliding spheres under gravity and the orchestrator's forcing.
// Over each coupling interval K, u_f and F are constant, so m dv/dt = K (u_f - v) + F + m g is
// integrated exactly:  v(t) = v_inf + (v0 - v_inf) exp(-t/tau),  tau = m/K,
// v_inf = u_f + (F + m g)/K,  x(t) = x0 + v_inf t + (v0 - v_inf) tau (1 - exp(-t/tau)).
// Exact for any time step, however small tau: the reference for stiff-drag tests.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>

#include "analytic_main.h"
#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/peer_terms.h"
#include "cosim/link/session.h"
#include "cosim/util/adapter_options.h"
#include "cosim/util/errors.h"

namespace cosim::analytic {

struct Particle {
  std::int64_t id;
  std::array<double, 3> x, v;
  double r;
  double coating = 0.0;
  double type = 1;
};

class FreeParticles final : public link::Solver {
 public:
  link::Capabilities capabilities() const override {
    link::Capabilities c;
    c.role = wire::PARTICLES;
    c.adapter = "free-particles";
    c.provides = {field::position, field::velocity, field::radius, field::coating_mass,
                  field::type};
    c.accepts = {field::drag_coefficient, field::fluid_velocity, field::explicit_force,
                 field::coating_increment};
    return c;
  }

  static const std::vector<util::OptionSpec>& optionSpecs() {
    static const std::vector<util::OptionSpec> s = {
        {"density", "2500", "[kg/m3] the particle density; > 0"},
        {"gravity", "[0, 0, -9.81]", "[m/s2]"},
        {"fixed", "false", "true: the particles do not move (a held particle, a fixed bed)"},
        {"particles", "none",
         "a list of { id, position: [x, y, z], velocity: [x, y, z], radius }: id defaults to "
         "the previous one + 1 (from 1), velocity to [0, 0, 0]; radius [m] > 0"},
        {"lattice", "none",
         "{ count: [nx, ny, nz], origin: [x, y, z], spacing, radius }: particles on a regular "
         "lattice, after those of particles:; spacing and radius [m] > 0"},
        {"domain_min", "unbounded",
         "[m] lower corner of the box the particles live in; one that leaves it is deleted and "
         "reported"},
        {"domain_max", "unbounded", "[m] upper corner of that box"},
    };
    return s;
  }

  void configure(const wire::Welcome& w) override {
    const util::AdapterOptions o(w.config_yaml(), "particles", "cosim-free-particles",
                                 optionSpecs(), "docs/analytic-adapters.md");
    send_ = {w.send().begin(), w.send().end()};
    rho_ = o.positive("density", 2500.0);
    g_ = o.vec3("gravity", {0, 0, -9.81});
    fixed_ = o.flag("fixed", false);
    if (o.has("particles")) {
      const YAML::Node list = o.node("particles");
      if (!list.IsSequence()) o.fail("particles", "expected a list of { position, radius, ... }");
      std::int64_t next = 1;
      for (std::size_t i = 0; i < list.size(); ++i) {
        const YAML::Node n = list[i];
        const std::string k = "particles[" + std::to_string(i) + "]";
        if (!n.IsMap()) o.fail(k, "expected a map { id, position, velocity, radius }");
        Particle p{};
        if (n["id"]) {
          const double id = o.numberAt(n["id"], k + ".id");
          if (id != std::floor(id) || std::fabs(id) > 9.0e15)
            o.fail(k + ".id", "expected a whole number, got " + n["id"].Scalar());
          p.id = static_cast<std::int64_t>(id);
        } else {
          p.id = next;
        }
        next = p.id + 1;
        p.x = o.vec3At(n["position"], k + ".position");
        p.v = n["velocity"] ? o.vec3At(n["velocity"], k + ".velocity")
                            : std::array<double, 3>{0, 0, 0};
        p.r = o.numberAt(n["radius"], k + ".radius");
        if (!(p.r > 0)) o.fail(k + ".radius", "expected a radius > 0 [m]");
        add(p);
      }
    }
    if (o.has("lattice")) {
      const YAML::Node l = o.node("lattice");
      const auto count = o.vec3At(l["count"], "lattice.count");
      const auto origin = o.vec3At(l["origin"], "lattice.origin");
      const double s = o.numberAt(l["spacing"], "lattice.spacing");
      const double r = o.numberAt(l["radius"], "lattice.radius");
      if (!(r > 0) || !(s > 0)) o.fail("lattice", "radius and spacing must be > 0 [m]");
      std::int64_t id = particles_.empty() ? 1 : particles_.rbegin()->first + 1;
      for (int k = 0; k < static_cast<int>(count[2]); ++k)
        for (int j = 0; j < static_cast<int>(count[1]); ++j)
          for (int i = 0; i < static_cast<int>(count[0]); ++i) {
            Particle p{};
            p.id = id++;
            p.x = {origin[0] + i * s, origin[1] + j * s, origin[2] + k * s};
            p.v = {0, 0, 0};
            p.r = r;
            add(p);
          }
    }
    if (particles_.empty()) o.fail("particles", "no particles: give particles: or lattice:");
    if (o.has("domain_min") || o.has("domain_max")) {
      bounded_ = true;
      dmin_ = o.vec3("domain_min", {-1e300, -1e300, -1e300});
      dmax_ = o.vec3("domain_max", {1e300, 1e300, 1e300});
    }
  }

  void advance(const wire::Advance& cmd, const link::ParticleData& terms, wire::Advanced& out,
               link::ParticleData& state) override {
    const double dt = cmd.dt();
    const auto n = terms.size();
    const std::vector<double>* K =
        terms.has(field::drag_coefficient) ? &terms.get(field::drag_coefficient) : nullptr;
    const std::vector<double>* uf =
        terms.has(field::fluid_velocity) ? &terms.get(field::fluid_velocity) : nullptr;
    const std::vector<double>* F =
        terms.has(field::explicit_force) ? &terms.get(field::explicit_force) : nullptr;
    const std::vector<double>* dm =
        terms.has(field::coating_increment) ? &terms.get(field::coating_increment) : nullptr;
    std::map<std::int64_t, std::size_t> row;
    for (std::size_t i = 0; i < n; ++i) row[terms.ids[i]] = i;
    for (const auto& [id, i] : row) {
      if (!particles_.count(id)) {
        throw link::ProtocolError("terms for particle " + std::to_string(id) +
                                  ", which does not exist");
      }
      if (dm) particles_[id].coating += (*dm)[i];
    }
    if (dt > 0 && !fixed_) {
      std::vector<std::int64_t> gone;
      for (auto& [id, p] : particles_) {
        const double m = rho_ * 4.0 / 3.0 * std::numbers::pi * p.r * p.r * p.r;
        auto it = row.find(id);
        double k = 0;
        std::array<double, 3> u{0, 0, 0}, f{0, 0, 0};
        if (it != row.end()) {
          const std::size_t i = it->second;
          if (K) k = (*K)[i];
          for (std::size_t c = 0; c < 3; ++c) {
            if (uf) u[c] = (*uf)[3 * i + c];
            if (F) f[c] = (*F)[3 * i + c];
          }
        }
        for (std::size_t c = 0; c < 3; ++c) {
          const double a = f[c] / m + g_[c];
          if (k > 0) {
            const double tau = m / k;
            const double vinf = u[c] + a * tau;
            const double decay = -std::expm1(-dt / tau);  // 1 - exp(-dt/tau), accurate for small dt
            const double v0 = p.v[c];
            p.v[c] = vinf + (v0 - vinf) * (1.0 - decay);
            p.x[c] += vinf * dt + (v0 - vinf) * tau * decay;
          } else {
            p.x[c] += p.v[c] * dt + 0.5 * a * dt * dt;
            p.v[c] += a * dt;
          }
        }
        if (bounded_) {
          for (std::size_t c = 0; c < 3; ++c) {
            if (p.x[c] < dmin_[c] || p.x[c] > dmax_[c]) {
              gone.push_back(id);
              break;
            }
          }
        }
      }
      for (auto id : gone) {
        particles_.erase(id);
        out.add_deleted_ids(id);
      }
    }
    state.ids.clear();
    for (const auto& [id, p] : particles_) state.ids.push_back(id);
    for (const auto& name : send_) {
      auto& v = state.field(name);
      std::size_t i = 0;
      for (const auto& [id, p] : particles_) {
        if (name == field::position)
          for (std::size_t c = 0; c < 3; ++c) v[3 * i + c] = p.x[c];
        else if (name == field::velocity)
          for (std::size_t c = 0; c < 3; ++c) v[3 * i + c] = p.v[c];
        else if (name == field::radius)
          v[i] = p.r;
        else if (name == field::coating_mass)
          v[i] = p.coating;
        else if (name == field::type)
          v[i] = p.type;
        ++i;
      }
    }
  }

  // The particles as they are, to the bit (raw doubles): a resumed run continues exactly.
  std::vector<std::string> checkpoint(const std::string& path) override {
    const auto file = std::filesystem::path(path) / "free-particles.state";
    std::ofstream os(file, std::ios::binary);
    const std::uint64_t n = particles_.size();
    os.write(reinterpret_cast<const char*>(&n), sizeof n);
    for (const auto& [id, p] : particles_) os.write(reinterpret_cast<const char*>(&p), sizeof p);
    os.close();
    if (!os) throw ResourceError("free-particles: cannot write " + file.string());
    return {file.string()};
  }

  void restore(const std::string& path) override {
    const auto file = std::filesystem::path(path) / "free-particles.state";
    std::ifstream is(file, std::ios::binary);
    std::uint64_t n = 0;
    is.read(reinterpret_cast<char*>(&n), sizeof n);
    if (!is || n > (1ULL << 32))
      throw InputError("free-particles: " + file.string() + " is not a checkpoint of this adapter");
    particles_.clear();
    for (std::uint64_t i = 0; i < n; ++i) {
      Particle p{};
      is.read(reinterpret_cast<char*>(&p), sizeof p);
      if (!is) throw InputError("free-particles: " + file.string() + " is truncated");
      particles_[p.id] = p;
    }
  }

 private:
  void add(const Particle& p) {
    if (particles_.count(p.id))
      throw InputError("free-particles options: particle id " + std::to_string(p.id) +
                       " given twice");
    particles_[p.id] = p;
  }
  std::vector<std::string> send_;
  std::map<std::int64_t, Particle> particles_;
  double rho_ = 2500;
  std::array<double, 3> g_{}, dmin_{}, dmax_{};
  bool fixed_ = false, bounded_ = false;
};

}  // namespace cosim::analytic

int main(int argc, char** argv) {
  cosim::link::ScenePeerTerms laws;  // coupling.data_path: peer
  return cosim::analytic::analyticMain<cosim::analytic::FreeParticles>(
      argc, argv, "cosim-free-particles",
      "non-colliding particles under gravity and the coupling forces (a cosim particle "
      "participant, normally started by `cosim run`)",
      &laws);
}
