// The run's log: everything goes to cosim.log in the run folder (time-stamped, flushed line by
// line, so a crash loses nothing); what the user should see while the run goes also goes to the
// console as "cosim: ...", unless the run is quiet. Warnings reach the console even then.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

namespace spdlog {
class logger;
}

namespace cosim::orchestrator {

class RunLog {
 public:
  explicit RunLog(bool quiet);
  ~RunLog();
  RunLog(const RunLog&) = delete;
  RunLog& operator=(const RunLog&) = delete;

  // Opens (appends to) the log file; lines written before are not kept in it.
  void open(const std::filesystem::path& file);
  bool quiet() const { return quiet_; }

  void file(const std::string& line);     // cosim.log only
  void console(const std::string& line);  // console only
  void show(const std::string& line);     // console and cosim.log
  void warn(const std::string& line);     // "cosim: warning: ..." on stderr, and cosim.log

 private:
  bool quiet_;
  std::shared_ptr<spdlog::logger> file_, out_, err_;
};

}  // namespace cosim::orchestrator
