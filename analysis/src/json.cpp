#include "cosim/analysis/json.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
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

const Json* Json::find(const std::string& key) const {
  const auto* obj = members();
  if (obj == nullptr) return nullptr;
  for (const auto& [k, v] : *obj) {
    if (k == key) return &v;
  }
  return nullptr;
}

namespace {
class Parser {
 public:
  explicit Parser(const std::string& t) : t_(t) {}
  Json document() {
    Json v = value();
    space();
    if (i_ != t_.size()) fail("end of the text");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& expected) const {
    throw std::runtime_error("JSON: expected " + expected + " at offset " + std::to_string(i_));
  }
  void space() {
    while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\n' || t_[i_] == '\r' || t_[i_] == '\t')) ++i_;
  }
  bool take(char c) {
    space();
    if (i_ < t_.size() && t_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  bool word(const char* w) {
    const std::size_t n = std::char_traits<char>::length(w);
    if (t_.compare(i_, n, w) == 0) {
      i_ += n;
      return true;
    }
    return false;
  }
  std::string text() {
    if (!take('"')) fail("a string");
    std::string out;
    while (i_ < t_.size() && t_[i_] != '"') {
      char c = t_[i_++];
      if (c == '\\') {
        if (i_ >= t_.size()) fail("an escape");
        c = t_[i_++];
        switch (c) {
          case 'n': out += '\n'; break;
          case 't': out += '\t'; break;
          case 'r': out += '\r'; break;
          case 'b': out += '\b'; break;
          case 'f': out += '\f'; break;
          case 'u': {
            if (i_ + 4 > t_.size()) fail("4 hex digits");
            const unsigned code = static_cast<unsigned>(std::stoul(t_.substr(i_, 4), nullptr, 16));
            i_ += 4;
            if (code < 0x80) {
              out += static_cast<char>(code);
            } else if (code < 0x800) {
              out += static_cast<char>(0xC0 | (code >> 6));
              out += static_cast<char>(0x80 | (code & 0x3F));
            } else {
              out += static_cast<char>(0xE0 | (code >> 12));
              out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
              out += static_cast<char>(0x80 | (code & 0x3F));
            }
            break;
          }
          default: out += c;  // " \\ /
        }
      } else {
        out += c;
      }
    }
    if (i_ >= t_.size()) fail("the closing quote of a string");
    ++i_;
    return out;
  }
  Json value() {
    space();
    if (i_ >= t_.size()) fail("a value");
    const char c = t_[i_];
    if (c == '{') {
      ++i_;
      Json o = Json::object();
      if (take('}')) return o;
      do {
        std::string key = text();
        if (!take(':')) fail("':'");
        o[key] = value();
      } while (take(','));
      if (!take('}')) fail("',' or '}'");
      return o;
    }
    if (c == '[') {
      ++i_;
      Json a = Json::array();
      if (take(']')) return a;
      do {
        a.push(value());
      } while (take(','));
      if (!take(']')) fail("',' or ']'");
      return a;
    }
    if (c == '"') return Json(text());
    if (word("true")) return Json(true);
    if (word("false")) return Json(false);
    if (word("null")) return Json();
    char* end = nullptr;
    const double d = std::strtod(t_.c_str() + i_, &end);
    if (end == t_.c_str() + i_) fail("a value");
    i_ = static_cast<std::size_t>(end - t_.c_str());
    return Json(d);
  }

  const std::string& t_;
  std::size_t i_ = 0;
};
}  // namespace

Json Json::parse(const std::string& text) { return Parser(text).document(); }

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
