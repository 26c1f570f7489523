#include "cli_checks.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace cosim::orchestrator::cli {

namespace {

// The number `in` holds, whole and finite; nothing when it holds anything else.
bool parseNumber(const std::string& in, double& value) {
  if (in.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(in.c_str(), &end);
  return end == in.c_str() + in.size() && errno != ERANGE && std::isfinite(value);
}

std::string quantity(const std::string& unit) {
  return unit.empty() ? "a number" : "a number of " + unit;
}

}  // namespace

CLI::Validator atLeast(double min, const std::string& unit) {
  return {[min, unit](std::string& in) -> std::string {
            double v = 0;
            if (!parseNumber(in, v) || v < min)
              return fmt::format("expected {} of at least {}, got '{}'", quantity(unit), min, in);
            return {};
          },
          fmt::format("NUMBER>={}", min)};
}

CLI::Validator above(double min, const std::string& unit, std::optional<double> max) {
  return {[min, max, unit](std::string& in) -> std::string {
            double v = 0;
            if (parseNumber(in, v) && v > min && (!max || v <= *max)) return {};
            if (max)
              return fmt::format("expected {} above {} and at most {}, got '{}'", quantity(unit),
                                 min, *max, in);
            return fmt::format("expected {} above {}, got '{}'", quantity(unit), min, in);
          },
          fmt::format("NUMBER>{}", min)};
}

CLI::Validator wholeNumber(std::uint64_t min, std::uint64_t max) {
  return {[min, max](std::string& in) -> std::string {
            const bool digits = !in.empty() && in.size() <= 19 &&
                                in.find_first_not_of("0123456789") == std::string::npos;
            const std::uint64_t v = digits ? std::strtoull(in.c_str(), nullptr, 10) : 0;
            if (!digits || v < min || v > max)
              return fmt::format("expected a whole number from {} to {}, got '{}'", min, max, in);
            return {};
          },
          fmt::format("INT in [{} - {}]", min, max)};
}

}  // namespace cosim::orchestrator::cli
