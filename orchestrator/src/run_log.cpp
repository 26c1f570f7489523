#include "run_log.h"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

namespace cosim::orchestrator {

RunLog::RunLog(bool quiet) : quiet_(quiet) {
  // Loggers of their own (not in spdlog's registry): several runs may share one process.
  out_ = std::make_shared<spdlog::logger>("cosim-console",
                                          std::make_shared<spdlog::sinks::stdout_sink_st>());
  out_->set_pattern("cosim: %v");
  err_ = std::make_shared<spdlog::logger>("cosim-errors",
                                          std::make_shared<spdlog::sinks::stderr_sink_st>());
  err_->set_pattern("cosim: warning: %v");
}

RunLog::~RunLog() = default;

void RunLog::open(const std::filesystem::path& file) {
  file_ = std::make_shared<spdlog::logger>(
      "cosim-file", std::make_shared<spdlog::sinks::basic_file_sink_st>(file.string()));
  file_->set_pattern("[%Y-%m-%d %H:%M:%S.%e] %v");
  file_->flush_on(spdlog::level::trace);
}

void RunLog::file(const std::string& line) {
  if (file_) file_->info(line);
}

void RunLog::console(const std::string& line) {
  if (!quiet_) {
    out_->info(line);
    out_->flush();
  }
}

void RunLog::show(const std::string& line) {
  console(line);
  file(line);
}

void RunLog::warn(const std::string& line) {
  err_->warn(line);
  err_->flush();
  file("warning: " + line);
}

}  // namespace cosim::orchestrator
