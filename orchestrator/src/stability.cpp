#include "stability.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iterator>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cosim/link/fields.h"
#include "cosim/util/all_finite.h"
#include "cosim/util/errors.h"
#include "cosim/util/format.h"

namespace cosim::orchestrator {

double relaxationTime(double mass, double K) { return K > 0 ? mass / K : INFINITY; }

namespace {}  // namespace

namespace {
// Snapshots from t = `from` to the run's end, the one at `from` included: one per output.interval,
// every coupling step when that is shorter.
double snapshotsLeft(const Scenario& sc, double from) {
  const double every = std::max(sc.output.interval, sc.coupling.dt);
  return std::floor(std::max(0.0, sc.coupling.end_time - from) / every) + 1;
}
}  // namespace

double particleOutputBytes(const Scenario& sc, const Plan& plan, const link::ParticleData& state,
                           double from) {
  double values = static_cast<double>(state.size());  // the ids
  for (const auto& name : plan.particles_send)
    if (state.has(name)) values += static_cast<double>(state.get(name).size());
  constexpr double kSnapshotOverhead = 4096.0;  // group, attributes, descriptions [bytes]
  return snapshotsLeft(sc, from) * (8.0 * values + kSnapshotOverhead);
}

std::optional<std::string> checkDiskSpace(const Scenario& sc, const Plan& plan,
                                          const link::ParticleData& state, double from,
                                          double available) {
  const double bytes = particleOutputBytes(sc, plan, state, from);
  if (!(bytes > 0.8 * available)) return std::nullopt;
  const double every = std::max(sc.output.interval, sc.coupling.dt);
  // the interval whose snapshots take half of what is free
  const double fits = every * bytes / (0.5 * std::max(available, 1.0));
  const auto gb = [](double b) { return fmt::format("{:.3g} GB", b / 1e9); };
  return "warning: particles.h5 will grow by about " + gb(bytes) + " over the run (" +
         fmt::format("{:.0f}", snapshotsLeft(sc, from)) + " snapshots of " +
         std::to_string(state.size()) + " particles, output.interval " +
         util::significant(sc.output.interval, 3) + " s), but only " + gb(available) +
         " are free on the run folder's disk: the run would stop when the disk is full (what it "
         "wrote stays readable; with checkpoint.interval set it resumes from the last one); free "
         "space, or record less often (output.interval: " +
         util::significant(fits, 3) + " would take half of the free space)";
}

std::string byteText(std::uintmax_t bytes) {
  const double b = static_cast<double>(bytes);
  char text[32];
  if (b >= 1e9) {
    std::snprintf(text, sizeof text, "%.2f GB", b / 1e9);
  } else if (b >= 1e6) {
    std::snprintf(text, sizeof text, "%.1f MB", b / 1e6);
  } else if (b >= 1e3) {
    std::snprintf(text, sizeof text, "%.1f kB", b / 1e3);
  } else {
    std::snprintf(text, sizeof text, "%ju B", bytes);
  }
  return text;
}

std::uintmax_t bytesOnDisk(const std::filesystem::path& p) {
  std::error_code ec;
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(p))) return 0;
  if (!std::filesystem::is_directory(p)) {
    const auto s = std::filesystem::file_size(p, ec);
    return ec ? 0 : s;
  }
  std::uintmax_t total = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(p, ec)) {
    if (e.is_regular_file(ec) && !e.is_symlink(ec)) total += e.file_size(ec);
  }
  return total;
}

std::optional<std::string> checkDiskFilling(double t0, double free0, double t, double free_now,
                                            double end,
                                            const std::function<std::string()>& largest) {
  const double used = free0 - free_now;
  if (!(t > t0) || !(used > 0)) return std::nullopt;
  const double rate = used / (t - t0);  // bytes per simulated second
  const double full = t + free_now / rate;
  if (!(full < end)) return std::nullopt;
  const auto bytes = [](double b) { return byteText(static_cast<std::uintmax_t>(b)); };
  return "warning: the run folder's disk has been filling by " + bytes(rate) +
         " per simulated second since t = " + util::significant(t0, 3) +
         " s; at that rate it is full at t = " + util::significant(full, 3) +
         " s, before the run's end at " + util::significant(end, 3) + " s (" + bytes(free_now) +
         " free now). The largest parts of the run folder: " + largest() +
         ". Free space, or write less: output.interval (particles.h5), the fluid's writeInterval "
         "and the particles' dumps (the shipped scenes' write_interval), the fluid's "
         "options.solver_log_every (docs/openfoam.md); the run stops with its records kept when "
         "the disk is full, and resumes from its last checkpoint";
}

std::string largestEntries(const std::filesystem::path& folder, std::size_t n) {
  namespace fs = std::filesystem;
  std::vector<std::pair<std::uintmax_t, std::string>> sizes;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    const bool dir = e.is_directory(ec) && !e.is_symlink(ec);
    sizes.emplace_back(bytesOnDisk(e.path()), e.path().filename().string() + (dir ? "/" : ""));
  }
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  std::string out;
  for (std::size_t i = 0; i < std::min(n, sizes.size()); ++i)
    out += (out.empty() ? "" : ", ") + sizes[i].second + " " + byteText(sizes[i].first);
  return out.empty() ? "(nothing)" : out;
}

StabilityReport checkBeforeRun(const Scenario& sc, const models::SceneModels& /*models*/,
                               const Plan& /*plan*/, const link::ParticleData& s,
                               double reported_dt_over_rayleigh) {
  StabilityReport r;
  const double dem_dt = sc.coupling.dt / sc.coupling.dem_steps;
  r.lines.push_back("coupling interval " + util::significant(sc.coupling.dt, 3) +
                    " s = " + std::to_string(sc.coupling.dem_steps) + " DEM steps of " +
                    util::significant(dem_dt, 3) + " s; " + std::to_string(s.size()) +
                    " particles at start");
  if (s.size() == 0)
    r.lines.push_back("warning: the particle participant reports no particles at start");
  if (sc.checkpoint.interval > 0 && sc.checkpoint.interval < sc.coupling.dt) {
    const double span = sc.coupling.end_time - sc.coupling.start_time;
    const double steps = span / sc.coupling.dt;
    r.lines.push_back(
        "warning: checkpoint.interval " + util::significant(sc.checkpoint.interval, 3) +
        " s is shorter than the coupling interval " + util::significant(sc.coupling.dt, 3) +
        " s: a checkpoint of both solvers' whole state after every coupling step (" +
        fmt::format("{:.0f}", steps) +
        " in this run), which costs more than the steps themselves; a long run "
        "needs one every few minutes of wall time (e.g. checkpoint.interval: " +
        util::significant(std::max(100.0 * sc.coupling.dt, 0.1 * span), 3) + ")");
  }

  // DEM dt / Rayleigh time from the constants, where they are given
  const auto& mat = sc.constants.material;
  std::optional<double> from_constants;
  double rmin = 0.0;
  if (s.has(field::radius) && s.size() > 0 && mat.particle_density > 0 && mat.youngs_modulus > 0) {
    const auto& rad = s.get(field::radius);
    rmin = *std::min_element(rad.begin(), rad.end());
    from_constants =
        dem_dt / rayleighTime(rmin, mat.particle_density, mat.youngs_modulus, mat.poisson_ratio);
  }
  double ratio = 0.0;
  std::string source;
  if (reported_dt_over_rayleigh > 0) {
    ratio = reported_dt_over_rayleigh;
    source = "the particle participant's own material data";
    if (from_constants && std::fabs(*from_constants / ratio - 1.0) > 0.01)
      r.lines.push_back(
          "warning: constants.youngs_modulus and poisson_ratio give DEM dt / Rayleigh time = " +
          util::significant(*from_constants, 3) +
          ", the particle participant's own material data " + util::significant(ratio, 3) +
          ": the participant's is used (it is what its contacts are computed with); correct or "
          "remove the constants");
  } else if (from_constants) {
    ratio = *from_constants;
    source = "constants.youngs_modulus, poisson_ratio, particle_density, r = " +
             util::significant(rmin, 3) + " m";
  } else {
    return r;
  }
  const double tR = dem_dt / ratio;
  std::string line = "DEM dt / Rayleigh time = " + util::significant(ratio, 3) +
                     " (t_R = " + util::significant(tR, 3) + " s, from " + source + ")";
  if (ratio > util::kRefuseRayleighFraction) {
    const double dt_max = util::kWarnRayleighFraction * tR;
    r.refusals.push_back(
        line + ": unstable contacts; use coupling.dem_steps >= " +
        std::to_string(static_cast<long long>(std::ceil(sc.coupling.dt / dt_max))) +
        " (DEM dt <= 0.2 t_R = " + util::significant(dt_max, 3) + " s)");
    line += " REFUSED";
  } else if (ratio > util::kWarnRayleighFraction) {
    line += " warning: above the usual 10-20 %";
  } else {
    line += " ok";
  }
  r.lines.push_back(line);
  return r;
}

StabilityReport checkFirstStep(const Scenario& sc, const link::ParticleData& state,
                               const link::ParticleData& samples,
                               const link::ParticleData& forcing) {
  StabilityReport r;
  const double dem_dt = sc.coupling.dt / sc.coupling.dem_steps;
  if (forcing.has(field::drag_coefficient) && state.has(field::radius) &&
      sc.constants.material.particle_density > 0) {
    const auto& K = forcing.get(field::drag_coefficient);
    const auto& rad = state.get(field::radius);
    double tmin = INFINITY;
    std::int64_t who = -1;
    for (std::size_t i = 0; i < state.size(); ++i) {
      const double m = sc.constants.material.particle_density * 4.0 / 3.0 * std::numbers::pi *
                       std::pow(rad[i], 3);
      const double t = relaxationTime(m, K[i]);
      if (t < tmin) {
        tmin = t;
        who = state.ids[i];
      }
    }
    if (std::isfinite(tmin)) {
      std::string line = "shortest particle relaxation time tau_p = " + util::significant(tmin, 3) +
                         " s (particle " + std::to_string(who) +
                         "): coupling interval = " + util::significant(sc.coupling.dt / tmin, 3) +
                         " tau_p, DEM dt = " + util::significant(dem_dt / tmin, 3) + " tau_p";
      if (sc.coupling.dt > tmin) {
        line +=
            "; drag is stiff: it stays stable because the particle adapter relaxes the velocity "
            "exactly over each DEM step and the fluid treats K implicitly, but the fluid velocity "
            "seen by the particles is frozen over the coupling interval";
      } else {
        line += " ok";
      }
      r.lines.push_back(line);
    }
  }
  if (samples.has(field::cell_size) && state.has(field::radius) && state.size() > 0) {
    const auto& h = samples.get(field::cell_size);
    const auto& rad = state.get(field::radius);
    double ratio_min = INFINITY, ratio_max = 0;
    for (std::size_t i = 0; i < state.size(); ++i) {
      if (h[i] <= 0) continue;  // lost particle
      const double q = h[i] / (2.0 * rad[i]);
      ratio_min = std::min(ratio_min, q);
      ratio_max = std::max(ratio_max, q);
    }
    if (std::isfinite(ratio_min)) {
      std::string line = "cell size / parcel diameter = " + util::significant(ratio_min, 3) +
                         " .. " + util::significant(ratio_max, 3);
      if (ratio_min < 1.0) {
        const double dmax = 2.0 * *std::max_element(rad.begin(), rad.end());
        r.refusals.push_back(line +
                             ": cells smaller than a parcel make the voidage meaningless; use "
                             "cells of at least 2 parcel diameters (>= " +
                             util::significant(2 * dmax, 3) +
                             " m) or a smaller coarse-graining factor");
        line += " REFUSED";
      } else if (ratio_min < 2.0 || ratio_max > 4.4) {
        line +=
            " warning: outside 2 - 4.4 diameters, where unresolved CFD-DEM is mesh-independent "
            "(paper 4.1)";
      } else {
        line += " ok";
      }
      r.lines.push_back(line);
    }
  }
  return r;
}

void StepMonitor::checkParticleLedger(const std::vector<std::int64_t>& before,
                                      const std::vector<std::int64_t>& after,
                                      const std::vector<std::int64_t>& inserted,
                                      const std::vector<std::int64_t>& deleted, std::uint64_t step,
                                      double time) {
  // The common step: nobody came or left and the particles report in the same order as
  // before (whose ids were checked for repeats when they were new).
  if (ledger_checked_ && inserted.empty() && deleted.empty() && before == after) return;
  ledger_checked_ = true;

  std::vector<std::int64_t> now(after);
  std::sort(now.begin(), now.end());
  if (std::adjacent_find(now.begin(), now.end()) != now.end()) {
    throw SolverError("particles: the state lists a particle id twice at step " +
                      std::to_string(step));
  }
  // expected = before - deleted + inserted, as a set
  std::vector<std::int64_t> kept(before), gone(deleted), born(inserted);
  std::sort(kept.begin(), kept.end());
  std::sort(gone.begin(), gone.end());
  std::sort(born.begin(), born.end());
  std::vector<std::int64_t> remaining, expect;
  std::set_difference(kept.begin(), kept.end(), gone.begin(), gone.end(),
                      std::back_inserter(remaining));
  std::set_union(remaining.begin(), remaining.end(), born.begin(), born.end(),
                 std::back_inserter(expect));
  expect.erase(std::unique(expect.begin(), expect.end()), expect.end());
  std::vector<std::int64_t> vanished, appeared;
  std::set_difference(expect.begin(), expect.end(), now.begin(), now.end(),
                      std::back_inserter(vanished));
  std::set_difference(now.begin(), now.end(), expect.begin(), expect.end(),
                      std::back_inserter(appeared));
  if (!vanished.empty() || !appeared.empty()) {
    std::ostringstream os;
    os << "particles: " << vanished.size() << " particle(s) vanished and " << appeared.size()
       << " appeared without being reported deleted/inserted at step " << step << " (t = " << time
       << " s)";
    if (!vanished.empty()) os << "; first vanished id " << vanished.front();
    if (!appeared.empty()) os << "; first new id " << appeared.front();
    throw SolverError(os.str());
  }
}

std::optional<std::string> StepMonitor::checkCourant(double co, std::uint64_t step, double time) {
  if (co > sc_.checks.max_courant) {
    std::ostringstream os;
    os << "fluid: Courant number " << co << " at step " << step << " (t = " << time
       << " s) exceeds checks.max_courant = " << sc_.checks.max_courant
       << ": reduce coupling.dt to about " << sc_.coupling.dt * 0.5 / co << " s (Courant 0.5)";
    // A growth that doubles every step is the coupled step going unstable in a stiff stretch: a
    // run resumed from its newest checkpoint with half the step (the DEM step kept) goes on
    const unsigned half = sc_.coupling.dem_steps / 2;
    if (half >= 1) {
      os << "; or go on from the newest checkpoint with a smaller step, the DEM step kept: cosim "
            "resume RUN --set coupling.dt="
         << sc_.coupling.dt / sc_.coupling.dem_steps * half << " --set coupling.dem_steps=" << half
         << " (docs/restarts.md)";
    }
    throw SolverError(os.str());
  }
  if (co > 1.0 && !courant_warned_) {
    courant_warned_ = true;
    std::ostringstream os;
    os << "warning: fluid Courant number " << co << " > 1 at step " << step << " (t = " << time
       << " s); PIMPLE stays stable with outer correctors but time accuracy suffers";
    return os.str();
  }
  return std::nullopt;
}

std::optional<std::string> StepMonitor::checkPrecursorBounds(double smallest, double largest,
                                                             std::uint64_t step, double time) {
  if (undershoot_warned_ || !(largest > 0) || !(smallest < -1e-6 * largest)) return std::nullopt;
  undershoot_warned_ = true;
  std::ostringstream os;
  os << "warning: the precursor's mass fraction in the gas fell to " << smallest << " at step "
     << step << " (t = " << time << " s; largest " << largest
     << "): its transport undershoots zero in a few cells (explicit non-orthogonal correction "
        "of the diffusion, or convection where the gas's flux and density disagree within the "
        "step). Parcels there take up a negative amount, so a few may end with a slightly "
        "negative coating; the precursor balance still closes. A more orthogonal mesh reduces "
        "it; so may `laplacian(Gamma,precursor) Gauss linear limited corrected 0.5` in the "
        "case's system/fvSchemes (docs/when-things-go-wrong.md)";
  return os.str();
}

void StepMonitor::setHeldAtStart(double held) { baseline_ = {0.0, 0.0, held, 0.0}; }

void StepMonitor::checkMassBalance(double in, double out, double held, double removed,
                                   std::uint64_t step, double time) {
  // Balance from the end of the first step on, so precursor already in the gas at the start
  // (unknown to the orchestrator) does not count as an error.
  if (!baseline_) {
    // Without the fluid's held-at-start, balance from the end of the first step on.
    baseline_ = {in, out, held, removed};
    return;
  }
  in -= (*baseline_)[0];
  out -= (*baseline_)[1];
  held -= (*baseline_)[2];
  removed -= (*baseline_)[3];
  const double scale = std::max({in, held, removed, 1e-300});
  const double err = (in - out - held - removed) / scale;
  if (std::fabs(err) > sc_.checks.mass_balance_tolerance) {
    std::ostringstream os;
    os << "precursor mass balance drifts at step " << step << " (t = " << time << " s): in " << in
       << " kg - out " << out << " kg - change held " << held << " kg - removed by particles "
       << removed << " kg = " << in - out - held - removed << " kg, relative " << err
       << " > checks.mass_balance_tolerance = " << sc_.checks.mass_balance_tolerance;
    throw SolverError(os.str());
  }
}

std::optional<std::string> checkParticleCount(const Scenario& sc,
                                              const link::ParticleData& initial_state) {
  if (!sc.checks.particle_count) return std::nullopt;
  const std::uint64_t want = *sc.checks.particle_count;
  const std::uint64_t have = initial_state.size();
  if (have == want) return std::nullopt;
  std::ostringstream m;
  m << "the particles hold " << have << " particles when coupling starts, where the scene's "
    << "checks.particle_count asks for " << want
    << fmt::format(" ({:+.1f} %)", 100.0 * (static_cast<double>(have) - static_cast<double>(want)) /
                                       static_cast<double>(want));
  const double rho = sc.constants.material.particle_density;
  if (rho > 0.0 && initial_state.has(field::radius) && have > 0) {
    double volume = 0.0;
    for (double r : initial_state.get(field::radius)) volume += r * r * r;
    volume *= 4.0 / 3.0 * std::numbers::pi;
    const double per = volume / static_cast<double>(have);
    m << fmt::format("; they weigh {:.4g} kg where {:.4g} kg were asked for", rho * volume,
                     rho * per * static_cast<double>(want));
  }
  if (have < want) {
    m << ".\n  The particle solver could not place them all (LIGGGHTS' insert/pack says only "
         "'WARNING: Particle insertion: Less insertions than requested' in its log). Make the "
         "fill region larger (taller), pour again once the first pour has settled (as "
         "scenarios/ft4-rheometer does with fill_pours), or lower the count; then run again.";
  } else {
    m << ".\n  The particle solver holds more than the scene asks for: check its script's "
         "insertion (two insertions, or a count that is not the scene's n_grains).";
  }
  return m.str();
}

std::optional<std::string> applyParticleChanges(std::vector<std::int64_t>& ids,
                                                std::vector<std::int64_t> inserted,
                                                std::vector<std::int64_t> deleted,
                                                std::uint64_t count) {
  std::sort(deleted.begin(), deleted.end());
  std::sort(inserted.begin(), inserted.end());
  auto held = [&](std::int64_t id) { return std::binary_search(ids.begin(), ids.end(), id); };
  if (const auto it = std::find_if_not(deleted.begin(), deleted.end(), held); it != deleted.end())
    return "deleted parcel " + std::to_string(*it) + ", which it did not hold";
  if (const auto it = std::find_if(inserted.begin(), inserted.end(), held); it != inserted.end())
    return "inserted parcel " + std::to_string(*it) + ", which it already held";
  if (const auto it = std::adjacent_find(inserted.begin(), inserted.end()); it != inserted.end())
    return "inserted parcel " + std::to_string(*it) + " twice";
  if (const auto it = std::adjacent_find(deleted.begin(), deleted.end()); it != deleted.end())
    return "deleted parcel " + std::to_string(*it) + " twice";
  const std::size_t after = ids.size() - deleted.size() + inserted.size();
  if (count != after)
    return "holds " + std::to_string(count) + " parcels, where the " + std::to_string(ids.size()) +
           " it held with the " + std::to_string(inserted.size()) + " it inserted and the " +
           std::to_string(deleted.size()) + " it deleted make " + std::to_string(after);
  if (deleted.empty() && inserted.empty()) return std::nullopt;
  std::vector<std::int64_t> kept, now;
  kept.reserve(ids.size());
  std::set_difference(ids.begin(), ids.end(), deleted.begin(), deleted.end(),
                      std::back_inserter(kept));
  now.reserve(after);
  std::merge(kept.begin(), kept.end(), inserted.begin(), inserted.end(), std::back_inserter(now));
  ids = std::move(now);
  return std::nullopt;
}

std::optional<std::string> compareWithChanges(const std::vector<std::int64_t>& known,
                                              std::vector<std::int64_t> sent) {
  std::sort(sent.begin(), sent.end());
  if (sent == known) return std::nullopt;
  const auto [a, b] = std::mismatch(known.begin(), known.end(), sent.begin(), sent.end());
  if (b == sent.end() || (a != known.end() && *a < *b))
    return "lacks parcel " + std::to_string(*a) + ", which it never reported deleted";
  return "holds parcel " + std::to_string(*b) + ", which it never reported inserted";
}

std::optional<std::string> checkParticleState(const link::ParticleData& s, const std::string& where,
                                              double max_speed, std::uint64_t step, double time) {
  // Runs four times a coupling step over every parcel: one branch-free pass per field, and the
  // message (with the first offending value) only when a pass fails.
  for (const auto& [name, v] : s.fields()) {
    if (util::allFinite(v)) continue;
    const unsigned c = std::max(1U, field::components(name));
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!std::isfinite(v[i])) {
        std::ostringstream os;
        os << where << ": " << name << " of particle " << s.ids[i / c] << " is " << v[i]
           << " at step " << step << " (t = " << time << " s)";
        return os.str();
      }
    }
  }
  if (s.has(field::velocity)) {
    const auto& v = s.get(field::velocity);
    const double max2 = max_speed * max_speed;
    double fastest2 = 0.0;
    for (std::size_t p = 0; p < s.size(); ++p)
      fastest2 = std::max(fastest2, v[3 * p] * v[3 * p] + v[3 * p + 1] * v[3 * p + 1] +
                                        v[3 * p + 2] * v[3 * p + 2]);
    if (fastest2 > max2) {
      for (std::size_t p = 0; p < s.size(); ++p) {
        const double speed = std::sqrt(v[3 * p] * v[3 * p] + v[3 * p + 1] * v[3 * p + 1] +
                                       v[3 * p + 2] * v[3 * p + 2]);
        if (speed > max_speed) {
          std::ostringstream os;
          os << where << ": particle " << s.ids[p] << " moves at " << speed << " m/s at step "
             << step << " (t = " << time << " s), above checks.max_particle_speed = " << max_speed
             << " m/s: the run is unstable (DEM dt too large, or drag too stiff for the coupling "
                "interval?)";
          return os.str();
        }
      }
    }
  }
  if (s.has(field::voidage)) {
    const auto& e = s.get(field::voidage);
    bool inside = true;
    for (double x : e) inside &= x > 0.0 && x <= 1.0 + 1e-9;
    if (!inside) {
      for (std::size_t p = 0; p < s.size(); ++p) {
        if (e[p] <= 0.0 || e[p] > 1.0 + 1e-9) {
          std::ostringstream os;
          os << where << ": voidage " << std::setprecision(10) << e[p] << std::setprecision(6)
             << " at particle " << s.ids[p] << " (step " << step << ") is outside (0, 1]";
          return os.str();
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace cosim::orchestrator
