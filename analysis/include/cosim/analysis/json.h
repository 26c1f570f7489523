// A tiny JSON value (null, bool, number, string, array, object with insertion order) and its
// writer, enough for summary.json and report.json. Non-finite numbers are written as null.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace cosim::analysis {

class Json {
 public:
  using Array = std::vector<Json>;
  using Object = std::vector<std::pair<std::string, Json>>;

  Json() = default;  // null
  Json(std::nullptr_t) {}
  Json(bool b) : v_(b) {}
  Json(double d) : v_(d) {}
  Json(int i) : v_(static_cast<double>(i)) {}
  Json(long i) : v_(static_cast<double>(i)) {}
  Json(long long i) : v_(static_cast<double>(i)) {}
  Json(unsigned long i) : v_(static_cast<double>(i)) {}
  Json(unsigned long long i) : v_(static_cast<double>(i)) {}
  Json(const char* s) : v_(std::string(s)) {}
  Json(std::string s) : v_(std::move(s)) {}
  Json(Array a) : v_(std::move(a)) {}
  Json(const std::vector<double>& xs);

  static Json object() { Json j; j.v_ = Object{}; return j; }
  static Json array() { Json j; j.v_ = Array{}; return j; }

  // Object access: adds the key (null) if absent. Turns a null value into an object.
  Json& operator[](const std::string& key);
  // Array append. Turns a null value into an array.
  void push(Json value);

  bool isNull() const { return std::holds_alternative<std::monostate>(v_); }
  const double* number() const { return std::get_if<double>(&v_); }
  const std::string* string() const { return std::get_if<std::string>(&v_); }
  const Object* members() const { return std::get_if<Object>(&v_); }
  const Array* elements() const { return std::get_if<Array>(&v_); }
  // Member of an object, nullptr if absent or not an object.
  const Json* find(const std::string& key) const;

  // Parses JSON text; throws std::runtime_error with the offset and what was expected.
  static Json parse(const std::string& text);
  // Serialised text; indent < 0 writes one line.
  std::string dump(int indent = 2) const;

 private:
  void dumpTo(std::string& out, int indent, int depth) const;
  std::variant<std::monostate, bool, double, std::string, Array, Object> v_;
};

// Shortest decimal text ("%.15g" .. "%.17g") that reads back as exactly the same double.
std::string formatShortest(double v);

// Escape a string for JSON (quotes included).
std::string jsonQuote(const std::string& s);

// Write text to path atomically (write path.tmp, then rename), so a reader never sees half a
// file. Throws std::runtime_error naming the path on failure.
void writeFileAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace cosim::analysis
