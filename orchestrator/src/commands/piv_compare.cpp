// cosim piv-compare SIMULATED MEASURED [--core x0,x1] [--labels A,B] [-o CSV]
#include <iostream>
#include <memory>

#include "commands.h"
#include "cosim/analysis/piv_command.h"

namespace cosim::orchestrator {

void addPivCompareCommand(CLI::App& app, Commands& commands) {
  struct Options {
    cosim::analysis::PivCompareCommandOptions compare;
    std::vector<double> core;
    std::vector<std::string> labels;
  };
  auto o = std::make_shared<Options>();
  auto& c = o->compare;
  auto* pivc = app.add_subcommand(
      "piv-compare",
      "Mean absolute error of simulated PIV profiles against measured ones, per profile and per "
      "region (upward core, downward sides); the CSV format is in docs/calibration-validation.md");
  pivc->add_option("simulated", c.simulated,
                   "run folder (its piv/profiles.csv, from cosim piv) or a profile CSV")
      ->required();
  pivc->add_option("measured", c.measured, "measured profiles (CSV: height_m,x_m,vz_m_s)")
      ->required();
  pivc->add_option("--core", o->core,
                   "x0,x1 [m]: the core is x0 <= x <= x1 (default: where the measured vz > 0)")
      ->delimiter(',')
      ->expected(2);
  pivc->add_option("-o,--output", c.output,
                   "comparison CSV (default: comparison.csv beside the simulated profiles); "
                   "its plot has the same name ending .png");
  pivc->add_flag("--no-plots{false}", c.plots, "the CSV only, no PNG");
  pivc->add_option("--labels", o->labels,
                   "A,B: the two profiles' names in the plot's legend (default "
                   "simulated,measured; e.g. 'cg 5,cg 10' when a run is compared with another)")
      ->delimiter(',')
      ->expected(2);
  commands.push_back({pivc, [o] {
                        auto& cmp = o->compare;
                        if (!o->core.empty()) {
                          if (!(o->core[0] < o->core[1])) {
                            std::cerr << "cosim piv-compare: --core " << o->core[0] << ","
                                      << o->core[1] << ": expected x0,x1 with x0 < x1 [m]\n";
                            return 2;
                          }
                          cmp.core_band = std::make_pair(o->core[0], o->core[1]);
                        }
                        if (!o->labels.empty()) {
                          cmp.simulated_label = o->labels[0];
                          cmp.measured_label = o->labels[1];
                        }
                        return cosim::analysis::runPivCompareCommand(cmp, std::cout);
                      }});
}

}  // namespace cosim::orchestrator
