// cosim-liggghts as a process speaking the protocol, with 1 and 2 MPI ranks: a settling bed,
// coating increments by id, checkpoints, and errors that must reach the orchestrator.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "adapter_harness.h"
#include "cosim/link/fields.h"
#include "cosim/link/particle_wire.h"
#include "test_dir.h"

using cosim::liggghts::test::AdapterRun;
using cosim::liggghts::test::dataDir;
using cosim::liggghts::test::ScratchDir;
using cosim::link::ParticleData;
namespace field = cosim::field;

namespace {

const std::vector<std::string> kState = {field::position, field::velocity, field::radius,
                                         field::coating_mass, field::type};
const std::vector<std::string> kForcing = {field::drag_coefficient, field::fluid_velocity,
                                           field::coating_increment};

std::filesystem::path participantDir(const std::filesystem::path& base, const std::string& name,
                                     const std::string& script) {
  const auto dir = base / name;
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(dataDir() / script, dir / script);
  return dir;
}

ParticleData stateOf(const cosim::wire::Envelope& reply) {
  if (reply.has_error()) throw std::runtime_error("adapter error: " + reply.error().message());
  if (!reply.has_advanced()) throw std::runtime_error("expected Advanced");
  return cosim::link::fromWire(reply.advanced().state());
}

struct Bed {
  ParticleData state;
  std::set<std::int64_t> inserted, deleted;
  double max_overlap = 0;  // largest overlap between two particles or a particle and a wall [m]
  double max_speed = 0;
  double bed_height = 0;  // twice the mean particle height [m]
};

// 1000 grains of 3 mm poured into a 40 mm cylinder (tests/liggghts/data/in.settling_bed),
// settled for 0.4 s: 267 coupling intervals of 50 DEM steps of 3e-5 s.
Bed settle(const std::filesystem::path& base, int ranks) {
  const auto dir = participantDir(base, "particles-np" + std::to_string(ranks), "in.settling_bed");
  AdapterRun run(dir, ranks);
  run.handshake("script: in.settling_bed\n", 1.5e-3, 50, kState, kForcing);
  Bed bed;
  ParticleData s = stateOf(run.advance(0, 0, ParticleData{}));
  for (int k = 0; k < 267; ++k) {
    auto reply = run.advance(1.5e-3, 50, ParticleData{});
    s = stateOf(reply);
    for (auto id : reply.advanced().inserted_ids())
      if (!bed.inserted.insert(id).second) throw std::runtime_error("id inserted twice");
    for (auto id : reply.advanced().deleted_ids()) bed.deleted.insert(id);
  }
  EXPECT_TRUE(run.shutdown().has_goodbye());
  EXPECT_EQ(run.waitExit(), 0);
  bed.state = s;
  const auto& x = s.get(field::position);
  const auto& v = s.get(field::velocity);
  const auto& r = s.get(field::radius);
  const std::size_t n = s.size();
  double zsum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    zsum += x[3 * i + 2];
    bed.max_speed = std::max(bed.max_speed, std::hypot(v[3 * i], v[3 * i + 1], v[3 * i + 2]));
    bed.max_overlap = std::max(bed.max_overlap, r[i] - x[3 * i + 2]);  // floor z = 0
    bed.max_overlap = std::max(bed.max_overlap, std::hypot(x[3 * i], x[3 * i + 1]) + r[i] - 0.02);
    for (std::size_t j = i + 1; j < n; ++j) {
      const double d =
          std::hypot(x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]);
      bed.max_overlap = std::max(bed.max_overlap, r[i] + r[j] - d);
    }
  }
  bed.bed_height = n ? 2 * zsum / static_cast<double>(n) : 0;
  return bed;
}

std::string rankName(const ::testing::TestParamInfo<int>& p) {
  return std::to_string(p.param) + "rank";
}

}  // namespace

// Issue 4: 1000 particles inserted in a cylinder settle into a bed: none lost, none overlapping
// more than 1 % of a diameter at rest, same count and same bed height (within 1 %) with 1 and 2
// MPI ranks.
TEST(LiggghtsAdapter, SettlingBedSameWithOneAndTwoRanks) {
  ScratchDir dir;
  std::map<int, Bed> beds;
  for (int ranks : {1, 2}) {
    const auto t0 = std::chrono::steady_clock::now();
    beds[ranks] = settle(dir.path(), ranks);
    std::printf("%d rank(s): %.1f s wall\n", ranks,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    const Bed& b = beds[ranks];
    EXPECT_EQ(b.state.size(), 1000u) << ranks << " rank(s)";
    EXPECT_EQ(b.inserted.size(), 1000u)
        << ranks << " rank(s): every particle reported inserted once";
    EXPECT_TRUE(b.deleted.empty()) << ranks << " rank(s)";
    EXPECT_LT(b.max_overlap, 0.01 * 0.003) << ranks << " rank(s)";
    EXPECT_LT(b.max_speed, 0.01) << ranks << " rank(s): bed not at rest";
    std::printf(
        "%d rank(s): %zu particles, bed height %.5f m, max overlap %.3g m, max speed %.3g m/s\n",
        ranks, b.state.size(), b.bed_height, b.max_overlap, b.max_speed);
  }
  EXPECT_NEAR(beds[2].bed_height, beds[1].bed_height, 0.01 * beds[1].bed_height);
}

// Issue 4: coating increments sent by the orchestrator arrive on the right particles by id,
// while the particles fall through the rank boundary (2 ranks), and accumulate.
class CoatingById : public ::testing::TestWithParam<int> {};

TEST_P(CoatingById, IncrementsLandOnTheirParticles) {
  ScratchDir dir;
  const int ranks = GetParam();
  const auto pdir = participantDir(dir.path(), "particles", "in.settling_bed");
  AdapterRun run(pdir, ranks);
  run.handshake("script: in.settling_bed\n", 1.5e-3, 50, kState, kForcing);
  ParticleData s = stateOf(run.advance(0, 0, ParticleData{}));
  s = stateOf(run.advance(1.5e-3, 50, ParticleData{}));  // insertion
  ASSERT_EQ(s.size(), 1000u);
  std::map<std::int64_t, double> expected;
  // the script splits the box at mid-height (z = 0.0345 m) between 2 ranks: count crossings
  std::map<std::int64_t, bool> started_above;
  for (std::size_t i = 0; i < s.size(); ++i)
    started_above[s.ids[i]] = s.get(field::position)[3 * i + 2] > 0.0345;
  for (int k = 0; k < 100; ++k) {
    ParticleData terms;
    // every other particle, an amount that depends on id and step
    for (auto id : s.ids)
      if ((id + k) % 2 == 0) terms.ids.push_back(id);
    auto& inc = terms.field(field::coating_increment);  // zero-filled, one per id
    for (std::size_t j = 0; j < terms.size(); ++j) {
      inc[j] = 1e-9 * static_cast<double>(terms.ids[j]) + 1e-12 * k;
      expected[terms.ids[j]] += inc[j];
    }
    s = stateOf(run.advance(1.5e-3, 50, terms));
    if (k % 10 == 9) {
      // a checkpoint moves the parcels that left their rank's sub-domain since the last
      // neighbour list (write_restart's exchange): the next terms must still find them
      auto cp = run.checkpoint((dir.path() / ("cp" + std::to_string(k))).string());
      ASSERT_TRUE(cp.has_checkpoint_written()) << (cp.has_error() ? cp.error().message() : "");
    }
  }
  const auto& c = s.get(field::coating_mass);
  ASSERT_EQ(s.size(), 1000u);
  int crossed = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    crossed += started_above[s.ids[i]] && s.get(field::position)[3 * i + 2] < 0.0345;
  EXPECT_GT(crossed, 100) << "too few particles changed sub-domain to test migration";
  for (std::size_t i = 0; i < s.size(); ++i)
    ASSERT_NEAR(c[i], expected[s.ids[i]], 1e-15 * expected[s.ids[i]]) << "id " << s.ids[i];
  // Advance(dt = 0) only credits and reports.
  ParticleData terms;
  terms.ids = {s.ids.front()};
  terms.field(field::coating_increment) = {1e-6};
  const ParticleData s2 = stateOf(run.advance(0, 0, terms));
  EXPECT_NEAR(s2.get(field::coating_mass)[0], expected[s.ids.front()] + 1e-6, 1e-15);
  EXPECT_EQ(s2.get(field::position), s.get(field::position));

  // Checkpoint: a restart file written where asked.
  auto cp = run.checkpoint((dir.path() / "checkpoint").string());
  ASSERT_TRUE(cp.has_checkpoint_written()) << (cp.has_error() ? cp.error().message() : "");
  ASSERT_EQ(cp.checkpoint_written().files_size(), 1);
  EXPECT_TRUE(std::filesystem::exists(cp.checkpoint_written().files(0)));
  EXPECT_TRUE(run.shutdown().has_goodbye());
  EXPECT_EQ(run.waitExit(), 0);
}

INSTANTIATE_TEST_SUITE_P(Ranks, CoatingById, ::testing::Values(1, 2), rankName);

// Issue 4: a malformed input script fails with LIGGGHTS' own message surfaced to the user
// (as wire::Error), and the process ends (non-zero) instead of hanging.
class MalformedScript : public ::testing::TestWithParam<int> {};

TEST_P(MalformedScript, LiggghtsMessageReachesOrchestrator) {
  ScratchDir dir;
  const auto pdir = participantDir(dir.path(), "particles", "in.malformed");
  AdapterRun run(pdir, GetParam());
  run.handshake("script: in.malformed\n", 1e-3, 50, kState, kForcing);
  const auto reply = run.receive(60);
  ASSERT_TRUE(reply.has_error());
  const std::string msg = reply.error().message();
  EXPECT_NE(msg.find("Invalid fix style"), std::string::npos) << msg;
  EXPECT_NE(msg.find("in.malformed, line 7"), std::string::npos) << msg;
  EXPECT_NE(msg.find("gravity_typo"), std::string::npos) << msg;
  const int rc = run.waitExit(30);
  EXPECT_NE(rc, 0);
  EXPECT_NE(rc, -1) << "adapter still running 30 s after the error";
}

INSTANTIATE_TEST_SUITE_P(Ranks, MalformedScript, ::testing::Values(1, 2), rankName);

// A DEM step above 0.3 Rayleigh times is refused with the dt that would work.
TEST(LiggghtsAdapter, UnstableTimestepIsRefusedWithAWorkingValue) {
  ScratchDir dir;
  const auto pdir = dir.path() / "particles";
  std::filesystem::create_directories(pdir);
  {
    std::ifstream in(dataDir() / "in.single_particle");
    std::ofstream out(pdir / "in.single_particle");
    std::string line;
    while (std::getline(in, line))
      out << (line == "timestep 1e-6" ? "timestep 5e-5" : line) << "\n";
  }
  AdapterRun run(pdir, 1);
  // 50 steps of 5e-5 s = 2.5e-3 s coupling interval. t_R = 7.68e-5 s: dt = 0.65 t_R.
  run.handshake("script: in.single_particle\n", 2.5e-3, 50, kState, kForcing);
  const auto reply = run.receive(60);
  ASSERT_TRUE(reply.has_error());
  const std::string msg = reply.error().message();
  EXPECT_NE(msg.find("0.651 x Rayleigh time"), std::string::npos) << msg;
  EXPECT_NE(msg.find("timestep 1.54e-05"), std::string::npos) << msg;  // 0.2 t_R
  EXPECT_NE(run.waitExit(30), 0);
}

// A negative friction coefficient, which LIGGGHTS accepts and the bed later blows up with, is
// refused before the script runs, with its line.
TEST(LiggghtsAdapter, NegativeFrictionIsRefusedWithItsLine) {
  ScratchDir dir;
  const auto pdir = dir.path() / "particles";
  std::filesystem::create_directories(pdir);
  int number = 0, friction_line = 0;
  {
    std::ifstream in(dataDir() / "in.single_particle");
    std::ofstream out(pdir / "in.single_particle");
    std::string line;
    while (std::getline(in, line)) {
      ++number;
      if (line == "fix m4 all property/global coefficientFriction peratomtypepair 1 0.52") {
        line = "fix m4 all property/global coefficientFriction peratomtypepair 1 -0.3";
        friction_line = number;
      }
      out << line << "\n";
    }
  }
  ASSERT_GT(friction_line, 0) << "tests/liggghts/data/in.single_particle changed";
  AdapterRun run(pdir, 1);
  run.handshake("script: in.single_particle\n", 1e-4, 100, kState, kForcing);
  const auto reply = run.receive(60);
  ASSERT_TRUE(reply.has_error());
  const std::string msg = reply.error().message();
  EXPECT_NE(msg.find("line " + std::to_string(friction_line)), std::string::npos) << msg;
  EXPECT_NE(msg.find("coefficientFriction` has the value -0.3"), std::string::npos) << msg;
  EXPECT_NE(run.waitExit(30), 0);
}

// The script's timestep must equal coupling dt / dem_steps.
TEST(LiggghtsAdapter, TimestepMismatchNamesBothValues) {
  ScratchDir dir;
  const auto pdir = participantDir(dir.path(), "particles", "in.single_particle");
  AdapterRun run(pdir, 1);
  run.handshake("script: in.single_particle\n", 1e-4, 50, kState, kForcing);  // 2e-6 per step
  const auto reply = run.receive(60);
  ASSERT_TRUE(reply.has_error());
  const std::string msg = reply.error().message();
  EXPECT_NE(msg.find("timestep 1e-06"), std::string::npos) << msg;
  EXPECT_NE(msg.find("timestep 2e-06"), std::string::npos) << msg;
  EXPECT_NE(msg.find("coupling.dem_steps: 100"), std::string::npos) << msg;
  EXPECT_NE(run.waitExit(30), 0);
}

// Options: an unknown key is refused by name.
TEST(LiggghtsAdapter, UnknownOptionIsRefused) {
  ScratchDir dir;
  const auto pdir = participantDir(dir.path(), "particles", "in.single_particle");
  AdapterRun run(pdir, 1);
  run.handshake("script: in.single_particle\nimpact_sped: 3\n", 5e-5, 50, kState, kForcing);
  const auto reply = run.receive(60);
  ASSERT_TRUE(reply.has_error());
  EXPECT_NE(reply.error().message().find("options.impact_sped: unknown option"), std::string::npos)
      << reply.error().message();
  EXPECT_NE(run.waitExit(30), 0);
}

// Issue 4: particles inserted (repeated insertion) and deleted (falling out of an open bottom)
// are reported by id exactly once each; the ledger inserted - deleted always equals the state,
// and the coating credited to particles that left is reported as deleted_coating_mass.
class InsertDelete : public ::testing::TestWithParam<int> {};

TEST_P(InsertDelete, LedgerMatchesState) {
  ScratchDir dir;
  const auto pdir = participantDir(dir.path(), "particles", "in.outlet");
  AdapterRun run(pdir, GetParam());
  run.handshake("script: in.outlet\n", 1.5e-3, 50, kState, kForcing);
  ParticleData s = stateOf(run.advance(0, 0, ParticleData{}));
  std::set<std::int64_t> alive(s.ids.begin(), s.ids.end()), ever = alive;
  std::map<std::int64_t, double> credited;
  double credited_to_deleted = 0, reported_deleted = 0;
  std::size_t deletions = 0;
  for (int k = 0; k < 120; ++k) {  // 0.18 s: 3 insertions, every batch falls out
    ParticleData terms;
    terms.ids.assign(alive.begin(), alive.end());
    auto& inc = terms.field(field::coating_increment);
    for (std::size_t j = 0; j < terms.size(); ++j) {
      inc[j] = 1e-9;
      credited[terms.ids[j]] += 1e-9;
    }
    const auto reply = run.advance(1.5e-3, 50, terms);
    s = stateOf(reply);
    for (auto id : reply.advanced().inserted_ids()) {
      ASSERT_TRUE(ever.insert(id).second) << "id " << id << " inserted twice";
      alive.insert(id);
    }
    for (auto id : reply.advanced().deleted_ids()) {
      ASSERT_EQ(alive.erase(id), 1u) << "deleted id " << id << " was not alive";
      credited_to_deleted += credited[id];
      ++deletions;
    }
    reported_deleted += reply.advanced().particles().deleted_coating_mass();
    ASSERT_EQ(std::set<std::int64_t>(s.ids.begin(), s.ids.end()), alive) << "step " << k;
  }
  EXPECT_GE(ever.size(), 80u) << "expected at least two insertions of 40";
  EXPECT_GE(deletions, 40u) << "expected at least one batch to leave";
  EXPECT_NEAR(reported_deleted, credited_to_deleted, 1e-12 * credited_to_deleted);
  EXPECT_TRUE(run.shutdown().has_goodbye());
  EXPECT_EQ(run.waitExit(), 0);
}

INSTANTIATE_TEST_SUITE_P(Ranks, InsertDelete, ::testing::Values(1, 2), rankName);

// A LIGGGHTS error in the middle of a run reaches the orchestrator as an Error with LIGGGHTS'
// message, and the process ends. The error is a division by zero in a variable printed at
// DEM step 600 (interval 12): LIGGGHTS raises it with error->one (MPI_Abort) on every rank.
class ErrorDuringRun : public ::testing::TestWithParam<int> {};

TEST_P(ErrorDuringRun, LiggghtsMessageReachesOrchestrator) {
  ScratchDir dir;
  const auto pdir = dir.path() / "particles";
  std::filesystem::create_directories(pdir);
  std::filesystem::copy_file(dataDir() / "in.outlet", pdir / "in.outlet");
  std::ofstream(pdir / "in.outlet", std::ios::app)
      << "variable a equal 1.0/(step-600)\nfix pr all print 100 \"a = $a\"\n";
  AdapterRun run(pdir, GetParam());
  run.handshake("script: in.outlet\n", 1.5e-3, 50, kState, kForcing);
  ASSERT_TRUE(run.advance(0, 0, ParticleData{}).has_advanced());
  std::string msg;
  int steps = 0;
  for (; steps < 30 && msg.empty(); ++steps) {
    const auto reply = run.advance(1.5e-3, 50, ParticleData{});
    if (reply.has_error()) msg = reply.error().message();
  }
  EXPECT_EQ(steps, 12);
  EXPECT_NE(msg.find("Divide by 0"), std::string::npos) << msg;
  EXPECT_NE(msg.find("running 50 DEM steps"), std::string::npos) << msg;
  const int rc = run.waitExit(30);
  EXPECT_NE(rc, 0);
  EXPECT_NE(rc, -1) << "adapter still running 30 s after the error";
}

INSTANTIATE_TEST_SUITE_P(Ranks, ErrorDuringRun, ::testing::Values(1, 2), rankName);

// Forcing that names a parcel LIGGGHTS does not have, or carries a NaN, is refused by name and
// the process ends, on any number of ranks: with several, each rank gets only its own parcels'
// terms, so rank 0 checks all of them before any rank applies its part.
class BadForcing : public ::testing::TestWithParam<int> {};

TEST_P(BadForcing, RefusedByNameAndTheRanksEnd) {
  struct Case {
    const char* what;
    std::function<void(ParticleData&)> spoil;
    const char* expected;
  };
  const std::vector<Case> cases{
      {"an unknown id", [](ParticleData& t) { t.ids.back() = 999999; }, "does not have: 999999"},
      {"a NaN", [](ParticleData& t) { t.field(field::drag_coefficient)[7] = std::nan(""); },
       "contains a NaN"},
  };
  for (const auto& c : cases) {
    ScratchDir dir;
    const auto pdir = participantDir(dir.path(), "particles", "in.settling_bed");
    AdapterRun run(pdir, GetParam());
    run.handshake("script: in.settling_bed\n", 1.5e-3, 50, kState, kForcing);
    ParticleData s = stateOf(run.advance(0, 0, ParticleData{}));
    s = stateOf(run.advance(1.5e-3, 50, ParticleData{}));  // insertion
    ASSERT_EQ(s.size(), 1000u) << c.what;
    ParticleData terms;
    terms.ids = s.ids;
    terms.field(field::drag_coefficient).assign(s.size(), 1e-6);
    terms.field(field::fluid_velocity).assign(3 * s.size(), 0.0);
    ASSERT_TRUE(run.advance(1.5e-3, 50, terms).has_advanced()) << c.what;  // a good one first
    c.spoil(terms);
    const auto reply = run.advance(1.5e-3, 50, terms);
    ASSERT_TRUE(reply.has_error()) << c.what;
    EXPECT_NE(reply.error().message().find(c.expected), std::string::npos)
        << c.what << ": " << reply.error().message();
    const int rc = run.waitExit(30);
    EXPECT_NE(rc, -1) << c.what << ": adapter still running 30 s after the error";
  }
}

INSTANTIATE_TEST_SUITE_P(Ranks, BadForcing, ::testing::Values(1, 2), rankName);

// Particles inserted after start-up are checked when they appear: a 3 mm bead (t_R = 1.836e-4 s)
// with a DEM step of 1e-4 s is refused at the first interval that inserts it.
TEST(LiggghtsAdapter, TimestepCheckedWhenParticlesAppear) {
  ScratchDir dir;
  const auto pdir = dir.path() / "particles";
  std::filesystem::create_directories(pdir);
  {
    std::ifstream in(dataDir() / "in.settling_bed");
    std::ofstream out(pdir / "in.settling_bed");
    std::string line;
    while (std::getline(in, line))
      out << (line == "timestep 3e-5" ? "timestep 1e-4" : line) << "\n";
  }
  AdapterRun run(pdir, 1);
  run.handshake("script: in.settling_bed\n", 5e-3, 50, kState, kForcing);
  const auto first = run.advance(0, 0, ParticleData{});
  ASSERT_TRUE(first.has_advanced()) << "no particles yet: nothing to refuse";
  EXPECT_EQ(first.advanced().state().ids_size(), 0);
  const auto reply = run.advance(5e-3, 50, ParticleData{});
  ASSERT_TRUE(reply.has_error());
  const std::string msg = reply.error().message();
  // t_R = pi * 1.5e-3 * sqrt(2500 / 1.9231e6) / 0.92553 = 1.6991e-4 / 0.92553 = 1.8358e-4 s:
  // dt/t_R = 0.5447, 0.2 t_R = 3.672e-5 s
  EXPECT_NE(msg.find("0.545 x Rayleigh time"), std::string::npos) << msg;
  EXPECT_NE(msg.find("timestep 3.67e-05"), std::string::npos) << msg;
  EXPECT_NE(run.waitExit(30), 0);
}

namespace {
// A LIGGGHTS `dump custom` file: its TIMESTEP and its rows (columns as in its ATOMS header).
struct DumpFile {
  long long step = -1;
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

DumpFile readDump(const std::filesystem::path& file) {
  std::ifstream in(file);
  DumpFile d;
  std::string line;
  while (std::getline(in, line)) {
    if (line == "ITEM: TIMESTEP") {
      std::getline(in, line);
      d.step = std::stoll(line);
    } else if (line.rfind("ITEM: ATOMS", 0) == 0) {
      std::istringstream h(line.substr(11));
      for (std::string c; h >> c;) d.columns.push_back(c);
      while (std::getline(in, line)) {
        std::istringstream r(line);
        std::vector<double> row;
        for (double x; r >> x;) row.push_back(x);
        if (!row.empty()) d.rows.push_back(row);
      }
    }
  }
  return d;
}

std::set<std::string> dumpsIn(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".dump") names.insert(e.path().filename().string());
  return names;
}

// Largest difference between a dump's positions and a state's, matched by id.
double largestPositionDifference(const DumpFile& d, const ParticleData& s) {
  const auto& x = s.get(field::position);
  double worst = 0;
  EXPECT_EQ(d.rows.size(), s.size());
  for (const auto& row : d.rows) {
    const auto it = std::find(s.ids.begin(), s.ids.end(), static_cast<std::int64_t>(row[0]));
    if (it == s.ids.end()) {
      ADD_FAILURE() << "id " << row[0] << " not in the state";
      continue;
    }
    const std::size_t i = static_cast<std::size_t>(it - s.ids.begin());
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(row[1 + c] - x[3 * i + c]));
  }
  return worst;
}
}  // namespace

// LIGGGHTS dumps on the coupled run's clock (docs/liggghts.md): the script settles the grains for
// 200 DEM steps, then restarts the step counter and defines a dump every 100 steps. Coupled for
// 5 intervals of 30 steps (t = 0 .. 1.5e-3 s), the dumps are g_0 (t = 0), g_100 and g_150 (the
// final time, not a multiple of 100: written when the run finishes), each stamped with its step,
// the last one holding the final state. Resumed from a checkpoint at step 60, the same files
// with the same steps follow, and the resume's final dump holds the same state.
TEST(LiggghtsAdapter, DumpsAreOnTheRunClockWithOneAtTheFinalTime) {
  ScratchDir dir;
  const auto fresh = participantDir(dir.path(), "fresh", "in.dump_clock");
  const auto checkpoint = dir.path() / "checkpoint";
  ParticleData final_state;
  {
    AdapterRun run(fresh, 1);
    run.handshake("script: in.dump_clock\n", 3e-4, 30, kState, kForcing);
    stateOf(run.advance(0, 0, ParticleData{}));
    for (int k = 0; k < 5; ++k) {
      final_state = stateOf(run.advance(3e-4, 30, ParticleData{}));
      if (k == 1) {
        ASSERT_TRUE(run.checkpoint(checkpoint.string()).has_checkpoint_written());
      }
    }
    EXPECT_TRUE(run.shutdown().has_goodbye());
    EXPECT_EQ(run.waitExit(), 0);
  }
  EXPECT_EQ(dumpsIn(fresh), (std::set<std::string>{"g_0.dump", "g_100.dump", "g_150.dump"}));
  for (const auto& [name, step] : std::map<std::string, long long>{
           {"g_0.dump", 0}, {"g_100.dump", 100}, {"g_150.dump", 150}}) {
    const DumpFile d = readDump(fresh / name);
    EXPECT_EQ(d.step, step) << name;
    EXPECT_EQ(d.rows.size(), 20u) << name;
  }
  // The final dump is the final state (to the dump's 6 significant digits: < 1e-7 m here).
  const DumpFile last = readDump(fresh / "g_150.dump");
  EXPECT_LT(largestPositionDifference(last, final_state), 1e-7);

  const auto resumed = participantDir(dir.path(), "resumed", "in.dump_clock");
  {
    AdapterRun run(resumed, 1);
    run.handshake("script: in.dump_clock\n", 3e-4, 30, kState, kForcing, checkpoint.string());
    stateOf(run.advance(0, 0, ParticleData{}));
    for (int k = 2; k < 5; ++k) final_state = stateOf(run.advance(3e-4, 30, ParticleData{}));
    EXPECT_TRUE(run.shutdown().has_goodbye());
    EXPECT_EQ(run.waitExit(), 0);
  }
  EXPECT_EQ(dumpsIn(resumed), (std::set<std::string>{"g_100.dump", "g_150.dump"}));
  EXPECT_EQ(readDump(resumed / "g_100.dump").step, 100);
  const DumpFile again = readDump(resumed / "g_150.dump");
  EXPECT_EQ(again.step, 150);
  EXPECT_LT(largestPositionDifference(again, final_state), 1e-7);
  EXPECT_LT(largestPositionDifference(again,
                                      [&] {
                                        ParticleData p;
                                        for (const auto& row : last.rows)
                                          p.ids.push_back(static_cast<std::int64_t>(row[0]));
                                        auto& x = p.field(field::position);
                                        for (std::size_t i = 0; i < last.rows.size(); ++i)
                                          std::copy(last.rows[i].begin() + 1,
                                                    last.rows[i].begin() + 4, x.begin() + 3 * i);
                                        return p;
                                      }()),
            1e-7)
      << "the resumed run ends where the uninterrupted one does";
}
