#include "scenario.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "cosim/models/registry.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

const std::map<std::string, AdapterInfo>& knownAdapters() {
  static const std::map<std::string, AdapterInfo> m = {
      {"analytic-fluid", {"cosim-analytic-fluid", wire::FLUID}},
      {"openfoam", {"cosimFoam", wire::FLUID}},
      {"free-particles", {"cosim-free-particles", wire::PARTICLES}},
      {"liggghts", {"cosim-liggghts", wire::PARTICLES}},
  };
  return m;
}

namespace {

// Error helper: "<file>:<line>: <key>: <what>".
class Context {
 public:
  explicit Context(fs::path origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key,
                         const std::string& what) const {
    std::ostringstream os;
    os << origin_.string();
    // A value that came from the command line has no line in the file: name the override.
    for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
      if (within(key, o->first)) {
        os << ": " << o->second << ": " << key << ": " << what;
        throw ScenarioError(os.str());
      }
    }
    if (node.IsDefined() && node.Mark().line >= 0) os << ":" << node.Mark().line + 1;
    os << ": " << key << ": " << what;
    for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
      if (within(o->first, key)) {
        os << " (" << o->first << " comes from the command line: " << o->second << ")";
        break;
      }
    }
    throw ScenarioError(os.str());
  }
  // An override of the command line ("--set KEY=VALUE", "--unset KEY") that changed `path`.
  void addOverride(const std::string& path, const std::string& shown) {
    overrides_.emplace_back(path, shown);
  }
  [[noreturn]] void failTop(const std::string& key, const std::string& what) const {
    for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
      if (within(key, o->first)) {
        throw ScenarioError(origin_.string() + ": " + o->second + ": " + key + ": " + what);
      }
    }
    throw ScenarioError(origin_.string() + ": " + key + ": " + what);
  }

  void allowOnly(const YAML::Node& map, const std::string& where,
                 const std::vector<std::string>& keys) const {
    if (!map.IsMap()) return;
    for (const auto& kv : map) {
      const auto k = kv.first.as<std::string>();
      if (std::find(keys.begin(), keys.end(), k) == keys.end()) {
        std::string list;
        for (const auto& q : keys) list += (list.empty() ? "" : ", ") + q;
        fail(kv.first, where.empty() ? k : where + "." + k,
             "unknown key (allowed here: " + list + "). Check the spelling.");
      }
    }
  }

  double number(const YAML::Node& n, const std::string& key) const {
    if (!n.IsDefined() || n.IsNull()) fail(n, key, "missing; expected a number");
    if (!n.IsScalar()) fail(n, key, "expected a number, got a list or map");
    const std::string s = n.Scalar();
    char* end = nullptr;
    double v = std::strtod(s.c_str(), &end);
    if (end == s.c_str() || *end != '\0') fail(n, key, "expected a number, got '" + s + "'");
    if (!std::isfinite(v)) fail(n, key, "expected a finite number, got '" + s + "'");
    return v;
  }
  double positive(const YAML::Node& n, const std::string& key, const std::string& unit) const {
    double v = number(n, key);
    if (!(v > 0)) fail(n, key, "must be > 0 " + unit + ", got " + n.Scalar());
    return v;
  }
  std::string text(const YAML::Node& n, const std::string& key) const {
    if (!n.IsDefined() || n.IsNull()) fail(n, key, "missing; expected a text value");
    if (!n.IsScalar()) fail(n, key, "expected a text value, got a list or map");
    return n.Scalar();
  }

  const fs::path& origin() const { return origin_; }

 private:
  // `key` is `path` or below it ("a.b" is within "a", "a[2]" within "a", "ab" not within "a").
  static bool within(const std::string& key, const std::string& path) {
    return key.rfind(path, 0) == 0 &&
           (key.size() == path.size() || key[path.size()] == '.' || key[path.size()] == '[');
  }
  fs::path origin_;
  std::vector<std::pair<std::string, std::string>> overrides_;  // path, as given
};

// Applies ${expr} to every scalar of the tree.
void templateTree(YAML::Node node, const Variables& vars, const Context& ctx,
                  const std::string& path) {
  if (node.IsScalar()) {
    const std::string s = node.Scalar();
    if (s.find("${") == std::string::npos) return;
    try {
      node = substitute(s, vars);
    } catch (const ExpressionError& e) {
      ctx.fail(node, path, e.what());
    }
  } else if (node.IsMap()) {
    for (auto kv : node) {
      templateTree(
          kv.second, vars, ctx,
          path.empty() ? kv.first.as<std::string>() : path + "." + kv.first.as<std::string>());
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      templateTree(node[i], vars, ctx, path + "[" + std::to_string(i) + "]");
    }
  }
}

const std::set<std::string>& sectionNames() {
  static const std::set<std::string> sections = {
      "name",   "description", "parameters", "participants", "coupling",   "constants",
      "models", "output",      "transport",  "checks",       "observables", "checkpoint"};
  return sections;
}

// "a.b.c" -> {"a", "b", "c"}; a bare name is a parameter: {"parameters", name}.
std::vector<std::string> keyPath(const std::string& key, const std::string& shown,
                                 const Context& ctx) {
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string p; std::getline(ss, p, '.');) {
    if (p.empty()) ctx.failTop(shown, "empty name in the key '" + key + "'");
    parts.push_back(p);
  }
  if (parts.empty()) ctx.failTop(shown, "no key given");
  if (!sectionNames().count(parts.front())) {
    if (parts.size() == 1) {
      parts.insert(parts.begin(), "parameters");  // bare name: a parameter
    } else {
      ctx.failTop(shown, "unknown section '" + parts.front() + "'");
    }
  }
  return parts;
}

std::string joinPath(const std::vector<std::string>& parts) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : ".") + p;
  return out;
}

// "a.b.c=value" -> node a/b/c = value. The value is YAML: numbers, text, lists and maps work;
// a list or map replaces the whole node (nothing of the old one is kept).
void applySet(YAML::Node root, const std::string& set, Context& ctx) {
  const std::string shown = "--set " + set;
  auto eq = set.find('=');
  if (eq == std::string::npos || eq == 0) {
    ctx.failTop(shown,
                "expected key=value, e.g. --set coupling.end_time=0.5 (a whole node: --set "
                "'models.coating_zone={shape: sphere, center: [0, 0, 0.01], radius: 0.005}')");
  }
  const std::string key = set.substr(0, eq);
  const std::string value = set.substr(eq + 1);
  std::vector<std::string> parts = keyPath(key, shown, ctx);
  if (parts.front() == "parameters" && parts.size() == 2 &&
      !(root["parameters"] && root["parameters"][parts[1]])) {
    ctx.failTop(shown,
                "the scenario has no parameter '" + parts[1] + "' (see its parameters: section)");
  }
  YAML::Node parsed;
  try {
    parsed = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    ctx.failTop(shown, "the value is not valid YAML: " + e.msg +
                           " (a map is written {key: value, ...}, a list [a, b, ...]; quote the "
                           "whole argument for the shell)");
  }
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node next = chain.back()[parts[i]];
    if (next.IsDefined() && !next.IsMap() && !next.IsNull()) {
      ctx.failTop(shown, "'" + parts[i] + "' is not a section");
    }
    chain.push_back(next);
  }
  chain.back()[parts.back()] = parsed;
  ctx.addOverride(joinPath(parts), shown);
}

// "a.b.c" -> node a/b/c removed (with everything below it); an error if it does not exist.
void applyUnset(YAML::Node root, const std::string& key, Context& ctx) {
  const std::string shown = "--unset " + key;
  std::vector<std::string> parts = keyPath(key, shown, ctx);
  YAML::Node node = root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    node.reset(node[parts[i]]);
    if (!node.IsMap()) {
      ctx.failTop(
          shown, "the scenario has no '" +
                     joinPath({parts.begin(), parts.begin() + static_cast<std::ptrdiff_t>(i) + 1}) +
                     "' section");
    }
  }
  if (!node[parts.back()]) ctx.failTop(shown, "the scenario has no '" + joinPath(parts) + "'");
  node.remove(parts.back());
  ctx.addOverride(joinPath(parts), shown);
}

models::Parameters toParameters(const YAML::Node& map, const std::string& owner,
                                const std::vector<std::string>& skip, const Context& ctx,
                                const std::string& key) {
  models::Parameters p(owner);
  for (const auto& kv : map) {
    const std::string k = kv.first.as<std::string>();
    if (std::find(skip.begin(), skip.end(), k) != skip.end()) continue;
    const YAML::Node& v = kv.second;
    if (v.IsScalar()) {
      const std::string s = v.Scalar();
      char* end = nullptr;
      double d = std::strtod(s.c_str(), &end);
      if (end != s.c_str() && *end == '\0') {
        p.set(k, d);
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
          if (v[i]["shape"]) child_owner = "coating zone shape '" + v[i]["shape"].Scalar() + "'";
          auto child = toParameters(v[i], child_owner, {}, ctx, ck);
          if (v[i]["shape"]) child.setText("shape", v[i]["shape"].Scalar());
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

namespace {
// Deep merge: maps are merged key by key, anything else in `over` replaces `base`.
YAML::Node merge(const YAML::Node& base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return YAML::Clone(over);
  YAML::Node out = YAML::Clone(base);
  for (const auto& kv : over) {
    const auto k = kv.first.as<std::string>();
    out[k] = out[k] ? merge(out[k], kv.second) : YAML::Clone(kv.second);
  }
  return out;
}
}  // namespace

Scenario parseScenario(const std::string& text, const fs::path& origin,
                       const std::vector<std::string>& sets,
                       const std::vector<std::string>& unsets) {
  Context ctx(origin);
  Scenario sc;
  sc.file = fs::absolute(origin);
  sc.dir = sc.file.parent_path();

  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ScenarioError(origin.string() + ":" + std::to_string(e.mark.line + 1) +
                        ": not valid YAML: " + e.msg);
  }
  if (!root.IsMap())
    ctx.failTop("(top level)", "expected a map with name, participants, coupling, models ...");
  // extends: another scenario file this one only changes (e.g. a size variant of a scene).
  if (root["extends"]) {
    const fs::path base = fs::absolute(origin).parent_path() / ctx.text(root["extends"], "extends");
    std::ifstream in(base);
    if (!in) ctx.fail(root["extends"], "extends", "cannot open '" + base.string() + "'");
    YAML::Node b;
    try {
      b = YAML::LoadFile(base.string());
    } catch (const YAML::ParserException& e) {
      throw ScenarioError(base.string() + ":" + std::to_string(e.mark.line + 1) +
                          ": not valid YAML: " + e.msg);
    }
    if (b["extends"])
      ctx.fail(root["extends"], "extends",
               "'" + base.string() + "' extends another file itself; one level only");
    root.remove("extends");
    root = merge(b, root);
  }
  ctx.allowOnly(root, "",
                {"name", "description", "parameters", "participants", "coupling", "constants",
                 "models", "output", "transport", "checks", "observables", "checkpoint"});
  for (const auto& u : unsets) applyUnset(root, u, ctx);
  for (const auto& s : sets) applySet(root, s, ctx);

  // Parameters first: each may use the ones before it.
  if (root["parameters"]) {
    if (!root["parameters"].IsMap())
      ctx.fail(root["parameters"], "parameters", "expected a map name: value");
    for (auto kv : root["parameters"]) {
      const auto k = kv.first.as<std::string>();
      YAML::Node v = kv.second;
      if (!v.IsScalar()) ctx.fail(v, "parameters." + k, "expected a number or ${expression}");
      try {
        const std::string s = v.Scalar();
        double val = 0;
        if (s.find("${") != std::string::npos) {
          if (!isSingleExpression(s)) ctx.fail(v, "parameters." + k, "expected one ${expression}");
          const auto b = s.find("${");
          val = evaluate(s.substr(b + 2, s.rfind('}') - b - 2), sc.parameters);
        } else {
          val = ctx.number(v, "parameters." + k);
        }
        sc.parameters[k] = val;
      } catch (const ExpressionError& e) {
        ctx.fail(v, "parameters." + k, e.what());
      }
    }
  }
  sc.name =
      root["name"] ? ctx.text(root["name"], "name") : origin.parent_path().filename().string();
  sc.parameters.erase("name");
  templateTree(root, sc.parameters, ctx, "");
  sc.resolved = root;
  if (sc.name.empty()) sc.name = "scene";
  if (root["description"]) sc.description = ctx.text(root["description"], "description");

  // ---- coupling --------------------------------------------------------------------------------
  const YAML::Node coupling = root["coupling"];
  if (!coupling)
    ctx.failTop("coupling",
                "missing section; expected { dt: SECONDS, dem_steps: N, end_time: SECONDS }");
  ctx.allowOnly(coupling, "coupling", {"dt", "dem_steps", "end_time", "start_time"});
  sc.dt =
      ctx.positive(coupling["dt"], "coupling.dt", "(coupling interval = CFD time step, seconds)");
  sc.end_time = ctx.positive(coupling["end_time"], "coupling.end_time", "(seconds)");
  if (coupling["start_time"])
    sc.start_time = ctx.number(coupling["start_time"], "coupling.start_time");
  if (coupling["dem_steps"]) {
    double n = ctx.number(coupling["dem_steps"], "coupling.dem_steps");
    if (n < 1 || n != std::floor(n) || n > 1e7) {
      ctx.fail(coupling["dem_steps"], "coupling.dem_steps",
               "expected a whole number of DEM steps per coupling interval (>= 1), got " +
                   coupling["dem_steps"].Scalar());
    }
    sc.dem_steps = static_cast<unsigned>(n);
  }
  if (sc.end_time <= sc.start_time) {
    ctx.fail(coupling["end_time"], "coupling.end_time", "must be later than start_time");
  }
  if (sc.dt > sc.end_time - sc.start_time) {
    ctx.fail(coupling["dt"], "coupling.dt", "is longer than the whole run (end_time - start_time)");
  }

  // ---- constants --------------------------------------------------------------------------------
  if (const YAML::Node c = root["constants"]) {
    ctx.allowOnly(c, "constants",
                  {"cg", "min_voidage", "gravity", "schmidt", "particle_density", "youngs_modulus",
                   "poisson_ratio"});
    if (c["particle_density"])
      sc.material.particle_density =
          ctx.positive(c["particle_density"], "constants.particle_density", "(kg/m3)");
    if (c["youngs_modulus"])
      sc.material.youngs_modulus =
          ctx.positive(c["youngs_modulus"], "constants.youngs_modulus", "(Pa)");
    if (c["poisson_ratio"]) {
      sc.material.poisson_ratio = ctx.number(c["poisson_ratio"], "constants.poisson_ratio");
      if (sc.material.poisson_ratio <= -1 || sc.material.poisson_ratio >= 0.5) {
        ctx.fail(c["poisson_ratio"], "constants.poisson_ratio",
                 "expected a Poisson ratio in (-1, 0.5)");
      }
    }
    if (c["cg"]) {
      sc.constants.cg = ctx.number(c["cg"], "constants.cg");
      if (sc.constants.cg < 1.0) {
        ctx.fail(
            c["cg"], "constants.cg",
            "coarse-graining factor must be >= 1 (1 = real particles), got " + c["cg"].Scalar());
      }
    }
    if (c["min_voidage"]) {
      sc.constants.min_voidage = ctx.number(c["min_voidage"], "constants.min_voidage");
      if (sc.constants.min_voidage <= 0.0 || sc.constants.min_voidage >= 1.0) {
        ctx.fail(c["min_voidage"], "constants.min_voidage",
                 "expected a voidage in (0, 1), e.g. 0.35");
      }
    }
    if (c["gravity"]) {
      if (!c["gravity"].IsSequence() || c["gravity"].size() != 3) {
        ctx.fail(c["gravity"], "constants.gravity", "expected three numbers [gx, gy, gz] in m/s2");
      }
      for (int i = 0; i < 3; ++i)
        sc.constants.gravity[i] = ctx.number(c["gravity"][i], "constants.gravity");
    }
    if (c["schmidt"]) sc.constants.schmidt = ctx.positive(c["schmidt"], "constants.schmidt", "");
  }

  // ---- participants -----------------------------------------------------------------------------
  const YAML::Node parts = root["participants"];
  if (!parts || !parts.IsMap() || parts.size() == 0) {
    ctx.failTop("participants",
                "missing; expected at least 'particles: { adapter: ... }' (and 'fluid:' for "
                "coupled scenes)");
  }
  for (const auto& kv : parts) {
    const std::string pname = kv.first.as<std::string>();
    const std::string key = "participants." + pname;
    const YAML::Node p = kv.second;
    if (pname != "fluid" && pname != "particles") {
      ctx.fail(kv.first, key, "unknown participant; a scene has 'fluid' and/or 'particles'");
    }
    if (!p.IsMap()) ctx.fail(p, key, "expected a map with at least 'adapter:'");
    ctx.allowOnly(p, key,
                  {"adapter", "command", "args", "launch", "mpi", "files", "timeout", "options"});
    ParticipantSpec ps;
    ps.name = pname;
    ps.adapter = ctx.text(p["adapter"], key + ".adapter");
    ps.role = pname == "fluid" ? wire::FLUID : wire::PARTICLES;
    auto known = knownAdapters().find(ps.adapter);
    if (p["command"]) {
      ps.command = ctx.text(p["command"], key + ".command");
    } else if (known == knownAdapters().end()) {
      std::string list;
      for (const auto& [k, i] : knownAdapters()) list += (list.empty() ? "" : ", ") + k;
      ctx.fail(p["adapter"], key + ".adapter",
               "unknown adapter '" + ps.adapter + "' (known: " + list +
                   "; a custom adapter also needs 'command: /path/to/executable')");
    } else {
      if (known->second.role != ps.role) {
        ctx.fail(p["adapter"], key + ".adapter",
                 "adapter '" + ps.adapter + "' simulates " +
                     (known->second.role == wire::FLUID ? "the fluid" : "particles") +
                     " and cannot be the '" + pname + "' participant");
      }
      ps.command = known->second.executable;
    }
    if (p["args"]) {
      if (!p["args"].IsSequence())
        ctx.fail(p["args"], key + ".args", "expected a list of arguments");
      for (const auto& a : p["args"]) ps.args.push_back(a.Scalar());
    }
    if (p["launch"]) {
      ps.launch = ctx.text(p["launch"], key + ".launch");
      if (ps.launch != "local" && ps.launch != "external") {
        ctx.fail(p["launch"], key + ".launch",
                 "expected 'local' (cosim starts it) or 'external' (started elsewhere, connects to "
                 "the orchestrator)");
      }
    }
    if (p["mpi"]) {
      double n = ctx.number(p["mpi"], key + ".mpi");
      if (n < 1 || n != std::floor(n) || n > 4096) {
        ctx.fail(p["mpi"], key + ".mpi",
                 "expected a whole number of MPI ranks >= 1, got " + p["mpi"].Scalar());
      }
      ps.mpi = static_cast<int>(n);
    }
    if (p["timeout"])
      ps.timeout = ctx.positive(p["timeout"], key + ".timeout", "(seconds one step may take)");
    if (p["files"]) {
      ps.files = sc.dir / ctx.text(p["files"], key + ".files");
      if (!fs::is_directory(ps.files)) {
        ctx.fail(p["files"], key + ".files",
                 "folder '" + ps.files.string() +
                     "' does not exist (paths are relative to the scenario file)");
      }
    }
    ps.options = p["options"] ? YAML::Clone(p["options"]) : YAML::Node(YAML::NodeType::Map);
    if (!ps.options.IsMap())
      ctx.fail(p["options"], key + ".options", "expected a map of adapter settings");
    sc.participants[pname] = ps;
  }
  if (!sc.participants.count("particles")) {
    ctx.failTop("participants.particles",
                "missing; every scene has particles (adapter: liggghts or free-particles)");
  }

  // ---- models -----------------------------------------------------------------------------------
  auto& registry = models::Registry::instance();
  if (const YAML::Node m = root["models"]) {
    ctx.allowOnly(m, "models", {"drag", "forces", "mass_transfer", "coating_zone", "plugins"});
    if (m["plugins"]) {
      if (!m["plugins"].IsSequence())
        ctx.fail(m["plugins"], "models.plugins", "expected a list of shared-library paths");
      for (std::size_t i = 0; i < m["plugins"].size(); ++i) {
        fs::path pth = sc.dir / ctx.text(m["plugins"][i], "models.plugins");
        if (!fs::exists(pth))
          ctx.fail(m["plugins"][i], "models.plugins", "plugin '" + pth.string() + "' not found");
        try {
          registry.loadPlugin(pth.string());
        } catch (const std::exception& e) {
          ctx.fail(m["plugins"][i], "models.plugins", e.what());
        }
        sc.plugins.push_back(pth);
      }
    }
    auto check = [&](const YAML::Node& node, const std::string& key, auto make) {
      try {
        make();
      } catch (const std::exception& e) {
        ctx.fail(node, key, e.what());
      }
    };
    if (m["drag"]) {
      sc.drag = modelSpec(m["drag"], "models.drag", "drag law", "law", ctx);
      check(m["drag"], "models.drag", [&] { registry.makeDrag(sc.drag->law, sc.drag->params); });
    }
    if (m["forces"]) {
      if (!m["forces"].IsSequence())
        ctx.fail(m["forces"], "models.forces",
                 "expected a list like [ { law: pressure_gradient } ]");
      for (std::size_t i = 0; i < m["forces"].size(); ++i) {
        const std::string key = "models.forces[" + std::to_string(i) + "]";
        sc.forces.push_back(modelSpec(m["forces"][i], key, "force model", "law", ctx));
        check(m["forces"][i], key,
              [&] { registry.makeForce(sc.forces.back().law, sc.forces.back().params); });
      }
    }
    if (m["mass_transfer"]) {
      sc.mass_transfer =
          modelSpec(m["mass_transfer"], "models.mass_transfer", "mass transfer law", "law", ctx);
      check(m["mass_transfer"], "models.mass_transfer",
            [&] { registry.makeMassTransfer(sc.mass_transfer->law, sc.mass_transfer->params); });
    }
    if (m["coating_zone"]) {
      if (!sc.mass_transfer) {
        ctx.fail(m["coating_zone"], "models.coating_zone",
                 "a coating zone without models.mass_transfer coats nothing; add a mass_transfer "
                 "law or remove the zone");
      }
      sc.coating_zone =
          modelSpec(m["coating_zone"], "models.coating_zone", "coating zone", "shape", ctx);
      check(m["coating_zone"], "models.coating_zone",
            [&] { registry.makeZone(sc.coating_zone->law, sc.coating_zone->params); });
    }
  }
  const bool needs_fluid = sc.drag || !sc.forces.empty() || sc.mass_transfer;
  if (needs_fluid && !sc.participants.count("fluid")) {
    ctx.failTop("participants.fluid",
                "missing, but the models need fluid fields (drag, forces or mass transfer); add a "
                "fluid participant (adapter: openfoam or analytic-fluid)");
  }
  // The prescribed flow of analytic-fluid is never disturbed by the particles: there is no own
  // wake to take out of its samples.
  if (sc.drag && sc.participants.count("fluid") && sc.participants.at("fluid").adapter == "analytic-fluid" &&
      sc.drag->params.text("undisturbed_velocity", "none") == "self_disturbance") {
    ctx.fail(root["models"]["drag"], "models.drag.undisturbed_velocity",
             "self_disturbance removes the particle's own disturbance of the gas it samples, but the "
             "analytic-fluid's prescribed flow carries none (it is not two-way coupled); use 'none'");
  }

  // ---- output, transport, checks
  // ------------------------------------------------------------------
  sc.output_folder = fs::current_path() / "runs" / sc.name;
  if (const YAML::Node o = root["output"]) {
    ctx.allowOnly(o, "output", {"folder", "interval"});
    if (o["folder"]) {
      fs::path f = ctx.text(o["folder"], "output.folder");
      sc.output_folder = f.is_absolute() ? f : fs::current_path() / f;
    }
    if (o["interval"]) {
      sc.output_interval = ctx.number(o["interval"], "output.interval");
      if (sc.output_interval < 0)
        ctx.fail(o["interval"], "output.interval",
                 "must be >= 0 seconds (0 = every coupling step)");
    }
  }
  if (const YAML::Node c = root["checkpoint"]) {
    ctx.allowOnly(c, "checkpoint", {"interval", "keep"});
    if (c["interval"]) {
      sc.checkpoint_interval = ctx.number(c["interval"], "checkpoint.interval");
      if (!(sc.checkpoint_interval >= 0) || !std::isfinite(sc.checkpoint_interval))
        ctx.fail(c["interval"], "checkpoint.interval",
                 "must be >= 0 simulated seconds (0 = no periodic checkpoints)");
    }
    if (c["keep"]) {
      const double k = ctx.number(c["keep"], "checkpoint.keep");
      if (!(k >= 1) || k != std::floor(k) || k > 1000)
        ctx.fail(c["keep"], "checkpoint.keep",
                 "must be a whole number of checkpoints to keep, 1 to 1000");
      sc.checkpoint_keep = static_cast<int>(k);
    }
  }
  if (const YAML::Node t = root["transport"]) {
    ctx.allowOnly(t, "transport", {"bind", "connect", "heartbeat_timeout", "handshake_timeout"});
    if (t["bind"]) sc.bind_endpoint = ctx.text(t["bind"], "transport.bind");
    if (t["connect"]) sc.connect_endpoint = ctx.text(t["connect"], "transport.connect");
    for (const std::string& ep : {sc.bind_endpoint, sc.connect_endpoint}) {
      if (!ep.empty() && ep.rfind("ipc://", 0) != 0 && ep.rfind("tcp://", 0) != 0) {
        ctx.fail(t, "transport", "endpoint '" + ep + "' must start with ipc:// or tcp://");
      }
    }
    if (t["heartbeat_timeout"])
      sc.heartbeat_timeout =
          ctx.positive(t["heartbeat_timeout"], "transport.heartbeat_timeout", "(seconds)");
    if (t["handshake_timeout"])
      sc.handshake_timeout =
          ctx.positive(t["handshake_timeout"], "transport.handshake_timeout", "(seconds)");
  }
  if (const YAML::Node c = root["checks"]) {
    ctx.allowOnly(c, "checks",
                  {"stability", "max_particle_speed", "mass_balance_tolerance", "max_courant"});
    if (c["max_courant"]) sc.max_courant = ctx.positive(c["max_courant"], "checks.max_courant", "");
    if (c["stability"]) {
      sc.stability = ctx.text(c["stability"], "checks.stability");
      if (sc.stability != "refuse" && sc.stability != "warn") {
        ctx.fail(c["stability"], "checks.stability",
                 "expected 'refuse' (stop unstable settings) or 'warn'");
      }
    }
    if (c["max_particle_speed"])
      sc.max_particle_speed =
          ctx.positive(c["max_particle_speed"], "checks.max_particle_speed", "(m/s)");
    if (c["mass_balance_tolerance"])
      sc.mass_balance_tolerance =
          ctx.positive(c["mass_balance_tolerance"], "checks.mass_balance_tolerance", "");
  }
  if (const YAML::Node obs = root["observables"]) {
    if (!obs.IsMap())
      ctx.fail(obs, "observables", "expected a map name: { quantity: ..., reference: ... }");
    for (const auto& kv : obs) {
      const std::string name = kv.first.as<std::string>();
      const std::string key = "observables." + name;
      const YAML::Node o = kv.second;
      ctx.allowOnly(o, key, {"quantity", "reference", "after"});
      ObservableSpec spec;
      spec.name = name;
      spec.quantity = ctx.text(o["quantity"], key + ".quantity");
      try {
        checkQuantity(spec.quantity);
      } catch (const std::exception& e) {
        ctx.fail(o["quantity"], key + ".quantity", e.what());
      }
      if (o["reference"]) spec.reference = ctx.number(o["reference"], key + ".reference");
      if (o["after"]) spec.after = ctx.number(o["after"], key + ".after");
      sc.observables.push_back(spec);
    }
  }
  return sc;
}

Scenario loadScenario(const fs::path& file, const std::vector<std::string>& sets,
                      const std::vector<std::string>& unsets) {
  fs::path path = file;
  if (fs::is_directory(path)) path /= "scenario.yaml";
  std::ifstream in(path);
  if (!in) {
    throw ScenarioError(
        path.string() +
        ": cannot open the scenario file (does it exist? a scenario folder needs a scenario.yaml)");
  }
  std::stringstream ss;
  ss << in.rdbuf();
  return parseScenario(ss.str(), path, sets, unsets);
}

}  // namespace cosim::orchestrator
