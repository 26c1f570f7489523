#include "cosim/link/models_wire.h"

#include <string>

#include "cosim.pb.h"
#include "cosim/link/errors.h"
#include "cosim/models/input_checks.h"

namespace cosim::link {

namespace {

void toWire(const models::Parameters& p, wire::ModelParameters& out) {
  out.set_owner(p.owner());
  for (const auto& [k, v] : p.numbers()) (*out.mutable_numbers())[k] = v;
  for (const auto& [k, v] : p.texts()) (*out.mutable_texts())[k] = v;
  for (const auto& [k, v] : p.lists()) {
    auto& list = (*out.mutable_lists())[k];
    list.mutable_values()->Add(v.begin(), v.end());
  }
  for (const auto& [k, v] : p.allChildren()) {
    auto& list = (*out.mutable_children())[k];
    for (const auto& child : v) toWire(child, *list.add_items());
  }
}

// `depth` bounds the nesting a peer can send (a union of unions of ... ).
models::Parameters fromWire(const wire::ModelParameters& in, const std::string& field, int depth) {
  if (depth > 8) {
    throw ProtocolError("SceneModels: " + field +
                        " nests parameters more than 8 deep; a scene's laws nest at most twice");
  }
  models::Parameters p(in.owner());
  for (const auto& [k, v] : in.numbers()) p.set(k, v);
  for (const auto& [k, v] : in.texts()) p.setText(k, v);
  for (const auto& [k, v] : in.lists()) p.setList(k, {v.values().begin(), v.values().end()});
  for (const auto& [k, v] : in.children()) {
    std::vector<models::Parameters> children;
    children.reserve(static_cast<std::size_t>(v.items_size()));
    for (int i = 0; i < v.items_size(); ++i) {
      children.push_back(
          fromWire(v.items(i), field + "." + k + "[" + std::to_string(i) + "]", depth + 1));
    }
    p.setChild(k, std::move(children));
  }
  return p;
}

void toWire(const models::ModelChoice& c, wire::ModelChoice& out) {
  out.set_law(c.law);
  toWire(c.params, *out.mutable_params());
}

models::ModelChoice fromWire(const wire::ModelChoice& in, const std::string& field) {
  if (in.law().empty()) throw ProtocolError("SceneModels: " + field + ".law is empty");
  return {in.law(), fromWire(in.params(), field + ".params", 0)};
}

}  // namespace

void toWire(const models::SceneModelChoices& c, const models::SceneConstants& k,
            wire::SceneModels& out) {
  if (c.drag) toWire(*c.drag, *out.mutable_drag());
  for (const auto& f : c.forces) toWire(f, *out.add_forces());
  if (c.mass_transfer) toWire(*c.mass_transfer, *out.mutable_mass_transfer());
  if (c.coating_zone) toWire(*c.coating_zone, *out.mutable_coating_zone());
  for (const auto& p : c.plugins) out.add_plugins(p);
  auto& w = *out.mutable_constants();
  w.set_cg(k.cg);
  w.set_min_voidage(k.min_voidage);
  w.mutable_gravity()->Add(std::begin(k.gravity), std::end(k.gravity));
  w.set_schmidt(k.schmidt);
}

ReceivedModels fromWire(const wire::SceneModels& in) {
  ReceivedModels r;
  if (in.has_drag()) r.choices.drag = fromWire(in.drag(), "drag");
  for (int i = 0; i < in.forces_size(); ++i)
    r.choices.forces.push_back(fromWire(in.forces(i), "forces[" + std::to_string(i) + "]"));
  if (in.has_mass_transfer())
    r.choices.mass_transfer = fromWire(in.mass_transfer(), "mass_transfer");
  if (in.has_coating_zone()) r.choices.coating_zone = fromWire(in.coating_zone(), "coating_zone");
  r.choices.plugins.assign(in.plugins().begin(), in.plugins().end());
  const auto& w = in.constants();
  if (!in.has_constants() || w.gravity_size() != 3) {
    throw ProtocolError("SceneModels: constants.gravity has " + std::to_string(w.gravity_size()) +
                        " values, expected 3 (x, y, z) [m/s2]");
  }
  r.constants.cg = w.cg();
  r.constants.min_voidage = w.min_voidage();
  for (int i = 0; i < 3; ++i) r.constants.gravity[i] = w.gravity(i);
  r.constants.schmidt = w.schmidt();
  // the laws' own check of their constants (a peer's form is checked as the scene's is)
  try {
    models::validateConstants("SceneModels.constants", r.constants);
  } catch (const models::ModelError& e) {
    throw ProtocolError(e.what());
  }
  return r;
}

}  // namespace cosim::link
