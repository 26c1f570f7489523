#include "scenario/models_section.h"

#include <algorithm>
#include <cstdlib>

#include "cosim/models/registry.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

const std::vector<KeySpec>& ModelsSection::keys() {
  static const std::vector<KeySpec> k = {
      {"drag", "none",
       "{ law: NAME, parameters... }: the drag on the parcels and its reaction on the gas; the "
       "laws and their parameters: docs/models.md; every law also takes the keys of "
       "models.drag below"},
      {"forces", "[]", "list of { law: NAME, parameters... }, e.g. pressure_gradient"},
      {"mass_transfer", "none",
       "{ law: NAME, parameters... }: coating from the precursor; absent, no species is solved "
       "and no precursor or coating field is sent anywhere"},
      {"coating_zone", "everywhere",
       "{ shape: NAME, parameters... }: where the precursor deposits; needs mass_transfer; the "
       "fields of each shape: docs/models.md"},
      {"plugins", "[]",
       "shared libraries registering more laws; a relative path is relative to the scenario "
       "file's folder, also when given with --set (an absolute path is taken as it is)"},
  };
  return k;
}

const std::vector<KeySpec>& ModelsSection::dragKeys() {
  static const std::vector<KeySpec> k = {
      {"law", "required", "the drag law's name (cosim models lists them)"},
      {"undisturbed_velocity", "none",
       "none | self_disturbance | self_disturbance_transient: evaluate the drag with the gas "
       "velocity the parcel would see without its own disturbance of its cell (any law, plugins "
       "included). self_disturbance takes the steady disturbance; self_disturbance_transient the "
       "part of it built up so far, from a force history per parcel id that the coupler keeps "
       "(and writes in checkpoints). Adds the cell_size and voidage fields; refused with "
       "analytic-fluid (a prescribed flow has no wake of its own); docs/models.md, \"Undisturbed "
       "gas velocity\""},
      {"self_disturbance_gain", "1 (the lattice)",
       "gamma, the gas solver's answer per unit force against the lattice's, 0.5 .. 2: the "
       "calibration of the undisturbed-velocity estimate for the scene's mesh, particle, solver "
       "settings and time step, measured with a held parcel (docs/models.md, \"Calibrating for "
       "the gas solver\"). Read with self_disturbance(_transient), kept unused with an "
       "explicit none, refused without undisturbed_velocity"},
      {"self_disturbance_offset", "0 (the lattice)",
       "beta, the parcel's own cell running ahead of the undisturbed gas with no force, "
       "-0.3 .. 0.3; calibrated and read as self_disturbance_gain"},
  };
  return k;
}

namespace {

models::Parameters toParameters(const YAML::Node& map, const std::string& owner,
                                const std::vector<std::string>& skip, const Context& ctx,
                                const std::string& key) {
  models::Parameters p(owner);
  if (!map.IsMap()) ctx.fail(map, key, "expected a map of parameters");
  for (const auto& kv : map) {
    const std::string k = ctx.keyName(kv.first, key);
    if (std::find(skip.begin(), skip.end(), k) != skip.end()) continue;
    const YAML::Node& v = kv.second;
    if (v.IsScalar()) {
      const std::string s = v.Scalar();
      char* end = nullptr;
      (void)std::strtod(s.c_str(), &end);
      if (end != s.c_str() && *end == '\0') {
        p.set(k, ctx.number(v, key + "." + k));
      } else if (s == "true" || s == "yes" || s == "on") {
        p.set(k, 1.0);
      } else if (s == "false" || s == "no" || s == "off") {
        p.set(k, 0.0);
      } else {
        p.setText(k, s);
      }
    } else if (v.IsSequence()) {
      if (v.size() > 0 && v[0].IsMap()) {
        std::vector<models::Parameters> children;
        for (std::size_t i = 0; i < v.size(); ++i) {
          const std::string ck = key + "." + k + "[" + std::to_string(i) + "]";
          std::string child_owner = owner + " " + k + "[" + std::to_string(i) + "]";
          if (!v[i].IsMap()) ctx.fail(v[i], ck, "expected a map like the first item of the list");
          std::string shape;
          if (v[i]["shape"]) {
            shape = ctx.text(v[i]["shape"], ck + ".shape");
            child_owner = "coating zone shape '" + shape + "'";
          }
          auto child = toParameters(v[i], child_owner, {}, ctx, ck);
          if (!shape.empty()) child.setText("shape", shape);
          children.push_back(child);
        }
        p.setChild(k, children);
      } else {
        std::vector<double> list;
        for (std::size_t i = 0; i < v.size(); ++i) {
          list.push_back(ctx.number(v[i], key + "." + k + "[" + std::to_string(i) + "]"));
        }
        p.setList(k, list);
      }
    } else if (v.IsMap()) {
      p.setChild(k, {toParameters(v, owner + " " + k, {}, ctx, key + "." + k)});
    }
  }
  return p;
}

ModelSpec modelSpec(const YAML::Node& n, const std::string& key, const std::string& kind,
                    const std::string& name_key, const Context& ctx) {
  if (!n.IsMap()) {
    ctx.fail(n, key, "expected a map like { " + name_key + ": NAME, ... }");
  }
  ModelSpec m;
  m.law = ctx.text(n[name_key], key + "." + name_key);
  m.line = n.Mark().line + 1;
  m.params = toParameters(n, kind + " '" + m.law + "' (" + key + ")", {name_key}, ctx, key);
  return m;
}

}  // namespace

ModelsSection parseModels(const YAML::Node& m, const Context& ctx, const fs::path& dir) {
  ModelsSection out;
  if (!ctx.section(m, "models", "{ drag: ..., forces: [...], mass_transfer: ... }")) return out;
  auto& registry = models::Registry::instance();
  ctx.allowOnly(m, "models", ModelsSection::keys());
  if (m["plugins"]) {
    if (!m["plugins"].IsSequence())
      ctx.fail(m["plugins"], "models.plugins", "expected a list of shared-library paths");
    for (std::size_t i = 0; i < m["plugins"].size(); ++i) {
      fs::path pth = dir / ctx.text(m["plugins"][i], "models.plugins");
      if (!fs::exists(pth))
        ctx.fail(m["plugins"][i], "models.plugins",
                 "plugin '" + pth.string() +
                     "' not found (a relative path is taken from the scenario's folder, " +
                     dir.string() + ", also with --set; give an absolute path for another place)");
      try {
        registry.loadPlugin(pth.string());
      } catch (const std::exception& e) {
        ctx.fail(m["plugins"][i], "models.plugins", e.what());
      }
      out.plugins.push_back(pth);
    }
  }
  // Builds the model once to check its parameters. An unknown law is the fault of the key
  // naming it (models.drag.law), anything else of the model's node (its parameters together).
  auto check = [&](const YAML::Node& node, const std::string& key, const std::string& name_key,
                   const std::string& law, const std::vector<std::string>& known, auto make) {
    try {
      make();
    } catch (const std::exception& e) {
      if (std::find(known.begin(), known.end(), law) == known.end())
        ctx.fail(node[name_key], key + "." + name_key, e.what());
      ctx.fail(node, key, e.what());
    }
  };
  if (m["drag"]) {
    out.drag = modelSpec(m["drag"], "models.drag", "drag law", "law", ctx);
    check(m["drag"], "models.drag", "law", out.drag->law, registry.dragNames(),
          [&] { registry.makeDrag(out.drag->law, out.drag->params); });
  }
  if (m["forces"]) {
    if (!m["forces"].IsSequence())
      ctx.fail(m["forces"], "models.forces", "expected a list like [ { law: pressure_gradient } ]");
    for (std::size_t i = 0; i < m["forces"].size(); ++i) {
      const std::string key = "models.forces[" + std::to_string(i) + "]";
      out.forces.push_back(modelSpec(m["forces"][i], key, "force model", "law", ctx));
      check(m["forces"][i], key, "law", out.forces.back().law, registry.forceNames(),
            [&] { registry.makeForce(out.forces.back().law, out.forces.back().params); });
    }
  }
  if (m["mass_transfer"]) {
    out.mass_transfer =
        modelSpec(m["mass_transfer"], "models.mass_transfer", "mass transfer law", "law", ctx);
    check(m["mass_transfer"], "models.mass_transfer", "law", out.mass_transfer->law,
          registry.massTransferNames(),
          [&] { registry.makeMassTransfer(out.mass_transfer->law, out.mass_transfer->params); });
  }
  if (m["coating_zone"]) {
    if (!out.mass_transfer) {
      ctx.fail(m["coating_zone"], "models.coating_zone",
               "a coating zone without models.mass_transfer coats nothing; add a mass_transfer "
               "law or remove the zone");
    }
    out.coating_zone =
        modelSpec(m["coating_zone"], "models.coating_zone", "coating zone", "shape", ctx);
    check(m["coating_zone"], "models.coating_zone", "shape", out.coating_zone->law,
          registry.zoneNames(),
          [&] { registry.makeZone(out.coating_zone->law, out.coating_zone->params); });
  }
  return out;
}

models::SceneModelChoices ModelsSection::choices() const {
  models::SceneModelChoices c;
  if (drag) c.drag = *drag;
  for (const auto& f : forces) c.forces.push_back(f);
  if (mass_transfer) c.mass_transfer = *mass_transfer;
  if (coating_zone) c.coating_zone = *coating_zone;
  for (const auto& p : plugins) c.plugins.push_back(p.string());
  return c;
}

}  // namespace cosim::orchestrator
