#include "zone_passes.h"

#include <algorithm>

#include "cosim/link/fields.h"

namespace cosim::orchestrator {

using analysis::ZonePass;

void ZonePassRecorder::start(const std::filesystem::path& run_folder) {
  writer_ = std::make_unique<analysis::ZonePassWriter>(run_folder / analysis::kZonePassesFile);
  open_.clear();
  coating_outside_ = 0;
  first_update_ = true;
}

void ZonePassRecorder::resume(const std::filesystem::path& run_folder, State state) {
  const auto path = run_folder / analysis::kZonePassesFile;
  analysis::truncateZonePasses(path, state.rows);
  writer_ =
      std::make_unique<analysis::ZonePassWriter>(path, analysis::ZonePassWriter::Mode::append);
  open_ = std::move(state.open);
  coating_outside_ = state.coating_outside;
  first_update_ = false;
}

void ZonePassRecorder::update(double time, const std::vector<std::int64_t>& ids,
                              const std::vector<char>& in_zone) {
  std::vector<std::int64_t> inside;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (in_zone[i]) inside.push_back(ids[i]);
  }
  std::sort(inside.begin(), inside.end());
  updateInside(time, std::move(inside));
}

void ZonePassRecorder::updateInside(double time, std::vector<std::int64_t> inside) {
  // Both sorted by id: one merge finds who left (open, not inside) and who entered.
  auto it = open_.begin();
  for (const std::int64_t id : inside) {
    while (it != open_.end() && it->first < id) {
      const OpenPass& p = it->second;
      closed_.push_back(
          {it->first, p.entry_time, time, p.coating, p.at_start, ZonePass::Exit::left});
      it = open_.erase(it);
    }
    if (it != open_.end() && it->first == id) {
      ++it;  // still inside
    } else {
      open_.emplace_hint(it, id, OpenPass{time, 0.0, first_update_});
    }
  }
  while (it != open_.end()) {
    const OpenPass& p = it->second;
    closed_.push_back({it->first, p.entry_time, time, p.coating, p.at_start, ZonePass::Exit::left});
    it = open_.erase(it);
  }
  first_update_ = false;
  flush();
}

void ZonePassRecorder::credit(const link::ParticleData& fr) {
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

void ZonePassRecorder::leave(const std::vector<std::int64_t>& deleted_ids, double time) {
  std::vector<std::int64_t> ids = deleted_ids;
  std::sort(ids.begin(), ids.end());
  for (const std::int64_t id : ids) {
    if (auto it = open_.find(id); it != open_.end()) {
      const OpenPass& p = it->second;
      closed_.push_back({id, p.entry_time, time, p.coating, p.at_start, ZonePass::Exit::deleted});
      open_.erase(it);
    }
  }
  flush();
}

void ZonePassRecorder::close(double time) {
  for (const auto& [id, p] : open_) {
    if (p.entry_time < time)
      closed_.push_back({id, p.entry_time, time, p.coating, p.at_start, ZonePass::Exit::run_end});
  }
  open_.clear();
  flush();
}

void ZonePassRecorder::flush() {
  if (closed_.empty() || !writer_) return;
  writer_->write(closed_);
  closed_.clear();
}

}  // namespace cosim::orchestrator
