// cosim keys [FILE]
#include <iostream>
#include <memory>

#include "../keys_command.h"
#include "commands.h"

namespace cosim::orchestrator {

void addKeysCommand(CLI::App& app, Commands& commands) {
  auto file = std::make_shared<std::string>();
  auto* keys = app.add_subcommand(
      "keys",
      "Create the orchestrator's CurveZMQ key file for tcp:// runs if it does not exist (mode "
      "0600), and show a key file's public keys (never a secret one)");
  keys->add_option("file", *file,
                   "key file (default: $XDG_CONFIG_HOME/cosim/orchestrator.key, else "
                   "~/.config/cosim/orchestrator.key); a participant's RUN/.cosim-NAME.key is "
                   "shown");
  commands.push_back({keys, [file] { return keysCommand(*file, std::cout); }});
}

}  // namespace cosim::orchestrator
