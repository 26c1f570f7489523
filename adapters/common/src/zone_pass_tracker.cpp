#include "cosim/link/zone_pass_tracker.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "cosim/link/fields.h"

namespace cosim::link {

double stepTime(double start, double dt, std::uint64_t k) {
  const double t = start + static_cast<double>(k) * dt;
  char text[32];
  std::snprintf(text, sizeof(text), "%.12g", t);
  return std::strtod(text, nullptr);
}

void ZonePassTracker::update(double time, const std::vector<std::int64_t>& ids,
                             const std::vector<char>& in_zone) {
  std::vector<std::int64_t> inside;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (in_zone[i]) inside.push_back(ids[i]);
  }
  std::sort(inside.begin(), inside.end());
  updateInside(time, std::move(inside));
}

void ZonePassTracker::updateInside(double time, std::vector<std::int64_t> inside) {
  const bool first = !started_;
  // Both sorted by id: one merge finds who left (open, not inside) and who entered.
  auto it = open_.begin();
  auto closeLeft = [&] {
    const OpenPass& p = it->second;
    closed_.push_back({it->first, p.entry_time, time, p.coating, p.at_start, ZonePass::Exit::left});
    it = open_.erase(it);
  };
  for (const std::int64_t id : inside) {
    while (it != open_.end() && it->first < id) closeLeft();
    if (it != open_.end() && it->first == id) {
      ++it;  // still inside
    } else {
      open_.emplace_hint(it, id, OpenPass{time, 0.0, first});
    }
  }
  while (it != open_.end()) closeLeft();
  started_ = true;
}

void ZonePassTracker::credit(const ParticleData& fr) {
  if (!fr.has(field::precursor_removed)) return;
  const auto& rm = fr.get(field::precursor_removed);
  for (std::size_t i = 0; i < fr.size(); ++i) {
    if (rm[i] == 0.0) continue;
    if (auto it = open_.find(fr.ids[i]); it != open_.end()) {
      it->second.coating += rm[i];
    } else {
      coating_outside_ += rm[i];
    }
  }
}

void ZonePassTracker::leave(const std::vector<std::int64_t>& deleted_ids, double time) {
  std::vector<std::int64_t> ids = deleted_ids;
  std::sort(ids.begin(), ids.end());
  for (const std::int64_t id : ids) {
    if (auto it = open_.find(id); it != open_.end()) {
      const OpenPass& p = it->second;
      closed_.push_back({id, p.entry_time, time, p.coating, p.at_start, ZonePass::Exit::deleted});
      open_.erase(it);
    }
  }
}

void ZonePassTracker::close(double time) {
  for (const auto& [id, p] : open_) {
    if (p.entry_time < time)
      closed_.push_back({id, p.entry_time, time, p.coating, p.at_start, ZonePass::Exit::run_end});
  }
  open_.clear();
}

std::vector<ZonePass> ZonePassTracker::takeClosed() {
  std::vector<ZonePass> out;
  out.swap(closed_);
  return out;
}

void ZonePassTracker::restore(State s) {
  open_ = std::move(s.open);
  coating_outside_ = s.coating_outside;
  started_ = s.started;
  closed_.clear();
}

}  // namespace cosim::link
