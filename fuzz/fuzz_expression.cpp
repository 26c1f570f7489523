// Fuzzes the ${expression} evaluator and the templating of text: any input must give a value or
// an ExpressionError, never a crash, undefined behaviour or another exception.
#include <cstddef>
#include <cstdint>
#include <string>

#include "expression.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const cosim::orchestrator::Variables vars{{"d", 1e-4}, {"flow_lpm", 50.0}, {"n", 3.0}};
  try {
    (void)cosim::orchestrator::evaluate(text, vars);
  } catch (const cosim::orchestrator::ExpressionError&) {
  }
  try {
    (void)cosim::orchestrator::substitute(text, vars);
  } catch (const cosim::orchestrator::ExpressionError&) {
  }
  return 0;
}
