#include "scenario.h"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>

#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "cosim/util/long_quotes.h"
#include "scenario/limits.h"
#include "scenario/yaml_input.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

const std::vector<KeySpec>& topLevelKeys() {
  static const std::vector<KeySpec> k = {
      {"extends", "none",
       "a scenario file (relative to this one) that this scene is a variant of: it is read "
       "first and this file's keys are merged into it, map by map (a value or a list replaces "
       "the other file's whole node); one level only"},
      {"name", "the folder's name",
       "the scene's name, which names its run folder: letters, digits, . _ - +, at most 100 "
       "characters, not starting with . or -"},
      {"description", "none", "one line"},
      {"parameters", "none",
       "numbers the rest of the file uses as ${name} or in ${expressions}, each name: value or "
       "name: { value, min, max, doc, show } (below); later ones may use earlier ones"},
      {"participants", "required",
       "particles (always) and fluid (started only if a model needs it), each as below"},
      {"coupling", "required", "the coupled time loop: interval, DEM steps, end, scheme"},
      {"constants", "the defaults below", "numbers every model sees, and the particle material"},
      {"models", "none", "the coupling laws; a scene without them couples nothing"},
      {"output", "the defaults below", "the run folder and the particle snapshots"},
      {"checkpoint", "none", "periodic checkpoints for cosim resume"},
      {"transport", "ipc in /tmp/cosim-UID/", "the link between cosim and its participants"},
      {"checks", "the defaults below", "what stops a run, and what is refused before it starts"},
      {"observables", "none", "named results with optional analytic references"},
  };
  return k;
}

const std::vector<KeySpec>& parameterKeys() {
  static const std::vector<KeySpec> k = {
      {"value", "required", "the number, or one ${expression} of earlier parameters"},
      {"min", "none",
       "the smallest value the scene holds for (inclusive; a number or ${expression}); a value "
       "below it is refused before anything starts, with the range and the doc"},
      {"max", "none", "the largest value the scene holds for, as min"},
      {"doc", "none", "what the parameter is, shown with a refused value and by cosim validate"},
      {"show", "false",
       "true: cosim validate prints the value (a derived number such as a bed's "
       "depth or the estimated cost)"},
  };
  return k;
}

namespace {

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

// The top-level keys --set may name (extends is read before any override).
const std::set<std::string>& sectionNames() {
  static const std::set<std::string> sections = [] {
    std::set<std::string> s;
    for (const auto& k : topLevelKeys())
      if (k.name != "extends") s.insert(k.name);
    return s;
  }();
  return sections;
}

// "a.b.c" -> {"a", "b", "c"}; a bare name is a parameter: {"parameters", name}.
std::vector<std::string> keyPath(const std::string& key, const std::string& shown,
                                 const Context& ctx) {
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string p; std::getline(ss, p, '.');) {
    if (p.empty()) ctx.failCommandLine(shown, "empty name in the key '" + key + "'");
    parts.push_back(p);
  }
  if (parts.empty()) ctx.failCommandLine(shown, "no key given");
  if (!sectionNames().count(parts.front())) {
    if (parts.size() == 1) {
      parts.insert(parts.begin(), "parameters");  // bare name: a parameter
    } else {
      ctx.failCommandLine(shown, "unknown section '" + parts.front() + "'");
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
// How an override is named in messages: as given, cut if very long.
std::string shownOverride(const std::string& flag, const std::string& arg) {
  return flag + " " + util::cutInput(arg);
}

void applySet(YAML::Node root, const std::string& set, Context& ctx) {
  const std::string shown = shownOverride("--set", set);
  auto eq = set.find('=');
  if (eq == std::string::npos || eq == 0) {
    ctx.failCommandLine(
        shown,
        "expected key=value, e.g. --set coupling.end_time=0.5 (a whole node: --set "
        "'models.coating_zone={shape: sphere, center: [0, 0, 0.01], radius: 0.005}')");
  }
  const std::string key = set.substr(0, eq);
  const std::string value = set.substr(eq + 1);
  std::vector<std::string> parts = keyPath(key, shown, ctx);
  if (parts.front() == "parameters" && parts.size() == 2 &&
      !(root["parameters"] && root["parameters"][parts[1]])) {
    ctx.failCommandLine(
        shown, "the scenario has no parameter '" + parts[1] + "' (see its parameters: section)");
  }
  YAML::Node parsed;
  try {
    if (value.size() > limits::kMaxFileBytes) {
      ctx.failCommandLine(
          shown, "the value is longer than " + std::to_string(limits::kMaxFileBytes) + " bytes");
    }
    parsed = YAML::Load(value);
  } catch (const YAML::DeepRecursion&) {
    ctx.failCommandLine(shown,
                        "the value is nested thousands of levels deep (maps and lists "
                        "inside each other); a value needs a few");
  } catch (const YAML::Exception& e) {
    ctx.failCommandLine(shown,
                        "the value is not valid YAML: " + e.msg +
                            " (a map is written {key: value, ...}, a list [a, b, ...]; quote the "
                            "whole argument for the shell)");
  }
  checkYamlTree(parsed, "command line " + shown, false, joinPath(parts));
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node next = chain.back()[parts[i]];
    if (next.IsDefined() && !next.IsMap() && !next.IsNull()) {
      ctx.failCommandLine(shown, "'" + parts[i] + "' is not a section");
    }
    chain.push_back(next);
  }
  YAML::Node target = chain.back()[parts.back()];
  if (parts.front() == "parameters" && parts.size() == 2 && target.IsMap() && parsed.IsScalar()) {
    target["value"] = parsed;  // a parameter with a range: the value changes, the range stays
  } else {
    chain.back()[parts.back()] = parsed;
  }
  ctx.addOverride(joinPath(parts), shown);
}

// "a.b.c" -> node a/b/c removed (with everything below it); an error if it does not exist.
void applyUnset(YAML::Node root, const std::string& key, Context& ctx) {
  const std::string shown = shownOverride("--unset", key);
  std::vector<std::string> parts = keyPath(key, shown, ctx);
  YAML::Node node = root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    node.reset(node[parts[i]]);
    if (!node.IsMap()) {
      ctx.failCommandLine(
          shown, "the scenario has no '" +
                     joinPath({parts.begin(), parts.begin() + static_cast<std::ptrdiff_t>(i) + 1}) +
                     "' section");
    }
  }
  if (!node[parts.back()])
    ctx.failCommandLine(shown, "the scenario has no '" + joinPath(parts) + "'");
  node.remove(parts.back());
  ctx.addOverride(joinPath(parts), shown);
}

// Deep merge into `base`: maps are merged key by key, anything else in `over` replaces `base`.
// Nodes are moved, not copied, so that each keeps its line in its own file for the messages.
YAML::Node merge(YAML::Node base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return over;
  for (const auto& kv : over) {
    const auto k = kv.first.as<std::string>();
    if (base[k])
      base[k] = merge(base[k], kv.second);
    else
      base[k] = kv.second;
  }
  return base;
}

// The key path of every node under `n` ("a.b", "a.b[2]"); `values`: those that are not maps.
void keyPaths(const YAML::Node& n, const std::string& path, std::set<std::string>& all,
              std::set<std::string>* values) {
  if (!path.empty()) all.insert(path);
  if (n.IsMap()) {
    for (const auto& kv : n) {
      if (!kv.first.IsScalar()) continue;  // refused by the section parsers
      keyPaths(kv.second, path.empty() ? kv.first.Scalar() : path + "." + kv.first.Scalar(), all,
               values);
    }
  } else {
    if (values && !path.empty()) values->insert(path);
    if (n.IsSequence())
      for (std::size_t i = 0; i < n.size(); ++i)
        keyPaths(n[i], path + "[" + std::to_string(i) + "]", all, values);
  }
}

// A parameter's value, a number or one ${expression} of the parameters before it.
double parameterValue(const YAML::Node& v, const std::string& key, const Variables& before,
                      const Context& ctx) {
  if (!v.IsScalar()) ctx.fail(v, key, "expected a number or ${expression}");
  try {
    const std::string& s = v.Scalar();
    if (s.find("${") == std::string::npos) return ctx.number(v, key);
    if (!isSingleExpression(s)) ctx.fail(v, key, "expected one ${expression}");
    const auto b = s.find("${");
    return evaluate(s.substr(b + 2, s.rfind('}') - b - 2), before);
  } catch (const ExpressionError& e) {
    ctx.fail(v, key, e.what());
  }
}

// A parameter is `name: value`, or `name: {value: V, min: A, max: B, doc: "...", show: true}`
// when the scene states the range it holds for (inclusive bounds; numbers or ${...} of earlier
// parameters) or a value `cosim validate` shows. A value outside the range is refused before
// anything starts, with the range and what the parameter is.
double rangedParameter(const YAML::Node& v, const std::string& key, const Variables& before,
                       const Context& ctx, std::vector<ShownParameter>& shown_values) {
  ctx.allowOnly(v, key, parameterKeys());
  if (!v["value"]) ctx.fail(v, key + ".value", "missing; a parameter with a range needs its value");
  const double val = parameterValue(v["value"], key + ".value", before, ctx);
  const std::string doc = v["doc"] ? " (" + ctx.text(v["doc"], key + ".doc") + ")" : "";
  std::optional<double> lo, hi;
  if (v["min"]) lo = parameterValue(v["min"], key + ".min", before, ctx);
  if (v["max"]) hi = parameterValue(v["max"], key + ".max", before, ctx);
  const auto shown = [](double x) { return fmt::format("{:.6g}", x); };
  if (lo && hi && *lo > *hi)
    ctx.fail(v["min"], key + ".min",
             "the range is empty: min " + shown(*lo) + " > max " + shown(*hi));
  if ((lo && val < *lo) || (hi && val > *hi)) {
    ctx.fail(v["value"], key,
             shown(val) + " is outside [" + (lo ? shown(*lo) : std::string("-inf")) + ", " +
                 (hi ? shown(*hi) : std::string("inf")) + "], the range the scene holds for" + doc +
                 "; give a value within it");
  }
  if (v["show"]) {
    bool show = false;
    if (!YAML::convert<bool>::decode(v["show"], show))
      ctx.fail(v["show"], key + ".show", "expected true or false");
    if (show)
      shown_values.push_back({key.substr(key.find('.') + 1), val,
                              v["doc"] ? ctx.text(v["doc"], key + ".doc") : std::string()});
  }
  return val;
}

// Parameters first: each may use the ones before it.
Variables parseParameters(const YAML::Node& params, const Context& ctx,
                          std::vector<ShownParameter>& shown) {
  Variables out;
  if (!params) return out;
  if (!params.IsMap()) ctx.fail(params, "parameters", "expected a map name: value");
  for (const auto& kv : params) {
    const auto k = ctx.keyName(kv.first, "parameters");
    const std::string key = "parameters." + k;
    out[k] = kv.second.IsMap() ? rangedParameter(kv.second, key, out, ctx, shown)
                               : parameterValue(kv.second, key, out, ctx);
  }
  return out;
}

// A parameter given with its range becomes its bare value in the tree, so that
// scenario.resolved.yaml (and what reads it) holds `name: number` throughout.
void dropParameterRanges(YAML::Node params) {
  if (!params.IsMap()) return;
  for (auto kv : params)
    if (kv.second.IsMap()) params[kv.first.Scalar()] = kv.second["value"];
}

// A scene that extends another and gives a bare value for a parameter the other file gives
// with its range changes the value only: the range stays.
void keepBaseRanges(const YAML::Node& base, YAML::Node own) {
  const YAML::Node bp = base["parameters"];
  YAML::Node op = own["parameters"];
  if (!bp.IsMap() || !op.IsMap()) return;
  for (auto kv : op) {
    if (!kv.first.IsScalar() || !kv.second.IsScalar()) continue;
    const std::string k = kv.first.Scalar();
    if (!bp[k].IsMap()) continue;
    YAML::Node wrapped(YAML::NodeType::Map);
    wrapped["value"] = kv.second;
    op[k] = wrapped;
  }
}

// extends: another scenario file this one only changes (e.g. a size variant of a scene).
YAML::Node applyExtends(YAML::Node root, const fs::path& origin, Context& ctx) {
  if (!root["extends"]) return root;
  const fs::path base = fs::absolute(origin).parent_path() / ctx.text(root["extends"], "extends");
  std::string text;
  try {
    text = readScenarioFile(base);
  } catch (const ScenarioError& e) {
    ctx.fail(root["extends"], "extends", e.what());
  }
  YAML::Node b = loadYaml(text, base.string(), true);
  if (!b.IsMap()) {
    ctx.fail(root["extends"], "extends",
             "'" + base.string() + "' is not a scenario (expected a map of sections)");
  }
  if (b["extends"])
    ctx.fail(root["extends"], "extends",
             "'" + base.string() + "' extends another file itself; one level only");
  root.remove("extends");
  keepBaseRanges(b, root);
  std::set<std::string> base_keys, own, own_values;
  keyPaths(b, "", base_keys, nullptr);
  keyPaths(root, "", own, &own_values);
  ctx.setExtends(base, std::move(base_keys), std::move(own), std::move(own_values));
  return merge(b, root);
}

Scenario parseTree(YAML::Node root, const fs::path& origin, const std::vector<std::string>& sets,
                   const std::vector<std::string>& unsets, Context& ctx, std::string& reading) {
  Scenario sc;
  sc.file = fs::absolute(origin);
  sc.dir = sc.file.parent_path();
  if (!root.IsMap())
    ctx.failTop("(top level)", "expected a map with name, participants, coupling, models ...");
  root = applyExtends(root, origin, ctx);
  ctx.allowOnly(root, "", topLevelKeys());
  for (const auto& u : unsets) applyUnset(root, u, ctx);
  for (const auto& s : sets) applySet(root, s, ctx);
  sc.overrides = sets;

  reading = "parameters";
  sc.parameters = parseParameters(root["parameters"], ctx, sc.shown);
  dropParameterRanges(root["parameters"]);
  reading = "name";
  sc.name =
      root["name"] ? ctx.text(root["name"], "name") : origin.parent_path().filename().string();
  sc.parameters.erase("name");
  reading = "(templating)";
  templateTree(root, sc.parameters, ctx, "");
  sc.resolved = root;
  if (sc.name.empty()) sc.name = "scene";
  if (const std::string why = unsafeNameReason(sc.name); !why.empty()) {
    ctx.fail(root["name"], "name",
             "'" + sc.name + "' " + why +
                 "; the name names the run folder: use letters, digits, '.', '_', '-', '+'");
  }
  if (root["description"]) sc.description = ctx.text(root["description"], "description");

  reading = "coupling";
  sc.coupling = parseCoupling(root["coupling"], ctx);
  reading = "constants";
  sc.constants = parseConstants(root["constants"], ctx);
  reading = "participants";
  sc.participants = parseParticipants(root["participants"], ctx, sc.dir);
  reading = "models";
  sc.models = parseModels(root["models"], ctx, sc.dir);
  if (sc.models.needsFluid() && !sc.participants.count("fluid")) {
    ctx.failTop("participants.fluid",
                "missing, but the models need fluid fields (drag, forces or mass transfer); add a "
                "fluid participant (adapter: openfoam or analytic-fluid)");
  }
  // The prescribed flow of analytic-fluid is never disturbed by the particles: there is no own
  // wake to take out of its samples.
  if (sc.models.drag && sc.participants.count("fluid") &&
      sc.participants.at("fluid").adapter == "analytic-fluid" &&
      sc.models.drag->params.text("undisturbed_velocity", "none") != "none") {
    ctx.fail(root["models"]["drag"], "models.drag.undisturbed_velocity",
             sc.models.drag->params.text("undisturbed_velocity") +
                 " removes the particle's own disturbance of the gas it samples, but the "
                 "analytic-fluid's prescribed flow carries none (it is not two-way coupled); use "
                 "'none'");
  }
  reading = "output";
  sc.output = parseOutput(root["output"], ctx, sc.name);
  reading = "checkpoint";
  sc.checkpoint = parseCheckpoint(root["checkpoint"], ctx);
  reading = "transport";
  sc.transport = parseTransport(root["transport"], ctx, sc.dir);
  reading = "checks";
  sc.checks = parseChecks(root["checks"], ctx);
  reading = "observables";
  sc.observables = parseObservables(root["observables"], ctx);
  return sc;
}

}  // namespace

Scenario parseScenario(const std::string& text, const fs::path& origin,
                       const std::vector<std::string>& sets,
                       const std::vector<std::string>& unsets) {
  Context ctx(origin);
  std::string reading = "(top level)";
  try {
    return parseTree(loadYaml(text, origin.string(), true), origin, sets, unsets, ctx, reading);
  } catch (const YAML::Exception& e) {
    // A shape no section check foresaw: still name the file, the line and the section.
    std::string msg = origin.string();
    if (e.mark.line >= 0) msg += ":" + std::to_string(e.mark.line + 1);
    throw ScenarioError(msg + ": " + reading + ": unexpected structure (" + e.msg +
                        "); compare the section with docs/scenario.md");
  }
}

Scenario loadScenario(const fs::path& file, const std::vector<std::string>& sets,
                      const std::vector<std::string>& unsets) {
  fs::path path = file;
  if (fs::is_directory(path)) path /= "scenario.yaml";
  return parseScenario(readScenarioFile(path), path, sets, unsets);
}

Scenario loadRunScene(const fs::path& run, const std::vector<std::string>& sets) {
  const auto file = run / "scenario.resolved.yaml";
  std::ifstream in(file);
  if (!in)
    throw ScenarioError(run.string() + " is not a run folder (no scenario.resolved.yaml in it)");
  std::stringstream text;
  text << in.rdbuf();
  std::string first;
  std::getline(text, first);
  const std::string prefix = "# ", suffix = " as run";
  const auto end = first.find(suffix);
  if (first.rfind(prefix, 0) != 0 || end == std::string::npos)
    throw ScenarioError(file.string() +
                        ": its first line must name the scenario it was made "
                        "from ('# <file> as run ...'); was it edited?");
  return parseScenario(text.str(), first.substr(prefix.size(), end - prefix.size()), sets);
}

}  // namespace cosim::orchestrator
