// Validators of command-line numbers that say in words what was expected (CLI11's
// NonNegativeNumber prints the largest double as its bound, and an unsigned option takes "-3" as
// 18446744073709551613). Each names the unit; CLI11 puts the option's name before the message.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

namespace cosim::orchestrator::cli {

// A finite number of `unit` (e.g. "seconds", "metres") of at least `min`.
CLI::Validator atLeast(double min, const std::string& unit);
// A finite number of `unit` above `min` (and at most `max` when given).
CLI::Validator above(double min, const std::string& unit, std::optional<double> max = {});
// A whole number from `min` to `max`, written without a sign or a fraction.
CLI::Validator wholeNumber(std::uint64_t min, std::uint64_t max);

}  // namespace cosim::orchestrator::cli
