// The PIV view of a run (piv_field.h).
#include "cosim/analysis/piv_field.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "cosim/analysis/files.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("PIV options: " + what);
}

// Cells of [lo, hi) at this size: the last one may be cut by hi, never dropped.
std::size_t cellsOver(double lo, double hi, double cell) {
  return static_cast<std::size_t>(std::ceil((hi - lo) / cell - 1e-9));
}

// Index of v in cells of size cell from lo, or n (outside) .
std::size_t bin(double v, double lo, double cell, std::size_t n) {
  const double f = std::floor((v - lo) / cell);
  if (!(f >= 0) || f >= static_cast<double>(n)) return n;
  return static_cast<std::size_t>(f);
}

std::string number(double v) { return std::isfinite(v) ? formatShortest(v) : std::string(); }
}  // namespace

double PivGrid::mean(std::size_t ix, std::size_t iz) const {
  const std::size_t k = iz * nx + ix;
  return samples[k] > 0 ? sum_vz[k] / static_cast<double>(samples[k]) : kNaN;
}

PivAccumulator::PivAccumulator(const PivOptions& options) : o_(options) {
  require(std::isfinite(o_.cell) && o_.cell > 0, fmt::format("cell = {} m: must be > 0", o_.cell));
  require(std::isfinite(o_.x_min) && std::isfinite(o_.x_max) && o_.x_max > o_.x_min,
          fmt::format("x range [{}, {}] m: needs x_min < x_max", o_.x_min, o_.x_max));
  require(std::isfinite(o_.z_min) && std::isfinite(o_.z_max) && o_.z_max > o_.z_min,
          fmt::format("z range [{}, {}] m: needs z_min < z_max", o_.z_min, o_.z_max));
  require(std::isfinite(o_.wall_y), "the front wall's y is not a number");
  require(!o_.depth || (std::isfinite(*o_.depth) && *o_.depth > 0),
          fmt::format("depth = {} m: must be > 0", o_.depth.value_or(0)));
  require(o_.blocks >= 1, "blocks = 0: the standard errors need at least 2 blocks (1: none)");
  require(std::isfinite(o_.from) && !std::isnan(o_.to) && o_.to >= o_.from,
          fmt::format("time window [{}, {}] s: needs from <= to", o_.from, o_.to));
  for (double h : o_.heights)
    require(std::isfinite(h) && h >= o_.z_min && h <= o_.z_max,
            fmt::format("profile height {} m lies outside the grid's z range [{}, {}] m", h,
                        o_.z_min, o_.z_max));
  auto& g = result_.grid;
  g.x0 = o_.x_min;
  g.z0 = o_.z_min;
  g.cell = o_.cell;
  g.nx = cellsOver(o_.x_min, o_.x_max, o_.cell);
  g.nz = cellsOver(o_.z_min, o_.z_max, o_.cell);
  require(g.nx * g.nz <= 100'000'000, "more than 1e8 grid cells: take a larger cell");
  g.sum_vz.assign(g.nx * g.nz, 0.0);
  g.samples.assign(g.nx * g.nz, 0);
  for (double h : o_.heights) {
    PivProfile p;
    p.height = h;
    for (std::size_t ix = 0; ix < g.nx; ++ix) p.x.push_back(g.xCentre(ix));
    p.vz.assign(g.nx, kNaN);
    p.samples.assign(g.nx, 0);
    p.stderr_vz.assign(g.nx, kNaN);
    result_.profiles.push_back(std::move(p));
    profile_sums_.emplace_back(g.nx, 0.0);
  }
}

void PivAccumulator::add(double time, const std::vector<double>& position,
                         const std::vector<double>& velocity, const std::vector<double>& radius) {
  const std::size_t n = position.size() / 3;
  if (velocity.size() != 3 * n || (!o_.depth && radius.size() != n))
    throw std::invalid_argument(fmt::format(
        "PIV snapshot at t = {} s: {} positions, {} velocities and {} radii do not match", time, n,
        velocity.size() / 3, radius.size()));
  auto& g = result_.grid;
  const std::size_t bins = result_.profiles.size() * g.nx;
  auto& snap_sum = snapshot_sums_.emplace_back(bins, 0.0);
  auto& snap_samples = snapshot_samples_.emplace_back(bins, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = position[3 * i], y = position[3 * i + 1], z = position[3 * i + 2];
    const double vz = velocity[3 * i + 2];
    const double depth = o_.depth ? *o_.depth : 2.0 * radius[i];
    if (!(y - o_.wall_y <= depth) || !std::isfinite(vz)) continue;
    const std::size_t ix = bin(x, g.x0, g.cell, g.nx);
    if (ix == g.nx) continue;
    const std::size_t iz = bin(z, g.z0, g.cell, g.nz);
    if (iz < g.nz) {
      g.sum_vz[iz * g.nx + ix] += vz;
      ++g.samples[iz * g.nx + ix];
      ++result_.samples;
    }
    for (std::size_t p = 0; p < result_.profiles.size(); ++p) {
      auto& prof = result_.profiles[p];
      if (z >= prof.height - 0.5 * g.cell && z < prof.height + 0.5 * g.cell) {
        profile_sums_[p][ix] += vz;
        ++prof.samples[ix];
        prof.vz[ix] = profile_sums_[p][ix] / static_cast<double>(prof.samples[ix]);
        snap_sum[p * g.nx + ix] += vz;
        ++snap_samples[p * g.nx + ix];
      }
    }
  }
  if (result_.snapshots == 0) result_.first_time = time;
  result_.last_time = time;
  ++result_.snapshots;
}

double batchMeansStandardError(const std::vector<double>& block_sums,
                               const std::vector<double>& block_samples) {
  double sum = 0, samples = 0;
  std::size_t holding = 0;
  for (std::size_t b = 0; b < block_sums.size(); ++b) {
    sum += block_sums[b];
    samples += block_samples[b];
    if (block_samples[b] > 0) ++holding;
  }
  if (holding < 2) return kNaN;
  const double ratio = sum / samples;
  double squares = 0;
  for (std::size_t b = 0; b < block_sums.size(); ++b) {
    const double d = block_sums[b] - ratio * block_samples[b];
    squares += d * d;
  }
  const auto nb = static_cast<double>(block_sums.size());
  return std::sqrt(nb / (nb - 1) * squares) / samples;
}

const PivResult& PivAccumulator::result() {
  const std::size_t snapshots = snapshot_sums_.size();
  const std::size_t blocks = std::min(o_.blocks, snapshots);
  result_.blocks = blocks;
  const std::size_t nx = result_.grid.nx;
  std::vector<double> block_sums(blocks), block_samples(blocks);
  for (std::size_t p = 0; p < result_.profiles.size(); ++p) {
    for (std::size_t ix = 0; ix < nx; ++ix) {
      std::fill(block_sums.begin(), block_sums.end(), 0.0);
      std::fill(block_samples.begin(), block_samples.end(), 0.0);
      // block b holds the snapshots [b S / B, (b + 1) S / B)
      for (std::size_t s = 0; s < snapshots; ++s) {
        const std::size_t b = s * blocks / snapshots;
        block_sums[b] += snapshot_sums_[s][p * nx + ix];
        block_samples[b] += snapshot_samples_[s][p * nx + ix];
      }
      result_.profiles[p].stderr_vz[ix] =
          blocks >= 2 ? batchMeansStandardError(block_sums, block_samples) : kNaN;
    }
  }
  return result_;
}

PivResult pivField(const ParticleFile& file, const PivOptions& options) {
  const bool radii = !options.depth;
  for (const char* f : {field::position, field::velocity}) {
    if (!file.hasField(f))
      throw InputError(file.path().string() + ": has no field '" + f +
                       "': the PIV view needs the parcels' positions and velocities");
  }
  if (radii && !file.hasField(field::radius))
    throw InputError(file.path().string() +
                     ": has no field 'radius': give the depth that counts (--depth)");
  PivAccumulator acc(options);
  const auto& snaps = file.snapshots();
  for (std::size_t s = 0; s < snaps.size(); ++s) {
    if (snaps[s].time < options.from - 1e-12 || snaps[s].time > options.to + 1e-12) continue;
    if (snaps[s].count == 0) {
      acc.add(snaps[s].time, {}, {}, {});
      continue;
    }
    acc.add(snaps[s].time, file.read(s, field::position), file.read(s, field::velocity),
            radii ? file.read(s, field::radius) : std::vector<double>{});
  }
  const PivResult& result = acc.result();  // the standard errors computed once
  if (result.snapshots == 0)
    throw InputError(fmt::format(
        "{}: no snapshot in {} <= t <= {} s (it holds {} snapshots{}): take another --from "
        "or --to",
        file.path().string(), options.from, options.to, snaps.size(),
        snaps.empty() ? std::string()
                      : fmt::format(" from {} to {} s", snaps.front().time, snaps.back().time)));
  return result;
}

void writePiv(const PivResult& r, const PivOptions& o, const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  const auto& g = r.grid;
  std::string grid = "x_m,z_m,vz_m_s,samples\n";
  for (std::size_t iz = 0; iz < g.nz; ++iz)
    for (std::size_t ix = 0; ix < g.nx; ++ix)
      grid +=
          fmt::format("{},{},{},{}\n", formatShortest(g.xCentre(ix)), formatShortest(g.zCentre(iz)),
                      number(g.mean(ix, iz)), g.samples[iz * g.nx + ix]);
  writeFileAtomically(folder / "grid.csv", grid);
  std::string prof = std::string(kProfilesHeader) + "\n";
  for (const auto& p : r.profiles)
    for (std::size_t i = 0; i < p.x.size(); ++i)
      prof += fmt::format("{},{},{},{},{}\n", formatShortest(p.height), formatShortest(p.x[i]),
                          number(p.vz[i]), p.samples[i], number(p.stderr_vz[i]));
  writeFileAtomically(folder / "profiles.csv", prof);
  const Json j = {{"from_s", o.from},
                  {"to_s", std::isfinite(o.to) ? Json(o.to) : Json("end")},
                  {"depth_m", o.depth ? Json(*o.depth) : Json("parcel diameter")},
                  {"front_wall_y_m", o.wall_y},
                  {"x_range_m", Json::array({o.x_min, o.x_max})},
                  {"z_range_m", Json::array({o.z_min, o.z_max})},
                  {"cell_m", o.cell},
                  {"heights_m", o.heights},
                  {"snapshots", r.snapshots},
                  {"first_time_s", r.first_time},
                  {"last_time_s", r.last_time},
                  {"samples", r.samples},
                  {"stderr_blocks", r.blocks}};
  writeJsonFile(folder / "piv.json", j, 2);
}

}  // namespace cosim::analysis
