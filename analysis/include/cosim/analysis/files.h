// Writing the files of a run: atomic replacement, the shortest exact text of a number, and the
// JSON files (summary.json, report.json, study.json, comparison.json) through nlohmann-json.
// `Json` keeps the keys in insertion order, so the files read in the order they are written.
#pragma once

#include <filesystem>
#include <fstream>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace cosim::analysis {

using Json = nlohmann::ordered_json;

// Shortest decimal text ("%.15g" .. "%.17g") that reads back as exactly the same double.
std::string formatShortest(double v);

// Write text to path atomically (write path.tmp, then rename), so a reader never sees half a
// file. Throws std::runtime_error naming the path and the reason (e.g. the disk is full) on
// failure, having removed path.tmp: a failed write leaves the old file as it was and nothing else.
void writeFileAtomically(const std::filesystem::path& path, const std::string& text);

// Writes text over path in place (truncating it first, which frees its space). For when there
// is no room for the second copy an atomic write needs (disk full): the file is briefly
// incomplete. Throws std::runtime_error naming the path and the reason on failure.
void overwriteFile(const std::filesystem::path& path, const std::string& text);

// The text of json, indented by indent spaces, then a newline. Non-finite numbers become null;
// bytes that are not UTF-8 are replaced.
std::string jsonText(const Json& json, int indent);

// Writes json (indented by indent spaces, then a newline) atomically. Non-finite numbers become
// null; bytes that are not UTF-8 (e.g. in a participant's log tail) are replaced, not an error.
void writeJsonFile(const std::filesystem::path& path, const Json& json, int indent);

// Opens a text file a user named (a measured CSV, a profile) for reading. Throws
// std::runtime_error naming the path when it is a folder, missing or unreadable; `expected`
// completes the message with what file was expected there.
std::ifstream openUserFile(const std::filesystem::path& path, const std::string& expected);

// A cell of a user's file as an error message quotes it: in single quotes, at most 40
// characters (then "..."), bytes outside printable ASCII as \xNN, so a binary file given by
// mistake cannot scramble the terminal.
std::string quotedCell(std::string_view text);

// Before a command writes its files where a user's option points (-o): refuses to replace a
// file the command did not write. `files` are the files it writes there, the first the one it
// always writes; `signature` is text that file's first 4 KiB hold when this command wrote it
// (its CSV header, a JSON key only it writes). Passes when that first file exists and holds the
// signature (the command's own earlier output, replaced as a whole) or when none of `files`
// exists; else throws std::runtime_error naming `option`, the first existing file and what to do.
// Nothing is written or removed.
void claimOutputFiles(const std::vector<std::filesystem::path>& files, std::string_view signature,
                      const std::string& option);

// A CSV a command writes at `file` (-o) with its plot beside it: FILE.png and the plotter's log
// FILE.plot.log. Refuses a name whose plot would be the CSV itself (FILE.png), then claims the
// three with the CSV's header line as signature (claimOutputFiles).
struct CsvWithPlot {
  std::filesystem::path csv, png, log;
};
CsvWithPlot claimCsvWithPlot(const std::filesystem::path& file, std::string_view csv_text,
                             const std::string& option);

// The same for a folder whose files the command replaces as a group (a report removes the old
// figures of its folder): passes when `folder` does not exist or is empty, or when it holds
// `marker` with `signature` in its first 4 KiB (the command's own earlier output).
void claimOutputFolder(const std::filesystem::path& folder, const std::string& marker,
                       std::string_view signature, const std::string& option);

// Parses a JSON file. Throws std::runtime_error naming the path when it cannot be read or parsed.
Json readJsonFile(const std::filesystem::path& path);

}  // namespace cosim::analysis
