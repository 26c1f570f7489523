// The subcommands of `cosim`, one file each in this folder: each adds its CLI11 subcommand with
// its options and validators and says how to run it. main.cpp only collects them.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "cosim/util/stop_request.h"

namespace cosim::orchestrator {

struct Command {
  CLI::App* app;             // the subcommand
  std::function<int()> run;  // called when it was given; returns the exit code
};
using Commands = std::vector<Command>;

// Help text shared by the commands that take a scene
extern const char* const kSetHelp;
extern const char* const kUnsetHelp;

// Ctrl-C and SIGTERM request processStop(): a run handed it (RunOptions::stop) stops after its
// step with a checkpoint (a second one at once); `pipe`: a closed pipe is an error to handle,
// not a signal that ends the process.
void catchStopSignals(bool ignore_pipe = true);
util::StopRequest& processStop();
// Ctrl-C and SIGTERM end a command at once, whatever its parent left them set to (a script's
// background job inherits Ctrl-C ignored): every command but those that catch them as above.
// Each file it writes is whole or as it was (analysis::writeFileAtomically holds them back
// while it writes).
void stopAtOnceOnSignals();

struct RunResult;
// The end of cosim run and cosim resume: a stopped run's reason on stderr, or each observable
// and the run folder on stdout (with -q too: it is the answer, not progress); the exit code.
int reportRunEnd(const RunResult& r);

// "a, b, c", or "(none)"
std::string joinNames(const std::vector<std::string>& names);

void addRunCommand(CLI::App& app, Commands& commands);
void addResumeCommand(CLI::App& app, Commands& commands);
void addPackCommand(CLI::App& app, Commands& commands);
void addValidateCommand(CLI::App& app, Commands& commands);
void addStudyCommand(CLI::App& app, Commands& commands);
void addBenchCommand(CLI::App& app, Commands& commands);
void addModelsCommand(CLI::App& app, Commands& commands);
void addKeysCommand(CLI::App& app, Commands& commands);
void addReferenceCommand(CLI::App& app, Commands& commands);
void addFt4Commands(CLI::App& app, Commands& commands);
void addBatchCommandLine(CLI::App& app, Commands& commands);
void addReportCommand(CLI::App& app, Commands& commands);
void addPivCommand(CLI::App& app, Commands& commands);
void addPivCompareCommand(CLI::App& app, Commands& commands);

}  // namespace cosim::orchestrator
