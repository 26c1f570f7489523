#include "zone_passes.h"

namespace cosim::orchestrator {

void ZonePassRecorder::start(const std::filesystem::path& run_folder) {
  writer_ = std::make_unique<analysis::ZonePassWriter>(run_folder / analysis::kZonePassesFile);
  tracker_ = {};
}

void ZonePassRecorder::resume(const std::filesystem::path& run_folder, State state) {
  const auto path = run_folder / analysis::kZonePassesFile;
  analysis::truncateZonePasses(path, state.rows);
  writer_ =
      std::make_unique<analysis::ZonePassWriter>(path, analysis::ZonePassWriter::Mode::append);
  tracker_.restore({std::move(state.open), state.coating_outside, true});
}

void ZonePassRecorder::update(double time, const std::vector<std::int64_t>& ids,
                              const std::vector<char>& in_zone) {
  tracker_.update(time, ids, in_zone);
  flush();
}

void ZonePassRecorder::credit(const link::ParticleData& fr) { tracker_.credit(fr); }

void ZonePassRecorder::leave(const std::vector<std::int64_t>& deleted_ids, double time) {
  tracker_.leave(deleted_ids, time);
  flush();
}

void ZonePassRecorder::close(double time) {
  tracker_.close(time);
  flush();
}

void ZonePassRecorder::write(const std::vector<analysis::ZonePass>& passes) {
  if (!passes.empty() && writer_) writer_->write(passes);
}

ZonePassRecorder::State ZonePassRecorder::state() const {
  const auto t = tracker_.state();
  return {writer_ ? writer_->rows() : 0, t.open, t.coating_outside};
}

void ZonePassRecorder::flush() {
  if (tracker_.closed().empty() || !writer_) return;
  writer_->write(tracker_.takeClosed());
}

}  // namespace cosim::orchestrator
