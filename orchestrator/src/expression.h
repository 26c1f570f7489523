// ${expr} templating: arithmetic on scenario parameters, used in the scenario file itself and in
// every text file of a participant's case folder (OpenFOAM dictionaries, LIGGGHTS scripts).
#pragma once

#include <map>
#include <stdexcept>
#include <string>

namespace cosim::orchestrator {

class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Variables = std::map<std::string, double>;

// How deep an expression may nest (parentheses, unary signs, ^, function calls), counted in the
// parser's levels: far more than any real expression needs, far less than overflows the stack.
inline constexpr int kMaxExpressionDepth = 200;

// Evaluates + - * / ^ ( ), unary minus, numbers (1e-3), variables, constants pi and e, and the
// functions sqrt, exp, log, sin, cos, tan, abs, min, max, pow, round, ceil, floor. Throws
// ExpressionError, also for an expression nested deeper than kMaxExpressionDepth.
double evaluate(const std::string& expr, const Variables& vars);

// Formats a number so that OpenFOAM and LIGGGHTS read back the same double.
std::string formatNumber(double v);

// Replaces every ${expr} in text with its value. Throws ExpressionError naming the expression.
std::string substitute(const std::string& text, const Variables& vars);

// True if text is exactly one ${expr} (possibly surrounded by spaces).
bool isSingleExpression(const std::string& text);

}  // namespace cosim::orchestrator
