#include "cosim/analysis/json.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace cosim::analysis {

Json::Json(const std::vector<double>& xs) {
  Array a;
  a.reserve(xs.size());
  for (double x : xs) a.emplace_back(x);
  v_ = std::move(a);
}

Json& Json::operator[](const std::string& key) {
  if (isNull()) v_ = Object{};
  auto* obj = std::get_if<Object>(&v_);
  if (obj == nullptr) throw std::logic_error("Json: '" + key + "' looked up in a non-object");
  for (auto& [k, v] : *obj) {
    if (k == key) return v;
  }
  obj->emplace_back(key, Json{});
  return obj->back().second;
}

void Json::push(Json value) {
  if (isNull()) v_ = Array{};
  auto* arr = std::get_if<Array>(&v_);
  if (arr == nullptr) throw std::logic_error("Json: push on a non-array");
  arr->push_back(std::move(value));
}

std::string formatShortest(double v) {
  char buf[32];
  for (int precision = 15; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string jsonQuote(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  out += '"';
  return out;
}

namespace {
void newline(std::string& out, int indent, int depth) {
  if (indent < 0) return;
  out += '\n';
  out.append(static_cast<std::size_t>(indent * depth), ' ');
}
}  // namespace

void Json::dumpTo(std::string& out, int indent, int depth) const {
  if (std::holds_alternative<std::monostate>(v_)) {
    out += "null";
  } else if (const auto* b = std::get_if<bool>(&v_)) {
    out += *b ? "true" : "false";
  } else if (const auto* d = std::get_if<double>(&v_)) {
    if (!std::isfinite(*d)) {
      out += "null";
    } else {
      out += formatShortest(*d);
    }
  } else if (const auto* s = std::get_if<std::string>(&v_)) {
    out += jsonQuote(*s);
  } else if (const auto* a = std::get_if<Array>(&v_)) {
    if (a->empty()) {
      out += "[]";
      return;
    }
    // Arrays of plain numbers stay on one line (long series stay readable).
    bool flat = true;
    for (const auto& x : *a) flat = flat && (std::holds_alternative<double>(x.v_) || x.isNull());
    out += '[';
    for (std::size_t i = 0; i < a->size(); ++i) {
      if (i) out += flat ? ", " : ",";
      if (!flat) newline(out, indent, depth + 1);
      (*a)[i].dumpTo(out, indent, depth + 1);
    }
    if (!flat) newline(out, indent, depth);
    out += ']';
  } else if (const auto* o = std::get_if<Object>(&v_)) {
    if (o->empty()) {
      out += "{}";
      return;
    }
    out += '{';
    for (std::size_t i = 0; i < o->size(); ++i) {
      if (i) out += ',';
      newline(out, indent, depth + 1);
      out += jsonQuote((*o)[i].first);
      out += indent < 0 ? ":" : ": ";
      (*o)[i].second.dumpTo(out, indent, depth + 1);
    }
    newline(out, indent, depth);
    out += '}';
  }
}

std::string Json::dump(int indent) const {
  std::string out;
  dumpTo(out, indent, 0);
  return out;
}

void writeFileAtomically(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("cannot write " + tmp.string() + ": check the folder exists and is writable");
    f << text;
    f.flush();
    if (!f) throw std::runtime_error("writing " + tmp.string() + " failed (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message());
}

}  // namespace cosim::analysis
