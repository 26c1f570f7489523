#include "cosim/analysis/particle_recorder.h"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "cosim/analysis/particle_file.h"
#include "cosim/link/fields.h"
#include "cosim/util/child_process.h"

namespace fs = std::filesystem;
using namespace cosim::analysis;

namespace {
// A fresh folder, removed at the end of the test if it passed.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(fs::temp_directory_path() /
              ("cosim_analysis_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    if (!::testing::Test::HasFailure()) fs::remove_all(path_);
  }
  operator const fs::path&() const { return path_; }
  fs::path operator/(const std::string& s) const { return path_ / s; }

 private:
  fs::path path_;
};

// Particles with ids `ids`; every value derived from the id and the time, so a reader can check
// it without keeping the writer's arrays.
cosim::link::ParticleData state(const std::vector<std::int64_t>& ids, double t) {
  cosim::link::ParticleData p;
  p.ids = ids;
  auto& pos = p.field(cosim::field::position);
  auto& vel = p.field(cosim::field::velocity);
  auto& rad = p.field(cosim::field::radius);
  auto& cm = p.field(cosim::field::coating_mass);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const double id = static_cast<double>(ids[i]);
    for (int c = 0; c < 3; ++c) {
      pos[3 * i + c] = id + 0.1 * c + t;
      vel[3 * i + c] = -id - c;
    }
    rad[i] = 7.5e-4;
    cm[i] = 1e-9 * id * t;
  }
  return p;
}

const RunIdentity kIdentity{"run-1234abcd", 3.0};

const std::vector<std::string> kFields = {cosim::field::position, cosim::field::velocity,
                                          cosim::field::radius, cosim::field::coating_mass};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Minimal XML well-formedness: declaration, balanced and properly nested tags.
bool wellFormed(const std::string& xml, std::string& why) {
  std::vector<std::string> stack;
  std::regex tag(R"re(<(/?)([A-Za-z_][\w:.-]*)([^<>]*?)(/?)>|<\?[^>]*\?>|<!DOCTYPE[^>]*>)re");
  std::size_t pos = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), tag); it != std::sregex_iterator();
       ++it) {
    const auto& m = *it;
    pos = static_cast<std::size_t>(m.position() + m.length());
    if (m[2].length() == 0) continue;  // declaration / doctype
    if (m[1] == "/") {
      if (stack.empty() || stack.back() != m[2]) {
        why = "unexpected </" + m[2].str() + ">";
        return false;
      }
      stack.pop_back();
    } else if (m[4] != "/") {
      stack.push_back(m[2]);
    }
  }
  (void)pos;
  if (!stack.empty()) {
    why = "unclosed <" + stack.back() + ">";
    return false;
  }
  return true;
}
}  // namespace

TEST(ParticleRecorder, RoundTripWithChangingParticleCounts) {
  const TempDir dir("roundtrip");
  const std::vector<std::vector<std::int64_t>> ids = {
      {1, 2, 3, 4, 5}, {1, 2, 3, 4, 5, 6, 7}, {2, 5, 6, 9}};
  const std::vector<double> times = {0.01, 0.02, 0.03};
  {
    ParticleRecorder rec(dir, kFields, kIdentity);
    for (std::size_t s = 0; s < ids.size(); ++s) rec.write(times[s], state(ids[s], times[s]));
    EXPECT_EQ(rec.snapshots(), 3u);
  }
  ParticleFile f(dir / kParticlesFile);
  ASSERT_EQ(f.snapshots().size(), 3u);
  EXPECT_EQ(f.fields(), kFields);
  for (std::size_t s = 0; s < ids.size(); ++s) {
    EXPECT_DOUBLE_EQ(f.snapshots()[s].time, times[s]);
    EXPECT_EQ(f.snapshots()[s].count, ids[s].size());
    EXPECT_EQ(f.ids(s), ids[s]);
    std::uint64_t comps = 0;
    const auto pos = f.read(s, cosim::field::position, &comps);
    EXPECT_EQ(comps, 3u);
    const auto cm = f.read(s, cosim::field::coating_mass, &comps);
    EXPECT_EQ(comps, 1u);
    for (std::size_t i = 0; i < ids[s].size(); ++i) {
      const double id = static_cast<double>(ids[s][i]);
      EXPECT_DOUBLE_EQ(pos[3 * i + 2], id + 0.2 + times[s]);
      EXPECT_DOUBLE_EQ(cm[i], 1e-9 * id * times[s]);
    }
  }
}

namespace {
// A string attribute of `object` in `file`, read with the HDF5 C API ("<missing>" if absent).
std::string stringAttribute(const fs::path& file, const std::string& object,
                            const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t o = H5Oopen(f, object.c_str(), H5P_DEFAULT);
  std::string value = "<missing>";
  if (o >= 0 && H5Aexists(o, name.c_str()) > 0) {
    const hid_t a = H5Aopen(o, name.c_str(), H5P_DEFAULT);
    const hid_t t = H5Aget_type(a);
    value.assign(H5Tget_size(t), '\0');
    H5Aread(a, t, value.data());
    while (!value.empty() && value.back() == '\0') value.pop_back();
    H5Tclose(t);
    H5Aclose(a);
  }
  if (o >= 0) H5Oclose(o);
  H5Fclose(f);
  return value;
}

double doubleAttribute(const fs::path& file, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  double v = std::nan("");
  if (H5Aexists(f, name.c_str()) > 0) {
    const hid_t a = H5Aopen(f, name.c_str(), H5P_DEFAULT);
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
  }
  H5Fclose(f);
  return v;
}
}  // namespace

TEST(ParticleRecorder, EveryDatasetCarriesUnitsAndMeaningAndTheRootTheRunIdAndCg) {
  const TempDir dir("describe");
  {
    ParticleRecorder rec(dir, kFields, kIdentity);
    rec.write(0.1, state({1, 2}, 0.1));
    rec.write(0.2, state({1, 2, 3}, 0.2));
  }
  const fs::path h5 = dir / kParticlesFile;
  EXPECT_EQ(stringAttribute(h5, "/", "run_id"), "run-1234abcd");
  EXPECT_EQ(doubleAttribute(h5, "cg"), 3.0);
  EXPECT_EQ(stringAttribute(h5, "/", "time_units"), "s");
  // The units a reader needs, by hand from the field's meaning.
  const std::vector<std::pair<std::string, std::string>> units = {
      {"id", "-"}, {"position", "m"}, {"velocity", "m/s"}, {"radius", "m"}, {"coating_mass", "kg"}};
  for (const char* group : {"/snapshots/000000/", "/snapshots/000001/"}) {
    for (const auto& [name, unit] : units) {
      EXPECT_EQ(stringAttribute(h5, group + name, "units"), unit) << group << name;
      const std::string what = stringAttribute(h5, group + name, "description");
      EXPECT_NE(what, "<missing>") << group << name;
      EXPECT_GT(what.size(), 10u) << group << name << ": '" << what << "'";
    }
  }
  EXPECT_NE(stringAttribute(h5, "/snapshots/000000/position", "description").find("position"),
            std::string::npos);
  EXPECT_NE(stringAttribute(h5, "/snapshots/000000/coating_mass", "description").find("coating"),
            std::string::npos);
  EXPECT_EQ(stringAttribute(h5, "/xdmf_connectivity", "units"), "-");
  EXPECT_EQ(ParticleFile(h5).runId(), "run-1234abcd");
  EXPECT_EQ(ParticleFile(h5).cg(), 3.0);

  // Appending (a resumed run) keeps the identity the file was created with.
  {
    ParticleRecorder rec(dir, kFields, RunIdentity{"another-id", 5.0},
                         ParticleRecorder::Mode::append);
    EXPECT_EQ(rec.identity().run_id, "run-1234abcd");
    EXPECT_EQ(rec.identity().cg, 3.0);
    rec.write(0.3, state({1}, 0.3));
  }
  EXPECT_EQ(stringAttribute(h5, "/", "run_id"), "run-1234abcd");
  EXPECT_EQ(doubleAttribute(h5, "cg"), 3.0);
  EXPECT_EQ(stringAttribute(h5, "/snapshots/000002/coating_mass", "units"), "kg");
}

TEST(ParticleRecorder, XdmfGivesEveryParticleItsOwnPolyvertexCell) {
  // ParaView's Xdmf3 reader makes cells only from explicit connectivity; each snapshot's
  // topology is the first `count` values of /xdmf_connectivity, which must be 0, 1, 2, ...
  const TempDir dir("cells");
  {
    ParticleRecorder rec(dir, kFields, kIdentity);
    rec.write(0.1, state({4, 9}, 0.1));
    rec.write(0.2, state({1, 2, 3, 4, 5, 6, 7}, 0.2));  // grows the connectivity
    rec.write(0.3, state({2, 3, 8}, 0.3));
  }
  const hid_t f = H5Fopen((dir / kParticlesFile).c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, "/xdmf_connectivity", H5P_DEFAULT);
  ASSERT_GE(d, 0);
  const hid_t space = H5Dget_space(d);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  std::vector<std::int64_t> index(n);
  H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, index.data());
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
  ASSERT_GE(n, 7u);
  for (std::size_t i = 0; i < index.size(); ++i) EXPECT_EQ(index[i], static_cast<std::int64_t>(i));

  const std::string x = slurp(dir / kParticlesXdmf);
  std::regex topology(
      R"re(<Topology TopologyType="Polyvertex" NumberOfElements="(\d+)" NodesPerElement="1">\s*)re"
      R"re(<DataItem ItemType="HyperSlab" Dimensions="(\d+)" Type="HyperSlab">\s*)re"
      R"re(<DataItem Dimensions="3 1" Format="XML">0 1 (\d+)</DataItem>\s*)re"
      R"re(<DataItem Dimensions="(\d+)" NumberType="Int" Precision="8" Format="HDF">particles\.h5:/xdmf_connectivity</DataItem>)re");
  std::vector<int> counts;
  for (auto it = std::sregex_iterator(x.begin(), x.end(), topology); it != std::sregex_iterator();
       ++it) {
    EXPECT_EQ((*it)[1], (*it)[2]);
    EXPECT_EQ((*it)[1], (*it)[3]);
    EXPECT_EQ(std::stoul((*it)[4]), n);
    counts.push_back(std::stoi((*it)[1]));
  }
  EXPECT_EQ(counts, (std::vector<int>{2, 7, 3})) << x;
}

TEST(ParticleRecorder, EmptySnapshotIsRecordedAndSkippedInXdmf) {
  const TempDir dir("empty");
  ParticleRecorder rec(dir, kFields, kIdentity);
  rec.write(0.5, state({}, 0.5));
  rec.write(1.0, state({3}, 1.0));
  ParticleFile f(dir / kParticlesFile);
  ASSERT_EQ(f.snapshots().size(), 2u);
  EXPECT_EQ(f.snapshots()[0].count, 0u);
  EXPECT_TRUE(f.read(0, cosim::field::coating_mass).empty());
  const std::string x = slurp(dir / kParticlesXdmf);
  EXPECT_EQ(x.find("/snapshots/000000/"), std::string::npos);
  EXPECT_NE(x.find("/snapshots/000001/position"), std::string::npos);
}

TEST(ParticleRecorder, XdmfIsWellFormedTemporalPolyvertexCollection) {
  const TempDir dir("xdmf");
  {
    ParticleRecorder rec(dir, kFields, kIdentity);
    rec.write(0.1, state({1, 2}, 0.1));
    rec.write(0.2, state({1, 2, 3}, 0.2));
  }
  const std::string x = slurp(dir / kParticlesXdmf);
  std::string why;
  EXPECT_TRUE(wellFormed(x, why)) << why << "\n" << x;
  EXPECT_NE(x.find("CollectionType=\"Temporal\""), std::string::npos);
  // An independent XML parser agrees (Python's, when there is a python3).
  auto python = [](const std::vector<std::string>& args) {
    std::vector<std::string> argv{"python3"};
    argv.insert(argv.end(), args.begin(), args.end());
    try {
      return cosim::util::runProgram(argv, "/dev/null");
    } catch (const std::exception&) {
      return -1;  // no python3
    }
  };
  if (python({"-c", "pass"}) == 0) {
    EXPECT_EQ(python({"-c", "import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])",
                      (dir / kParticlesXdmf).string()}),
              0)
        << "xml.etree could not parse " << (dir / kParticlesXdmf).string();
  }
  // One Uniform grid per snapshot, each with its own particle count and time.
  std::regex grid(
      R"re(<Time Value="([0-9.e-]+)"/>\s*<Topology TopologyType="Polyvertex" NumberOfElements="(\d+)")re");
  std::vector<std::pair<double, int>> found;
  for (auto it = std::sregex_iterator(x.begin(), x.end(), grid); it != std::sregex_iterator();
       ++it) {
    found.emplace_back(std::stod((*it)[1]), std::stoi((*it)[2]));
  }
  ASSERT_EQ(found.size(), 2u);
  EXPECT_DOUBLE_EQ(found[0].first, 0.1);
  EXPECT_EQ(found[0].second, 2);
  EXPECT_DOUBLE_EQ(found[1].first, 0.2);
  EXPECT_EQ(found[1].second, 3);
  // Every HDF5 reference points at a dataset that exists, with the stated first dimension.
  ParticleFile f(dir / kParticlesFile);
  std::regex item(
      R"re(<DataItem Dimensions="(\d+)[^"]*"[^>]*>particles\.h5:/snapshots/(\d+)/(\w+)</DataItem>)re");
  int refs = 0;
  for (auto it = std::sregex_iterator(x.begin(), x.end(), item); it != std::sregex_iterator();
       ++it, ++refs) {
    std::size_t snap = f.snapshots().size();  // index of the referenced group among the snapshots
    for (std::size_t i = 0; i < f.snapshots().size(); ++i) {
      if (f.snapshots()[i].group == (*it)[2]) snap = i;
    }
    ASSERT_LT(snap, f.snapshots().size()) << "XDMF references a missing group " << (*it)[2];
    const std::string field = (*it)[3];
    const auto rows = std::stoul((*it)[1]);
    if (field == "id") {
      EXPECT_EQ(f.ids(snap).size(), rows);
    } else {
      std::uint64_t comps = 0;
      const auto values = f.read(snap, field, &comps);
      ASSERT_GT(comps, 0u) << field;
      EXPECT_EQ(values.size() / comps, rows) << field;
    }
  }
  EXPECT_EQ(refs, 2 * 5);  // position + id + velocity + radius + coating_mass per grid
  EXPECT_NE(x.find("Name=\"coating_mass\" AttributeType=\"Scalar\""), std::string::npos);
  EXPECT_NE(x.find("Name=\"velocity\" AttributeType=\"Vector\""), std::string::npos);
}

TEST(ParticleRecorder, SnapshotsSurviveACrashOfTheWriter) {
  const TempDir dir("crash");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // The child records two snapshots and dies without running any destructor.
    ParticleRecorder* rec = new ParticleRecorder(dir, kFields, kIdentity);
    rec->write(0.1, state({1, 2, 3}, 0.1));
    rec->write(0.2, state({1, 2, 3, 4}, 0.2));
    ::_exit(3);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 3);
  ParticleFile f(dir / kParticlesFile);
  ASSERT_EQ(f.snapshots().size(), 2u);
  EXPECT_EQ(f.ids(1), (std::vector<std::int64_t>{1, 2, 3, 4}));
  EXPECT_DOUBLE_EQ(f.read(1, cosim::field::coating_mass)[3], 1e-9 * 4 * 0.2);
  EXPECT_TRUE(fs::exists(dir / kParticlesXdmf));
}

TEST(ParticleRecorder, SnapshotAtTheSameTimeReplacesThePreviousOne) {
  // The orchestrator records the last step, credits the last coating, and records again.
  const TempDir dir("replace");
  {
    ParticleRecorder rec(dir, kFields, kIdentity);
    rec.write(0.1, state({1, 2}, 0.1));
    rec.write(0.2, state({1, 2}, 0.2));
    auto final = state({1, 2, 3}, 0.2);
    final.field(cosim::field::coating_mass)[0] = 42.0;
    rec.write(0.2, final);
    EXPECT_EQ(rec.snapshots(), 2u);
  }
  {
    ParticleFile f(dir / kParticlesFile);
    ASSERT_EQ(f.snapshots().size(), 2u);
    EXPECT_EQ(f.snapshots()[1].count, 3u);
    EXPECT_EQ(f.read(1, cosim::field::coating_mass)[0], 42.0);
  }
  const std::string x = slurp(dir / kParticlesXdmf);
  EXPECT_EQ(x.find("/snapshots/000001/"), std::string::npos);  // the replaced group is gone
  EXPECT_NE(x.find("/snapshots/000002/coating_mass"), std::string::npos);
  {
    ParticleRecorder rec(dir, kFields, kIdentity, ParticleRecorder::Mode::append);
    rec.write(0.3, state({1}, 0.3));
  }
  ParticleFile g(dir / kParticlesFile);
  ASSERT_EQ(g.snapshots().size(), 3u);
  EXPECT_EQ(g.snapshots()[2].group, "000003");
}

TEST(ParticleRecorder, AReaderInAnotherProcessDoesNotBlockTheWriter) {
  const TempDir dir("reader");
  ParticleRecorder rec(dir, kFields, kIdentity);
  rec.write(0.1, state({1, 2}, 0.1));
  int toChild[2], toParent[2];
  ASSERT_EQ(::pipe(toChild), 0);
  ASSERT_EQ(::pipe(toParent), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // Holds the file open read-only (as ParaView would) until the parent has written.
    int code = 0;
    {
      ParticleFile f(dir / kParticlesFile);
      char c = 'r';
      if (::write(toParent[1], &c, 1) != 1) code = 1;
      if (::read(toChild[0], &c, 1) != 1) code = 1;
    }
    ::_exit(code);
  }
  char c = 0;
  ASSERT_EQ(::read(toParent[0], &c, 1), 1);
  EXPECT_NO_THROW(rec.write(0.2, state({1, 2, 3}, 0.2)));
  ASSERT_EQ(::write(toChild[1], &c, 1), 1);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  ParticleFile f(dir / kParticlesFile);
  EXPECT_EQ(f.snapshots().size(), 2u);
}

TEST(ParticleRecorder, AppendContinuesNumbering) {
  const TempDir dir("append");
  { ParticleRecorder(dir, kFields, kIdentity).write(0.1, state({1}, 0.1)); }
  {
    ParticleRecorder rec(dir, kFields, kIdentity, ParticleRecorder::Mode::append);
    EXPECT_EQ(rec.snapshots(), 1u);
    rec.write(0.2, state({1, 2}, 0.2));
  }
  ParticleFile f(dir / kParticlesFile);
  ASSERT_EQ(f.snapshots().size(), 2u);
  EXPECT_EQ(f.snapshots()[1].count, 2u);
}

TEST(ParticleRecorder, ClearErrors) {
  const TempDir dir("errors");
  ParticleRecorder rec(dir, kFields, kIdentity);
  cosim::link::ParticleData p;
  p.ids = {1};
  p.field(cosim::field::position);
  try {
    rec.write(0.1, p);
    FAIL() << "a missing field must be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'velocity'"), std::string::npos) << e.what();
  }
  rec.write(0.1, state({1}, 0.1));
  try {
    rec.write(0.05, state({1}, 0.05));
    FAIL() << "a time going back must be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("times must increase"), std::string::npos) << e.what();
  }
  try {
    ParticleFile missing(dir / "nothing.h5");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing.h5"), std::string::npos);
  }
}

namespace {
// Rewrites dataset `name` of snapshot group `group` with `values` (a 1-D array), as a damaged
// file or another writer would leave it.
void rewriteDataset(const fs::path& file, const std::string& group, const std::string& name,
                    const std::vector<double>& values) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t g = H5Gopen2(f, ("snapshots/" + group).c_str(), H5P_DEFAULT);
  ASSERT_GE(g, 0);
  ASSERT_GE(H5Ldelete(g, name.c_str(), H5P_DEFAULT), 0);
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t set =
      H5Dcreate2(g, name.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(set, 0);
  ASSERT_GE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  H5Dclose(set);
  H5Sclose(space);
  H5Gclose(g);
  H5Fclose(f);
}
}  // namespace

// A damaged file (a field with fewer rows than the snapshot's ids, a NaN) is refused by the
// reader with the snapshot, its time and the dataset: it would otherwise pass silently into every
// statistic of a report (a NaN CV, a mean over the wrong parcels).
TEST(ParticleRecorder, ADamagedSnapshotIsRefusedNamingItsTimeAndDataset) {
  for (const std::string damage : {"short", "nan"}) {
    SCOPED_TRACE(damage);
    const TempDir dir("damaged_" + damage);
    {
      ParticleRecorder rec(dir, kFields, kIdentity);
      rec.write(0.01, state({1, 2, 3, 4}, 0.01));
      rec.write(0.02, state({1, 2, 3, 4}, 0.02));
    }
    if (damage == "short")
      rewriteDataset(dir / kParticlesFile, "000001", cosim::field::coating_mass, {1e-9, 2e-9});
    else
      rewriteDataset(dir / kParticlesFile, "000001", cosim::field::coating_mass,
                     {1e-9, 2e-9, std::nan(""), 4e-9});
    ParticleFile f(dir / kParticlesFile);
    EXPECT_EQ(f.read(0, cosim::field::coating_mass).size(), 4u);  // the intact one reads
    try {
      f.read(1, cosim::field::coating_mass);
      FAIL() << "a damaged snapshot must be refused";
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("snapshot 000001 (t = 0.02 s), dataset 'coating_mass'"), std::string::npos)
          << msg;
      EXPECT_NE(msg.find(damage == "short" ? "has 2 rows for the 4 parcel ids"
                                           : "value nan (row 2) is not a finite number"),
                std::string::npos)
          << msg;
    }
  }
}
