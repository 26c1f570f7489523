#include "cosim/analysis/files.h"

#include <fmt/format.h>
#include <signal.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "cosim/util/errors.h"

namespace cosim::analysis {

std::string formatShortest(double v) { return fmt::format("{}", v); }

namespace {

// Why writing `path` failed, from errno, with what to do when the disk is full.
std::string writeFailure(const std::filesystem::path& path, int err) {
  std::string why = "cannot write " + path.string() + ": " + std::strerror(err);
  if (err == ENOSPC || err == EDQUOT) why += " (the disk is full: free space and run again)";
  if (err == EFBIG) why += " (larger than the file size limit, ulimit -f)";
  return why;
}

// Writes all of text to path (created or truncated); false with errno set on failure.
bool writeWhole(const std::filesystem::path& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return false;
  const bool written =
      std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
  const int err = errno;
  const bool closed = std::fclose(f) == 0;
  if (!written) errno = err;
  return written && closed;
}

}  // namespace

namespace {
// Ctrl-C (SIGINT) and SIGTERM held back while a file is written and renamed into place, and
// delivered at once after: a command stopped by them (e.g. `cosim report` in its default
// disposition) leaves each file whole or as it was, and no `.tmp` beside it.
class StopSignalsHeld {
 public:
  StopSignalsHeld() {
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    held_ = pthread_sigmask(SIG_BLOCK, &stop, &before_) == 0;
  }
  ~StopSignalsHeld() {
    if (held_) pthread_sigmask(SIG_SETMASK, &before_, nullptr);
  }
  StopSignalsHeld(const StopSignalsHeld&) = delete;
  StopSignalsHeld& operator=(const StopSignalsHeld&) = delete;

 private:
  sigset_t before_{};
  bool held_ = false;
};
}  // namespace

void writeFileAtomically(const std::filesystem::path& path, const std::string& text) {
  const StopSignalsHeld held;
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  if (!writeWhole(tmp, text)) {
    const int err = errno;
    std::error_code ec;
    std::filesystem::remove(tmp, ec);  // never leave half a file behind
    throw Error(kindOfErrno(err), writeFailure(tmp, err));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw Error(kindOfErrno(ec.value()),
                "cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message());
  }
}

void overwriteFile(const std::filesystem::path& path, const std::string& text) {
  if (!writeWhole(path, text)) {
    const int err = errno;
    throw Error(kindOfErrno(err), writeFailure(path, err));
  }
}

std::string jsonText(const Json& json, int indent) {
  return json.dump(indent, ' ', false, Json::error_handler_t::replace) + "\n";
}

void writeJsonFile(const std::filesystem::path& path, const Json& json, int indent) {
  writeFileAtomically(path, jsonText(json, indent));
}

std::ifstream openUserFile(const std::filesystem::path& path, const std::string& expected) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path.string() + ": is a folder; expected " + expected);
  if (!std::filesystem::exists(path, ec))
    throw InputError(path.string() + ": no such file; expected " + expected);
  std::ifstream in(path);
  if (!in) {
    const int err = errno;
    throw Error(kindOfErrno(err), fmt::format("{}: cannot be read ({}); expected {}", path.string(),
                                              std::strerror(err), expected));
  }
  return in;
}

std::string quotedCell(std::string_view text) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f)
      out += static_cast<char>(c);
    else
      out += fmt::format("\\x{:02x}", c);
  }
  out += text.size() > kMax ? "'..." : "'";
  return out;
}

namespace {

// Whether `path` is a file whose first 4 KiB hold `signature`.
bool holdsSignature(const std::filesystem::path& path, std::string_view signature) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find(signature) != std::string::npos;
}

}  // namespace

void claimOutputFiles(const std::vector<std::filesystem::path>& files, std::string_view signature,
                      const std::string& option) {
  if (files.empty() || holdsSignature(files.front(), signature)) return;
  for (const auto& f : files) {
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::symlink_status(f, ec))) continue;
    const std::string why = f == files.front() ? "is not an earlier output of this command"
                                               : "is not this command's to replace (no " +
                                                     files.front().filename().string() +
                                                     " of an earlier run of it beside it)";
    throw InputError(fmt::format(
        "{}: {} already exists and {}; it is left as it is: give {} another name or folder", option,
        f.string(), why, option));
  }
}

CsvWithPlot claimCsvWithPlot(const std::filesystem::path& file, std::string_view csv_text,
                             const std::string& option) {
  CsvWithPlot out{file, file, file};
  out.png.replace_extension(".png");
  out.log.replace_extension(".plot.log");
  if (out.png == file || out.log == file)
    throw InputError(option + " " + file.string() +
                     ": the CSV's plot takes its name ending .png: give a name ending .csv");
  claimOutputFiles({out.csv, out.png, out.log}, csv_text.substr(0, csv_text.find('\n') + 1),
                   option);
  return out;
}

void claimOutputFolder(const std::filesystem::path& folder, const std::string& marker,
                       std::string_view signature, const std::string& option) {
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(folder, ec))) return;
  if (!std::filesystem::is_directory(folder, ec))
    throw InputError(option + ": " + folder.string() + " exists and is not a folder");
  if (std::filesystem::is_empty(folder, ec) || holdsSignature(folder / marker, signature)) return;
  throw InputError(fmt::format(
      "{}: {} holds other files and no {} of this command's earlier output; nothing in it was "
      "touched: give {} a new or empty folder",
      option, folder.string(), marker, option));
}

Json readJsonFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read " + path.string());
  std::stringstream text;
  text << in.rdbuf();
  try {
    return Json::parse(text.str());
  } catch (const Json::exception& e) {
    throw InputError(path.string() + " is not valid JSON (" + e.what() + ")");
  }
}

}  // namespace cosim::analysis
