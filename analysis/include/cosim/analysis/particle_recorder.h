// ParticleRecorder: per-particle snapshots of a run in run_dir/particles.h5 (HDF5) plus
// run_dir/particles.xmf (XDMF temporal collection of Polyvertex grids, one cell per particle) so
// ParaView's default reader and view show the particles, coloured by any recorded field.
//
// Layout of particles.h5 (see docs/analysis.md); every dataset carries the string attributes
// `units` and `description`:
//   /                     attributes format="cosim-particles", version=1, fields="a,b,..."
//                         run_id (as in summary.json), cg (coarse-graining factor), time_units="s"
//   /xdmf_connectivity    int64 [M >= every count]: 0, 1, 2, ...; particles.xmf takes its first
//                         N values as the Polyvertex cells of a snapshot
//   /snapshots/000000     group, attributes time [s], count [-]
//     id                  int64 [N]
//     <field>             float64 [N] or [N, components]   (e.g. position [N,3])
//
// Crash safety: the file is opened, the snapshot written, flushed and closed on every write(),
// so a crash of the run between writes leaves a complete, readable file. The XDMF file is
// replaced atomically (write + rename) after every snapshot.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cosim/link/particle_data.h"

namespace cosim::analysis {

inline constexpr const char* kParticlesFile = "particles.h5";
inline constexpr const char* kParticlesXdmf = "particles.xmf";

// Which run a particles.h5 belongs to: written at its root.
struct RunIdentity {
  std::string run_id;  // the run's id, as in summary.json
  double cg = 1.0;     // coarse-graining factor: one parcel stands for cg^3 real grains
};

class ParticleRecorder {
 public:
  enum class Mode {
    create,  // start a new particles.h5 (an existing one is replaced)
    append,  // continue an existing particles.h5 (restart); created if absent
  };

  // fields: names of the per-particle fields to record (cosim::field names; ids always are).
  // identity: written at the root of a new file; when appending, the file's own is kept (and
  // `identity` written only into a file recorded before identities were). Throws
  // std::runtime_error naming the file if it cannot be created.
  ParticleRecorder(const std::filesystem::path& run_dir, std::vector<std::string> fields,
                   const RunIdentity& identity, Mode mode = Mode::create);

  // Append one snapshot. `particles` must hold every recorded field with ids.size() rows.
  // Times must increase; a snapshot at the same time as the previous one replaces it (e.g. the
  // final state after the last coating credit). Throws std::runtime_error with the field / time
  // at fault.
  void write(double time, const cosim::link::ParticleData& particles);

  // Resume: removes the snapshots after `time` (recorded after the checkpoint the run continues
  // from), so the file reads as if the run had never gone past it.
  void truncateAfter(double time);

  std::size_t snapshots() const { return entries_.size(); }
  // The identity at the root of the file (for an appended file: the one it was created with).
  const RunIdentity& identity() const { return identity_; }
  const std::filesystem::path& file() const { return h5_; }
  const std::filesystem::path& xdmf() const { return xmf_; }

 private:
  struct Entry {
    std::string group;
    double time;
    std::uint64_t count;
  };
  struct FieldShape {
    std::string name;
    std::uint64_t components;
  };
  void writeXdmf() const;

  std::filesystem::path h5_;
  std::filesystem::path xmf_;
  std::vector<std::string> fields_;
  std::vector<FieldShape> shapes_;  // components known after the first snapshot with particles
  std::vector<Entry> entries_;
  std::size_t next_index_ = 0;  // name of the next snapshot group
  RunIdentity identity_;
  std::uint64_t connectivity_ = 0;  // length of /xdmf_connectivity
};

}  // namespace cosim::analysis
