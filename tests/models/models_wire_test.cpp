// The coupling terms as a participant would compute them over its own parcels: the scene's laws
// carried over the wire (cosim/link/models_wire.h) build the same laws, and the terms of a
// parcel depend on that parcel alone, so parcels split between two evaluators (two particle
// ranks) get, bit for bit, the terms one evaluator gives them all.
#include "cosim/link/models_wire.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "cosim.pb.h"
#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/peer_terms.h"
#include "cosim/models/coupling_terms.h"

namespace cosim::models {
namespace {

// A scene like the coating bed's, with every kind of parameter: numbers, texts, lists and a
// union zone whose parts nest.
SceneModelChoices coatingScene() {
  SceneModelChoices c;
  Parameters drag("drag 'beetstra' (models.drag)");
  drag.setText("undisturbed_velocity", "self_disturbance_transient");
  c.drag = ModelChoice{"beetstra", drag};
  c.forces.push_back({"pressure_gradient", Parameters("force 'pressure_gradient'")});
  c.mass_transfer = ModelChoice{"deen_gunn", Parameters("mass transfer 'deen_gunn'")};
  Parameters cone("part");
  cone.setText("shape", "cone_frustum");
  cone.setList("base", {0.0, 0.0, 0.004});
  cone.setList("axis", {0.0, 0.0, 1.0});
  cone.set("length", 0.01);
  cone.set("base_radius", 0.002);
  cone.set("top_radius", 0.004);
  Parameters sphere("part");
  sphere.setText("shape", "sphere");
  sphere.setList("center", {0.0, 0.0, 0.02});
  sphere.set("radius", 0.003);
  Parameters inner("part");
  inner.setText("shape", "union");
  inner.setChild("parts", {sphere});
  Parameters zone("coating zone 'union' (models.coating_zone)");
  zone.setChild("parts", {cone, inner});
  c.coating_zone = ModelChoice{"union", zone};
  return c;
}

SceneConstants constants() {
  SceneConstants k;
  k.cg = 5.0;
  k.min_voidage = 0.3;
  k.gravity[0] = 0.1;
  k.gravity[2] = -9.81;
  k.schmidt = 0.7;
  return k;
}

void expectSame(const Parameters& a, const Parameters& b) {
  EXPECT_EQ(a.owner(), b.owner());
  EXPECT_EQ(a.numbers(), b.numbers());
  EXPECT_EQ(a.texts(), b.texts());
  EXPECT_EQ(a.lists(), b.lists());
  ASSERT_EQ(a.allChildren().size(), b.allChildren().size());
  for (const auto& [key, children] : a.allChildren()) {
    ASSERT_EQ(b.allChildren().count(key), 1U) << key;
    const auto& other = b.allChildren().at(key);
    ASSERT_EQ(children.size(), other.size()) << key;
    for (std::size_t i = 0; i < children.size(); ++i) expectSame(children[i], other[i]);
  }
}

link::ReceivedModels roundTrip(const SceneModelChoices& c, const SceneConstants& k) {
  wire::SceneModels w;
  link::toWire(c, k, w);
  wire::SceneModels parsed;
  EXPECT_TRUE(parsed.ParseFromString(w.SerializeAsString()));
  return link::fromWire(parsed);
}

// n parcels of a bed around the zone at step `step`: positions across the zone's edge, slips,
// voidages from dense to dilute, every one in a cell (none lost).
void bed(std::size_t n, int step, link::ParticleData& state, link::ParticleData& samples) {
  std::vector<double> x, v, r, u, eps, rho, mu, grad_p, y, cell;
  state = {};
  samples = {};
  for (std::size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) + 0.37 * step;
    state.ids.push_back(static_cast<std::int64_t>(1000 + 7 * i));
    x.insert(x.end(), {0.003 * std::sin(s), 0.003 * std::cos(1.3 * s), 0.001 * s});
    v.insert(v.end(), {0.01 * std::cos(s), -0.02, 0.05 * std::sin(0.7 * s)});
    r.push_back(5.0 * 90e-6 / 2.0);
    u.insert(u.end(), {0.0, 0.01 * std::sin(s), 0.2 + 0.1 * std::cos(s)});
    eps.push_back(0.42 + 0.5 * (0.5 + 0.5 * std::sin(2.1 * s)));
    rho.push_back(1.1);
    mu.push_back(1.8e-5);
    grad_p.insert(grad_p.end(), {0.0, 10.0 * std::cos(s), -6000.0});
    y.push_back(0.01 * (0.5 + 0.5 * std::cos(s)));
    cell.push_back(0.004);
  }
  state.put(field::position, x);
  state.put(field::velocity, v);
  state.put(field::radius, r);
  samples.ids = state.ids;
  samples.put(field::fluid_velocity, u);
  samples.put(field::voidage, eps);
  samples.put(field::fluid_density, rho);
  samples.put(field::fluid_viscosity, mu);
  samples.put(field::pressure_gradient, grad_p);
  samples.put(field::precursor_fraction, y);
  samples.put(field::cell_size, cell);
}

link::ParticleData part(const link::ParticleData& d, std::size_t from, std::size_t to) {
  link::ParticleData p;
  p.ids.assign(d.ids.begin() + static_cast<std::ptrdiff_t>(from),
               d.ids.begin() + static_cast<std::ptrdiff_t>(to));
  for (const auto& name : d.names()) {
    const std::size_t c = d.get(name).size() / d.size();
    const auto& v = d.get(name);
    p.put(name, {v.begin() + static_cast<std::ptrdiff_t>(c * from),
                 v.begin() + static_cast<std::ptrdiff_t>(c * to)});
  }
  return p;
}

TEST(ModelsWire, CarriesEveryParameterOfEveryLaw) {
  const auto c = coatingScene();
  SceneModelChoices with_plugin = c;
  with_plugin.plugins = {"/opt/laws/libmy_drag.so"};
  const auto r = roundTrip(with_plugin, constants());
  ASSERT_TRUE(r.choices.drag && r.choices.mass_transfer && r.choices.coating_zone);
  EXPECT_EQ(r.choices.drag->law, "beetstra");
  expectSame(r.choices.drag->params, c.drag->params);
  ASSERT_EQ(r.choices.forces.size(), 1U);
  EXPECT_EQ(r.choices.forces[0].law, "pressure_gradient");
  expectSame(r.choices.mass_transfer->params, c.mass_transfer->params);
  EXPECT_EQ(r.choices.coating_zone->law, "union");
  expectSame(r.choices.coating_zone->params, c.coating_zone->params);
  EXPECT_EQ(r.choices.plugins, with_plugin.plugins);
  EXPECT_EQ(r.constants.cg, 5.0);
  EXPECT_EQ(r.constants.min_voidage, 0.3);
  EXPECT_EQ(r.constants.gravity[0], 0.1);
  EXPECT_EQ(r.constants.gravity[1], 0.0);
  EXPECT_EQ(r.constants.gravity[2], -9.81);
  EXPECT_EQ(r.constants.schmidt, 0.7);
  // a scene without coating carries no coating law
  SceneModelChoices drag_only;
  drag_only.drag = c.drag;
  const auto d = roundTrip(drag_only, constants());
  EXPECT_TRUE(d.choices.drag);
  EXPECT_FALSE(d.choices.mass_transfer || d.choices.coating_zone);
  EXPECT_TRUE(d.choices.forces.empty());
}

// Two evaluators with the laws from the wire, each over half of the parcels, over three
// intervals (the drag's force history by parcel id carried from one to the next), against one
// evaluator with the scene's own laws over all of them.
TEST(ModelsWire, TermsSplitOverTwoEvaluatorsAreTheTermsOfOne) {
  const auto c = coatingScene();
  const auto k = constants();
  const auto r = roundTrip(c, k);
  const SceneModels all = makeSceneModels(c);
  const SceneModels first = makeSceneModels(r.choices);
  const SceneModels second = makeSceneModels(r.choices);
  ASSERT_TRUE(all.wake && first.wake && second.wake);
  const std::size_t n = 40;
  const std::size_t half = 17;
  std::size_t in_zone = 0;
  for (int step = 0; step < 3; ++step) {
    link::ParticleData state;
    link::ParticleData samples;
    bed(n, step, state, samples);
    const std::vector<char> none(n, 0);
    const auto whole = evaluateTerms(all, true, k, state, samples, none, 1e-4);
    const std::vector<char> none_a(half, 0);
    const std::vector<char> none_b(n - half, 0);
    const auto a = evaluateTerms(first, true, r.constants, part(state, 0, half),
                                 part(samples, 0, half), none_a, 1e-4);
    const auto b = evaluateTerms(second, true, r.constants, part(state, half, n),
                                 part(samples, half, n), none_b, 1e-4);
    for (const auto* terms : {&whole.forcing, &whole.exchange}) {
      const bool forcing = terms == &whole.forcing;
      const auto& ta = forcing ? a.forcing : a.exchange;
      const auto& tb = forcing ? b.forcing : b.exchange;
      ASSERT_EQ(terms->names(), ta.names());
      for (const auto& name : terms->names()) {
        std::vector<double> joined = ta.get(name);
        joined.insert(joined.end(), tb.get(name).begin(), tb.get(name).end());
        EXPECT_EQ(joined, terms->get(name)) << name << " at step " << step;
      }
    }
    std::vector<char> zone = a.in_zone;
    zone.insert(zone.end(), b.in_zone.begin(), b.in_zone.end());
    EXPECT_EQ(zone, whole.in_zone);
    for (char z : whole.in_zone) in_zone += z != 0 ? 1 : 0;
  }
  // the bed straddles the zone: the split is tested on parcels inside and outside it
  EXPECT_GT(in_zone, 0U);
  EXPECT_LT(in_zone, 3 * n);
}

// The particle participant's laws on the peer data path (cosim/link/peer_terms.h): a checkpoint
// of their force history, read back into laws built anew, continues every parcel's wake as the
// laws that never stopped do, bit for bit; a damaged history is refused with the file named.
TEST(ModelsWire, PeerTermsResumeTheWakeHistoryBitForBit) {
  wire::PeerLink link;
  link::toWire(coatingScene(), constants(), *link.mutable_models());
  link.set_coating(true);
  link::ScenePeerTerms running;
  running.configure(link);
  const std::size_t n = 40;
  const std::vector<char> none(n, 0);
  std::string saved;
  link::PeerTerms::Terms last;
  for (int step = 0; step < 3; ++step) {
    link::ParticleData state;
    link::ParticleData samples;
    bed(n, step, state, samples);
    last = running.evaluate(state, samples, none, 1e-4);
    if (step == 1) saved = running.saveState();
  }
  ASSERT_FALSE(saved.empty());
  link::ScenePeerTerms resumed;
  resumed.configure(link);
  resumed.restoreState(saved);
  EXPECT_EQ(resumed.saveState(), saved);
  link::ParticleData state;
  link::ParticleData samples;
  bed(n, 2, state, samples);
  const auto again = resumed.evaluate(state, samples, none, 1e-4);
  ASSERT_EQ(again.forcing.names(), last.forcing.names());
  for (const auto& name : last.forcing.names())
    EXPECT_EQ(again.forcing.get(name), last.forcing.get(name)) << name;
  EXPECT_EQ(resumed.saveState(), running.saveState());
  // and the history matters: laws without it give other forces
  link::ScenePeerTerms fresh;
  fresh.configure(link);
  const auto other = fresh.evaluate(state, samples, none, 1e-4);
  bool differs = false;
  for (const auto& name : last.forcing.names())
    differs = differs || other.forcing.get(name) != last.forcing.get(name);
  EXPECT_TRUE(differs) << "the wake history changed no force: the test would prove nothing";

  const std::vector<std::string> damaged_ones = {saved.substr(0, saved.size() - 3), "nonsense",
                                                 saved + "x"};
  for (const auto& damaged : damaged_ones) {
    link::ScenePeerTerms laws;
    laws.configure(link);
    try {
      laws.restoreState(damaged);
      FAIL() << "a damaged history accepted";
    } catch (const link::ProtocolError& e) {
      EXPECT_NE(std::string(e.what()).find(link::kPeerTermsFile), std::string::npos) << e.what();
    }
  }
}

TEST(ModelsWire, RefusesWhatNoSceneGives) {
  const auto c = coatingScene();
  {
    wire::SceneModels w;
    link::toWire(c, constants(), w);
    w.mutable_constants()->mutable_gravity()->RemoveLast();
    try {
      (void)link::fromWire(w);
      FAIL() << "two gravity components accepted";
    } catch (const link::ProtocolError& e) {
      EXPECT_NE(std::string(e.what()).find("constants.gravity has 2 values, expected 3"),
                std::string::npos)
          << e.what();
    }
  }
  {
    wire::SceneModels w;
    link::toWire(c, constants(), w);
    w.mutable_mass_transfer()->clear_law();
    EXPECT_THROW((void)link::fromWire(w), link::ProtocolError);
  }
  {
    wire::SceneModels w;
    auto k = constants();
    k.min_voidage = 0.0;
    link::toWire(c, k, w);
    try {
      (void)link::fromWire(w);
      FAIL() << "min_voidage 0 accepted";
    } catch (const link::ProtocolError& e) {
      EXPECT_NE(std::string(e.what()).find("SceneModels.constants: constant 'min_voidage'"),
                std::string::npos)
          << e.what();
    }
  }
  {
    // parameters nested deeper than any scene nests them (the union's third part, 12 deep)
    wire::SceneModels w;
    link::toWire(c, constants(), w);
    auto* p = w.mutable_coating_zone()->mutable_params();
    for (int i = 0; i < 12; ++i) p = (*p->mutable_children())["parts"].add_items();
    try {
      (void)link::fromWire(w);
      FAIL() << "12 levels accepted";
    } catch (const link::ProtocolError& e) {
      EXPECT_NE(std::string(e.what()).find("coating_zone.params.parts[2].parts[0]"),
                std::string::npos)
          << e.what();
    }
  }
}

// The laws over 50,000 parcels split into parts on several threads (the orchestrator's models
// phase) give every number of the laws over them on one, bit for bit, with lost parcels in
// every part; an input error in a later part names its parcel among all.
TEST(CouplingTerms, PartsOnThreadsAreTheTermsOfOneEvaluation) {
  SceneModelChoices c = coatingScene();
  c.drag->params = Parameters("drag 'beetstra' (models.drag)");  // no wake: splittable
  const SceneModels m = makeSceneModels(c);
  ASSERT_TRUE(m.splittable);
  const auto k = constants();
  const std::size_t n = 50000;
  link::ParticleData state;
  link::ParticleData samples;
  bed(n, 1, state, samples);
  std::vector<char> lost(n, 0);
  for (std::size_t i = 5; i < n; i += 4999) lost[i] = 1;
  const auto one = evaluateTerms(m, true, k, state, samples, lost, 1e-4, 1);
  std::size_t inside = 0;
  for (char z : one.in_zone) inside += z != 0 ? 1 : 0;
  ASSERT_GT(inside, 0U);  // the bed straddles the zone
  ASSERT_LT(inside, n);
  for (unsigned threads : {2U, 3U, 8U}) {
    const auto split = evaluateTerms(m, true, k, state, samples, lost, 1e-4, threads);
    for (const auto* terms : {&one.forcing, &one.exchange}) {
      const auto& other = terms == &one.forcing ? split.forcing : split.exchange;
      ASSERT_EQ(terms->names(), other.names());
      EXPECT_EQ(terms->ids, other.ids);
      for (const auto& name : terms->names()) {
        const auto& a = terms->get(name);
        const auto& b = other.get(name);
        ASSERT_EQ(a.size(), b.size()) << name;
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0)
            << name << " on " << threads << " threads";
      }
    }
    EXPECT_EQ(split.in_zone, one.in_zone) << threads << " threads";
  }
  // a voidage out of range in the last part is named by its place among all the parcels
  auto bad = samples;
  bad.field(field::voidage)[n - 3] = 1.7;
  try {
    evaluateTerms(m, true, k, state, bad, lost, 1e-4, 4);
    ADD_FAILURE() << "a voidage of 1.7 passed";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("of parcel " + std::to_string(n - 3) + " "),
              std::string::npos)
        << e.what();
  }
}

// A law that carries work from one parcel to the next (the filtered Beetstra with the gas at
// each parcel) and a scene with plugins are evaluated in one part.
TEST(CouplingTerms, LawsCarryingWorkAcrossParcelsAndPluginsAreNotSplit) {
  SceneModelChoices c;
  Parameters filtered("drag 'beetstra' (models.drag)");
  filtered.setText("filtered", "true");
  filtered.set("particle_density", 1500.0);
  c.drag = ModelChoice{"beetstra", filtered};
  EXPECT_FALSE(makeSceneModels(c).splittable);
  Parameters reference = filtered;
  reference.set("reference_fluid_density", 1.2);
  reference.set("reference_fluid_viscosity", 1.8e-5);
  c.drag = ModelChoice{"beetstra", reference};
  EXPECT_TRUE(makeSceneModels(c).splittable);  // one terminal velocity for the whole batch
  c.drag = ModelChoice{"beetstra", Parameters("drag 'beetstra' (models.drag)")};
  EXPECT_TRUE(makeSceneModels(c).splittable);
  c.plugins = {"/nonexistent/libmy_drag.so"};  // not loaded: no law of the scene names it
  EXPECT_FALSE(makeSceneModels(c).splittable);
}

}  // namespace
}  // namespace cosim::models
