#include "cosim/analysis/particle_recorder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"
#include "hdf5_handle.h"

namespace cosim::analysis {

namespace {
std::string groupName(std::size_t index) { return fmt::format("{:06d}", index); }

std::string joined(const std::vector<std::string>& xs) {
  std::string s;
  for (const auto& x : xs) s += (s.empty() ? "" : ",") + x;
  return s;
}

constexpr const char* kConnectivity = "xdmf_connectivity";

void writeIdentity(hid_t f, const RunIdentity& id, const std::string& file) {
  h5::writeAttribute(f, "run_id", id.run_id, file);
  h5::writeAttribute(f, "cg", id.cg, file);
  h5::writeAttribute(f, "time_units", std::string("s"), file);
}

// /xdmf_connectivity = 0, 1, ..., length-1, long enough for `count` particles. particles.xmf
// gives every snapshot the first `count` of them as its Polyvertex cells (one per particle):
// without explicit cells ParaView's Xdmf3 reader makes points only, which its default Surface
// view does not draw. Grown by doubling (a replaced dataset's space is not reclaimed by HDF5).
void growConnectivity(hid_t f, std::uint64_t count, std::uint64_t& length,
                      const std::string& file) {
  if (count <= length) return;
  const std::uint64_t n = std::max(count, 2 * length);
  std::vector<std::int64_t> index(n);
  for (std::uint64_t i = 0; i < n; ++i) index[i] = static_cast<std::int64_t>(i);
  if (h5::exists(f, kConnectivity) && H5Ldelete(f, kConnectivity, H5P_DEFAULT) < 0)
    throw ResourceError(file + ": cannot replace /" + std::string(kConnectivity));
  h5::writeInt64s(f, kConnectivity, index.data(), n, file);
  h5::describeDataset(f, kConnectivity, "-",
                      "0, 1, 2, ...: particles.xmf takes the first `count` values as the "
                      "Polyvertex cells (one per particle) of a snapshot",
                      file);
  length = n;
}

std::string unitsOf(const std::string& field) {
  const std::string u = cosim::field::units(field);
  return u.empty() ? "unknown" : u;
}

std::string descriptionOf(const std::string& field) {
  const std::string d = cosim::field::description(field);
  return d.empty() ? "per-particle field '" + field + "' sent by the particles participant" : d;
}
}  // namespace

ParticleRecorder::ParticleRecorder(const std::filesystem::path& run_dir,
                                   std::vector<std::string> fields, const RunIdentity& identity,
                                   Mode mode)
    : h5_(run_dir / kParticlesFile),
      xmf_(run_dir / kParticlesXdmf),
      fields_(std::move(fields)),
      identity_(identity) {
  for (const auto& f : fields_) {
    if (f.empty() || f == "id" || f.find_first_of(",/") != std::string::npos) {
      throw std::logic_error("ParticleRecorder: field name '" + f +
                             "' is not allowed (empty, 'id', or containing ',' or '/')");
    }
    shapes_.push_back({f, cosim::field::components(f)});
  }
  std::error_code ec;
  std::filesystem::create_directories(run_dir, ec);
  if (ec)
    throw Error(kindOfErrno(ec.value()), "ParticleRecorder: cannot create run folder " +
                                             run_dir.string() + ": " + ec.message());

  const std::string file = h5_.string();
  if (mode == Mode::append && std::filesystem::exists(h5_)) {
    h5::Handle f = h5::openFile(file, H5F_ACC_RDWR, "to continue recording");
    const std::string had = h5::readStringAttribute(f, "fields", file);
    if (had != joined(fields_)) {
      throw InputError(file + " records fields '" + had + "' but this run records '" +
                       joined(fields_) + "': use a new run folder or the same fields");
    }
    h5::Handle snaps = h5::openGroup(f, "snapshots", file);
    for (const auto& name : h5::members(snaps, file)) {
      h5::Handle g = h5::openGroup(snaps, name, file);
      const double t = h5::readDoubleAttribute(g, "time", file);
      const auto n = static_cast<std::uint64_t>(h5::readDoubleAttribute(g, "count", file));
      entries_.push_back({name, t, n});
      next_index_ = std::max<std::size_t>(next_index_, std::stoul(name) + 1);
      if (n > 0) {
        for (auto& s : shapes_) {
          std::uint64_t rows = 0, cols = 0;
          h5::readDoubles(g, s.name, rows, cols, file);
          s.components = cols;
        }
      }
    }
    if (h5::hasAttribute(f, "run_id")) {
      identity_.run_id = h5::readStringAttribute(f, "run_id", file);
      identity_.cg = h5::readDoubleAttribute(f, "cg", file);
    } else {
      writeIdentity(f, identity_, file);  // recorded before files carried their identity
    }
    if (h5::exists(f, kConnectivity)) connectivity_ = h5::readInt64s(f, kConnectivity, file).size();
    std::uint64_t most = 0;
    for (const auto& e : entries_) most = std::max(most, e.count);
    growConnectivity(f, most, connectivity_, file);
    H5Fflush(f, H5F_SCOPE_GLOBAL);
    writeXdmf();
    return;
  }
  h5::Handle f = h5::createFile(file);
  h5::writeAttribute(f, "format", std::string("cosim-particles"), file);
  h5::writeAttribute(f, "version", std::int64_t{1}, file);
  h5::writeAttribute(f, "fields", joined(fields_), file);
  writeIdentity(f, identity_, file);
  h5::createGroup(f, "snapshots", file);
  H5Fflush(f, H5F_SCOPE_GLOBAL);
  writeXdmf();
}

void ParticleRecorder::write(double time, const cosim::link::ParticleData& particles) {
  const std::string file = h5_.string();
  if (!std::isfinite(time)) throw std::logic_error(file + ": snapshot time is not finite");
  const bool replace = !entries_.empty() && time == entries_.back().time;
  if (!entries_.empty() && !replace && !(time > entries_.back().time)) {
    throw InputError(file + ": snapshot time " + std::to_string(time) +
                     " s does not follow the previous one (" +
                     std::to_string(entries_.back().time) + " s); times must increase");
  }
  const std::uint64_t n = particles.size();
  for (auto& s : shapes_) {
    if (!particles.has(s.name)) {
      throw PeerError("ParticleRecorder: the particle state at t = " + std::to_string(time) +
                      " s has no field '" + s.name +
                      "'; the particles participant must send it (scenario output fields)");
    }
    const auto len = static_cast<std::uint64_t>(particles.get(s.name).size());
    if (s.components == 0 && n > 0) s.components = len / n;  // field unknown to cosim::field
    const std::uint64_t comps = s.components == 0 ? 1 : s.components;
    if (len != n * comps) {
      throw PeerError("ParticleRecorder: field '" + s.name + "' at t = " + std::to_string(time) +
                      " s has " + std::to_string(len) + " values for " + std::to_string(n) +
                      " particles x " + std::to_string(comps) + " components");
    }
  }

  // Group names count every snapshot ever written, so a replacement gets a fresh name and the
  // old group is unlinked only after the new one is complete (a reader keeps the later of two
  // groups with equal times, should a crash fall in between).
  const std::string name = groupName(next_index_);
  {
    h5::Handle f = h5::openFile(file, H5F_ACC_RDWR, "to add a snapshot");
    h5::Handle snaps = h5::openGroup(f, "snapshots", file);
    if (h5::exists(snaps, name)) {
      throw InputError(file + ": snapshot " + name +
                       " already exists (two recorders on one file?)");
    }
    h5::Handle g = h5::createGroup(snaps, name, file);
    h5::writeAttribute(g, "time", time, file);
    h5::writeAttribute(g, "count", static_cast<std::int64_t>(n), file);
    h5::writeInt64s(g, "id", particles.ids.data(), n, file);
    h5::describeDataset(g, "id", "-",
                        "particle id given by the particles participant, the same particle's "
                        "over the whole run (LIGGGHTS atom id)",
                        file);
    for (const auto& s : shapes_) {
      h5::writeDoubles(g, s.name, particles.get(s.name).data(), n,
                       s.components == 0 ? 1 : s.components, file);
      h5::describeDataset(g, s.name, unitsOf(s.name), descriptionOf(s.name), file);
    }
    growConnectivity(f, n, connectivity_, file);
    if (H5Fflush(f, H5F_SCOPE_GLOBAL) < 0)
      throw ResourceError(file + ": flush failed (disk full?)");
    if (replace) {
      if (H5Ldelete(snaps, entries_.back().group.c_str(), H5P_DEFAULT) < 0) {
        throw ResourceError(file + ": cannot replace snapshot " + entries_.back().group);
      }
      H5Fflush(f, H5F_SCOPE_GLOBAL);
    }
  }  // closed here: what is on disk is complete
  if (replace) entries_.pop_back();
  entries_.push_back({name, time, n});
  ++next_index_;
  writeXdmf();
}

void ParticleRecorder::truncateAfter(double time) {
  const std::string file = h5_.string();
  if (entries_.empty() || !(entries_.back().time > time)) return;
  {
    h5::Handle f = h5::openFile(file, H5F_ACC_RDWR, "to cut it back to a checkpoint");
    h5::Handle snaps = h5::openGroup(f, "snapshots", file);
    while (!entries_.empty() && entries_.back().time > time) {
      if (H5Ldelete(snaps, entries_.back().group.c_str(), H5P_DEFAULT) < 0)
        throw ResourceError(file + ": cannot remove snapshot " + entries_.back().group);
      entries_.pop_back();
    }
    if (H5Fflush(f, H5F_SCOPE_GLOBAL) < 0)
      throw ResourceError(file + ": flush failed (disk full?)");
  }
  next_index_ = entries_.empty() ? 0 : std::stoul(entries_.back().group) + 1;
  writeXdmf();
}

void ParticleRecorder::writeXdmf() const {
  bool hasPosition = false;
  for (const auto& s : shapes_) hasPosition = hasPosition || s.name == cosim::field::position;
  if (!hasPosition) return;  // nothing to place in space; particles.h5 alone holds the data

  const std::string h5name = h5_.filename().string();
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<Xdmf Version=\"2.0\">\n <Domain>\n"
    << "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& e : entries_) {
    if (e.count == 0) continue;  // an empty grid confuses readers; the time is still in the .h5
    const std::string path = h5name + ":/snapshots/" + e.group + "/";
    x << "   <Grid Name=\"t" << e.group << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << e.time << "\"/>\n"
      << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << e.count
      << "\" NodesPerElement=\"1\">\n"
      << "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"" << e.count
      << "\" Type=\"HyperSlab\">\n"
      << "      <DataItem Dimensions=\"3 1\" Format=\"XML\">0 1 " << e.count << "</DataItem>\n"
      << "      <DataItem Dimensions=\"" << connectivity_
      << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << h5name << ":/" << kConnectivity
      << "</DataItem>\n"
      << "     </DataItem>\n    </Topology>\n"
      << "    <Geometry GeometryType=\"XYZ\">\n"
      << "     <DataItem Dimensions=\"" << e.count
      << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << path
      << "position</DataItem>\n    </Geometry>\n"
      << "    <Attribute Name=\"id\" AttributeType=\"Scalar\" Center=\"Node\">\n"
      << "     <DataItem Dimensions=\"" << e.count
      << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << path
      << "id</DataItem>\n    </Attribute>\n";
    for (const auto& s : shapes_) {
      if (s.name == cosim::field::position) continue;
      const std::uint64_t c = s.components == 0 ? 1 : s.components;
      const char* type = c == 1 ? "Scalar" : c == 3 ? "Vector" : "Matrix";
      x << "    <Attribute Name=\"" << s.name << "\" AttributeType=\"" << type
        << "\" Center=\"Node\">\n"
        << "     <DataItem Dimensions=\"" << e.count;
      if (c != 1) x << " " << c;
      x << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << path << s.name
        << "</DataItem>\n    </Attribute>\n";
    }
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  writeFileAtomically(xmf_, x.str());
}

}  // namespace cosim::analysis
