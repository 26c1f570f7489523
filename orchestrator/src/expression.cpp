#include "expression.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

namespace cosim::orchestrator {

namespace {

class Parser {
 public:
  Parser(const std::string& s, const Variables& v) : s_(s), vars_(v) {}

  double parse() {
    double v = sum();
    skip();
    if (pos_ != s_.size()) fail("unexpected '" + s_.substr(pos_, 1) + "'");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    // A long expression is shown by its start: the message stays readable.
    const std::string shown = s_.size() > 80 ? s_.substr(0, 80) + "..." : s_;
    throw ExpressionError("in expression '" + shown + "': " + why);
  }
  // Every recursion (parentheses, signs, ^, function arguments) goes one level down; a
  // pathological expression is refused instead of overflowing the stack.
  struct Level {
    explicit Level(Parser& p) : p_(p) {
      if (++p_.depth_ > kMaxExpressionDepth) {
        p_.fail("nested more than " + std::to_string(kMaxExpressionDepth) +
                " levels deep (parentheses, signs, ^ or function calls); write it in simpler "
                "steps, e.g. as several parameters");
      }
    }
    ~Level() { --p_.depth_; }
    Level(const Level&) = delete;
    Level& operator=(const Level&) = delete;
    Parser& p_;
  };
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool eat(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  double sum() {
    Level level(*this);
    double v = product();
    while (true) {
      if (eat('+'))
        v += product();
      else if (eat('-'))
        v -= product();
      else
        return v;
    }
  }
  double product() {
    double v = unary();
    while (true) {
      if (eat('*')) {
        v *= unary();
      } else if (eat('/')) {
        double d = unary();
        if (d == 0.0) fail("division by zero");
        v /= d;
      } else {
        return v;
      }
    }
  }
  // Unary minus binds looser than ^ (-a^2 = -(a^2)); ^ is right associative.
  double unary() {
    Level level(*this);
    if (eat('-')) return -unary();
    if (eat('+')) return unary();
    return power();
  }
  double power() {
    double b = primary();
    if (eat('^')) return std::pow(b, unary());
    return b;
  }
  double primary() {
    skip();
    if (eat('(')) {
      double v = sum();
      if (!eat(')')) fail("missing ')'");
      return v;
    }
    if (pos_ < s_.size() &&
        (std::isdigit(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '.')) {
      const char* start = s_.c_str() + pos_;
      char* end = nullptr;
      double v = std::strtod(start, &end);
      pos_ += static_cast<std::size_t>(end - start);
      return v;
    }
    if (pos_ < s_.size() &&
        (std::isalpha(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) {
      std::size_t b = pos_;
      while (pos_ < s_.size() &&
             (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) {
        ++pos_;
      }
      const std::string name = s_.substr(b, pos_ - b);
      if (eat('(')) return call(name);
      auto it = vars_.find(name);
      if (it != vars_.end()) return it->second;
      if (name == "pi") return std::numbers::pi;
      if (name == "e") return std::numbers::e;
      std::string known;
      for (const auto& [k, x] : vars_) known += (known.empty() ? "" : ", ") + k;
      fail("unknown parameter '" + name + "' (parameters: " + (known.empty() ? "none" : known) +
           ")");
    }
    fail(pos_ < s_.size() ? "unexpected '" + s_.substr(pos_, 1) + "'" : "unexpected end");
  }
  double call(const std::string& f) {
    std::vector<double> args;
    if (!eat(')')) {
      do {
        args.push_back(sum());
      } while (eat(','));
      if (!eat(')')) fail("missing ')' after arguments of " + f);
    }
    auto need = [&](std::size_t n) {
      if (args.size() != n) fail(f + " takes " + std::to_string(n) + " argument(s)");
    };
    if (f == "sqrt") {
      need(1);
      if (args[0] < 0) fail("sqrt of a negative number");
      return std::sqrt(args[0]);
    }
    if (f == "exp") {
      need(1);
      return std::exp(args[0]);
    }
    if (f == "log") {
      need(1);
      if (args[0] <= 0) fail("log of a non-positive number");
      return std::log(args[0]);
    }
    if (f == "sin") {
      need(1);
      return std::sin(args[0]);
    }
    if (f == "cos") {
      need(1);
      return std::cos(args[0]);
    }
    if (f == "tan") {
      need(1);
      return std::tan(args[0]);
    }
    if (f == "abs") {
      need(1);
      return std::fabs(args[0]);
    }
    if (f == "min") {
      need(2);
      return std::min(args[0], args[1]);
    }
    if (f == "max") {
      need(2);
      return std::max(args[0], args[1]);
    }
    if (f == "pow") {
      need(2);
      return std::pow(args[0], args[1]);
    }
    if (f == "round") {
      need(1);
      return std::round(args[0]);
    }
    if (f == "ceil") {
      need(1);
      return std::ceil(args[0]);
    }
    if (f == "floor") {
      need(1);
      return std::floor(args[0]);
    }
    fail("unknown function '" + f + "'");
  }

  const std::string& s_;
  const Variables& vars_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace

double evaluate(const std::string& expr, const Variables& vars) {
  double v = Parser(expr, vars).parse();
  if (!std::isfinite(v)) throw ExpressionError("expression '" + expr + "' is not finite");
  return v;
}

std::string formatNumber(double v) { return fmt::format("{}", v); }  // shortest exact form

std::string substitute(const std::string& text, const Variables& vars) {
  std::string out;
  out.reserve(text.size());
  std::size_t pos = 0;
  while (true) {
    std::size_t b = text.find("${", pos);
    if (b == std::string::npos) {
      out.append(text, pos, std::string::npos);
      return out;
    }
    std::size_t e = text.find('}', b + 2);
    if (e == std::string::npos) {
      throw ExpressionError("unclosed '${' in '" + text.substr(b, 40) + "'");
    }
    if (b > 0 && text[b - 1] == '$') {
      // $${...} is the escape for a literal ${...} (e.g. a shell or LIGGGHTS variable in a case
      // file)
      out.append(text, pos, b - 1 - pos);
      out.append(text, b, e + 1 - b);
      pos = e + 1;
      continue;
    }
    out.append(text, pos, b - pos);
    out += formatNumber(evaluate(text.substr(b + 2, e - b - 2), vars));
    pos = e + 1;
  }
}

bool isSingleExpression(const std::string& text) {
  std::size_t b = text.find_first_not_of(" \t");
  std::size_t e = text.find_last_not_of(" \t");
  if (b == std::string::npos) return false;
  return text.compare(b, 2, "${") == 0 && text[e] == '}' &&
         text.find("${", b + 2) == std::string::npos;
}

}  // namespace cosim::orchestrator
