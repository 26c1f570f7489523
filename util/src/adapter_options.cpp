#include "cosim/util/adapter_options.h"

#include <cctype>
#include <cmath>
#include <sstream>

#include "cosim/util/errors.h"
#include "cosim/util/format.h"

namespace cosim::util {

namespace {

std::string cell(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '<' && i + 1 < text.size() && std::isalpha(static_cast<unsigned char>(text[i + 1]))) {
      out += "&lt;";
    } else if (c == '|') {
      out += "\\|";
    } else if (c == '\n') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::string optionsTable(const std::vector<OptionSpec>& specs, const std::string& heading,
                         const std::string& prefix) {
  std::ostringstream os;
  os << "| " << heading << " | default | meaning |\n|---|---|---|\n";
  for (const auto& s : specs)
    os << "| `" << prefix << s.name << "` | " << cell(s.default_value) << " | " << cell(s.doc)
       << " |\n";
  return os.str();
}

AdapterOptions::AdapterOptions(const std::string& yaml, const std::string& participant,
                               std::string adapter, const std::vector<OptionSpec>& specs,
                               std::string page)
    : where_("scenario participants." + participant + ".options"),
      adapter_(std::move(adapter)),
      page_(std::move(page)) {
  try {
    root_ = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw InputError(where_ + ": not valid YAML: " + e.what());
  }
  if (!root_ || root_.IsNull()) root_ = YAML::Node(YAML::NodeType::Map);
  if (!root_.IsMap())
    throw InputError(where_ + ": expected a map of options (key: value), got '" + got(root_) + "'");
  std::vector<std::string> known;
  known.reserve(specs.size());
  for (const auto& s : specs) known.push_back(s.name);
  for (const auto& kv : root_) {
    const std::string key = kv.first.Scalar();
    bool ok = false;
    for (const auto& k : known) ok = ok || k == key;
    if (!ok)
      fail(key,
           "unknown option of " + adapter_ + "; it knows " + joined(known) + " (" + page_ + ")");
  }
}

std::string AdapterOptions::keyName(const std::string& key) const { return where_ + "." + key; }

void AdapterOptions::fail(const std::string& key, const std::string& what) const {
  throw InputError(keyName(key) + ": " + what);
}

std::string AdapterOptions::got(const YAML::Node& n) const {
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

double AdapterOptions::number(const std::string& key, double fallback, double lo, double hi) const {
  if (!has(key)) return fallback;
  const double v = numberAt(root_[key], key);
  if (!(v >= lo && v <= hi))
    fail(key, "expected a value in [" + exact(lo) + ", " + exact(hi) + "], got " + exact(v));
  return v;
}

double AdapterOptions::positive(const std::string& key, double fallback) const {
  const double v = number(key, fallback);
  if (has(key) && !(v > 0)) fail(key, "expected a number > 0, got " + exact(v));
  return v;
}

int AdapterOptions::whole(const std::string& key, int fallback, int lo, int hi) const {
  if (!has(key)) return fallback;
  const double v = number(key, fallback, lo, hi);
  if (v != std::floor(v))
    fail(key, "expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                  ", got " + exact(v));
  return static_cast<int>(v);
}

bool AdapterOptions::flag(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const YAML::Node n = root_[key];
  bool v = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v))
    fail(key, "expected true or false, got '" + got(n) + "'");
  return v;
}

std::string AdapterOptions::text(const std::string& key, const std::string& fallback) const {
  if (!has(key)) return fallback;
  const YAML::Node n = root_[key];
  if (!n.IsScalar()) fail(key, "expected a text, got '" + got(n) + "'");
  return n.Scalar();
}

std::string AdapterOptions::requiredText(const std::string& key, const std::string& example) const {
  if (!has(key))
    fail(key, "missing; " + adapter_ + " needs it, e.g. `" + key + ": " + example + "`");
  const std::string v = text(key, "");
  if (v.empty()) fail(key, "is empty; give it, e.g. `" + key + ": " + example + "`");
  return v;
}

std::string AdapterOptions::choice(const std::string& key, const std::string& fallback,
                                   const std::vector<std::string>& allowed) const {
  const std::string v = text(key, fallback);
  for (const auto& a : allowed)
    if (v == a) return v;
  fail(key, "expected one of " + joined(allowed) + ", got '" + v + "'");
}

std::array<double, 3> AdapterOptions::vec3(const std::string& key,
                                           const std::array<double, 3>& fallback) const {
  return has(key) ? vec3At(root_[key], key) : fallback;
}

double AdapterOptions::numberAt(const YAML::Node& n, const std::string& path) const {
  if (!n) fail(path, "missing; expected a number");
  double v = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v) || !std::isfinite(v))
    fail(path, "expected a number, got '" + got(n) + "'");
  return v;
}

std::array<double, 3> AdapterOptions::vec3At(const YAML::Node& n, const std::string& path) const {
  if (!n) fail(path, "missing; expected three numbers [x, y, z]");
  std::array<double, 3> out{};
  bool ok = n.IsSequence() && n.size() == 3;
  for (std::size_t i = 0; ok && i < 3; ++i)
    ok = n[i].IsScalar() && YAML::convert<double>::decode(n[i], out[i]) && std::isfinite(out[i]);
  if (!ok) fail(path, "expected three numbers [x, y, z], got '" + got(n) + "'");
  return out;
}

std::vector<std::string> AdapterOptions::names(const std::string& key,
                                               const std::vector<std::string>& fallback) const {
  if (!has(key)) return fallback;
  const YAML::Node n = root_[key];
  std::vector<std::string> out;
  if (n.IsScalar()) {
    out.push_back(n.Scalar());
  } else if (n.IsSequence()) {
    for (const auto& e : n) {
      if (!e.IsScalar()) fail(key, "expected a name or a list of names, got '" + got(n) + "'");
      out.push_back(e.Scalar());
    }
  } else {
    fail(key, "expected a name or a list of names, got '" + got(n) + "'");
  }
  return out;
}

}  // namespace cosim::util
