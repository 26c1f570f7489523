// Reading particles.h5 written by ParticleRecorder (layout in particle_recorder.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace cosim::analysis {

struct SnapshotInfo {
  std::string group;  // name under /snapshots
  double time = 0;    // [s]
  std::uint64_t count = 0;
};

class ParticleFile {
 public:
  // Opens read-only; throws std::runtime_error naming the file if it is missing or not ours.
  explicit ParticleFile(const std::filesystem::path& path);
  ~ParticleFile();
  ParticleFile(ParticleFile&&) noexcept;
  ParticleFile& operator=(ParticleFile&&) noexcept;

  const std::filesystem::path& path() const { return path_; }
  // The run the file belongs to (root attributes run_id, as in summary.json, and cg); "" and 1
  // for a file recorded before they were written.
  const std::string& runId() const { return run_id_; }
  double cg() const { return cg_; }
  const std::vector<std::string>& fields() const { return fields_; }
  bool hasField(const std::string& name) const;
  // Snapshots sorted by time.
  const std::vector<SnapshotInfo>& snapshots() const { return snapshots_; }

  std::vector<std::int64_t> ids(std::size_t snapshot) const;
  // Values of a field, row-major [count x components]; components receives the width.
  std::vector<double> read(std::size_t snapshot, const std::string& field,
                           std::uint64_t* components = nullptr) const;

 private:
  struct Impl;
  std::filesystem::path path_;
  std::vector<std::string> fields_;
  std::string run_id_;
  double cg_ = 1.0;
  std::vector<SnapshotInfo> snapshots_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cosim::analysis
