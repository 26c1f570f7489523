// Reading text files for messages: the tail of a participant's or a tool's log.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace cosim::util {

// The last `lines` lines of a text file, oldest first; nullopt if it cannot be opened.
std::optional<std::vector<std::string>> lastLines(const std::filesystem::path& file,
                                                  std::size_t lines);

// The last `lines` lines, each followed by '\n' (empty if the file is missing or empty).
std::string tailOfFile(const std::filesystem::path& file, std::size_t lines);

}  // namespace cosim::util
