#include "cosim/analysis/particle_file.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/util/all_finite.h"
#include "cosim/util/errors.h"
#include "hdf5_handle.h"

namespace cosim::analysis {

struct ParticleFile::Impl {
  h5::Handle file;
  h5::Handle snapshots;
};

ParticleFile::ParticleFile(const std::filesystem::path& path)
    : path_(path), impl_(std::make_unique<Impl>()) {
  const std::string name = path.string();
  if (!std::filesystem::exists(path)) {
    throw InputError(name +
                     " does not exist: the run recorded no particles (is the "
                     "output interval set and did the run reach its first output time?)");
  }
  impl_->file = h5::openFile(name, H5F_ACC_RDONLY, "for reading");
  const std::string format = h5::readStringAttribute(impl_->file, "format", name);
  if (format != "cosim-particles") {
    throw InputError(name + " has format '" + format + "', expected 'cosim-particles'");
  }
  std::stringstream fs(h5::readStringAttribute(impl_->file, "fields", name));
  for (std::string f; std::getline(fs, f, ',');) {
    if (!f.empty()) fields_.push_back(f);
  }
  if (h5::hasAttribute(impl_->file, "run_id")) {
    run_id_ = h5::readStringAttribute(impl_->file, "run_id", name);
    cg_ = h5::readDoubleAttribute(impl_->file, "cg", name);
  }
  impl_->snapshots = h5::openGroup(impl_->file, "snapshots", name);
  for (const auto& g : h5::members(impl_->snapshots, name)) {
    h5::Handle group = h5::openGroup(impl_->snapshots, g, name);
    SnapshotInfo s;
    s.group = g;
    s.time = h5::readDoubleAttribute(group, "time", name);
    s.count = static_cast<std::uint64_t>(h5::readDoubleAttribute(group, "count", name));
    snapshots_.push_back(s);
  }
  // Group names are zero-padded creation indices: sorting by (time, name) and keeping the last
  // of equal times keeps the replacement of a snapshot (see ParticleRecorder::write).
  std::sort(snapshots_.begin(), snapshots_.end(), [](const SnapshotInfo& a, const SnapshotInfo& b) {
    return a.time != b.time ? a.time < b.time : a.group < b.group;
  });
  std::vector<SnapshotInfo> unique;
  for (const auto& s : snapshots_) {
    if (!unique.empty() && unique.back().time == s.time)
      unique.back() = s;
    else
      unique.push_back(s);
  }
  snapshots_ = std::move(unique);
}

ParticleFile::~ParticleFile() = default;
ParticleFile::ParticleFile(ParticleFile&&) noexcept = default;
ParticleFile& ParticleFile::operator=(ParticleFile&&) noexcept = default;

bool ParticleFile::hasField(const std::string& field) const {
  return std::find(fields_.begin(), fields_.end(), field) != fields_.end();
}

std::vector<std::int64_t> ParticleFile::ids(std::size_t snapshot) const {
  const std::string name = path_.string();
  h5::Handle g = h5::openGroup(impl_->snapshots, snapshots_.at(snapshot).group, name);
  return h5::readInt64s(g, "id", name);
}

std::vector<double> ParticleFile::read(std::size_t snapshot, const std::string& field,
                                       std::uint64_t* components) const {
  const std::string name = path_.string();
  if (!hasField(field)) {
    std::string have;
    for (const auto& f : fields_) have += (have.empty() ? "" : ", ") + f;
    throw InputError(name + " has no field '" + field + "' (recorded: " + have +
                     "); record it in the scenario's output fields");
  }
  const SnapshotInfo& info = snapshots_.at(snapshot);
  h5::Handle g = h5::openGroup(impl_->snapshots, info.group, name);
  const std::string where = name + ", snapshot " + info.group +
                            " (t = " + formatShortest(info.time) + " s), dataset '" + field + "'";
  std::uint64_t rows = 0, cols = 0;
  std::vector<double> v;
  try {
    v = h5::readDoubles(g, field, rows, cols, name);
  } catch (const std::exception& e) {
    throw Error(kindOf(e, ErrorKind::input),
                where + ": " + e.what() + " (the file is damaged or was not written by cosim)");
  }
  // One row per parcel of the snapshot, every value a number: anything else is a damaged file,
  // and would pass silently into every statistic of a report.
  const std::uint64_t n = h5::rowsOf(g, "id", name);
  if (rows != n)
    throw InputError(where + " has " + std::to_string(rows) + " rows for the " + std::to_string(n) +
                     " parcel ids of the snapshot: the file is damaged or was not "
                     "written by cosim");
  if (!util::allFinite(v)) {
    const auto k = static_cast<std::size_t>(
        std::find_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }) - v.begin());
    throw InputError(where + ": value " + std::to_string(v[k]) + " (row " +
                     std::to_string(k / std::max<std::uint64_t>(cols, 1)) +
                     ") is not a finite number; cosim never records one, so the file "
                     "is damaged");
  }
  if (components != nullptr) *components = cols;
  return v;
}

}  // namespace cosim::analysis
