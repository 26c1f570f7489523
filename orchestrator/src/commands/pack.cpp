// cosim pack RUN DEST
#include <iostream>
#include <memory>

#include "commands.h"
#include "run_pack.h"
#include "scenario.h"
#include "stability.h"

namespace cosim::orchestrator {

void addPackCommand(CLI::App& app, Commands& commands) {
  struct Options {
    std::string run, dest;
  };
  auto o = std::make_shared<Options>();
  auto* pack = app.add_subcommand(
      "pack",
      "Copy a stopped run to DEST so that it continues there (another machine or disk): the "
      "scene, the records and the newest checkpoint; logs, older checkpoints, the fluid's time "
      "folders and the particles' dumps left out. Then: cosim resume DEST");
  pack->add_option("run", o->run, "run folder (stopped: Ctrl-C writes a checkpoint)")->required();
  pack->add_option("dest", o->dest, "new folder for the copy (must not exist)")->required();
  commands.push_back({pack, [o] {
                        PackResult p;
                        try {
                          p = packRun(o->run, o->dest, loadRunScene(o->run));
                        } catch (const std::exception& e) {
                          std::cerr << "cosim pack: " << e.what() << "\n";
                          return 1;
                        }
                        std::cout << "cosim: packed " << o->run << " into " << o->dest << ": "
                                  << byteText(p.copied_bytes) << " in " << p.copied_files
                                  << " files, continuing from the checkpoint at t = "
                                  << p.checkpoint.filename().string() << " s\n";
                        for (const auto& [kind, bytes] : p.left_out)
                          std::cout << "  left out " << kind << ": " << byteText(bytes) << "\n";
                        std::cout << "  continue it with: cosim resume " << o->dest
                                  << " (the same cosim and solvers; add --set "
                                     "coupling.end_time=T to go further)\n";
                        return 0;
                      }});
}

}  // namespace cosim::orchestrator
