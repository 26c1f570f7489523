// cosim piv RUN [options]: the particle velocity a PIV camera sees through the front wall
#include <iostream>
#include <memory>

#include "../cli_checks.h"
#include "commands.h"
#include "cosim/analysis/piv_command.h"

namespace cosim::orchestrator {

void addPivCommand(CLI::App& app, Commands& commands) {
  auto o = std::make_shared<cosim::analysis::PivCommandOptions>();
  auto* piv = app.add_subcommand(
      "piv",
      "The particle velocity a PIV camera sees through the front wall: the time-averaged "
      "vertical velocity of the parcels next to it on a grid, and its profiles across the width "
      "(RUN/piv/grid.csv, profiles.csv); docs/calibration-validation.md section 2");
  piv->add_option("run", o->run, "run folder")->required();
  piv->add_option("--from", o->from,
                  "snapshots at t >= this count [s] (default: the scene parameter piv_discard, "
                  "else 0)");
  piv->add_option("--to", o->to, "snapshots at t <= this count [s] (default: the end)");
  piv->add_option("--depth", o->depth,
                  "a parcel is seen when its centre lies within this distance of the front wall "
                  "[m] (default: within its own diameter)")
      ->check(cli::above(0.0, "metres"));
  piv->add_option("--cell", o->cell, "grid cell and profile band [m] (default 0.004)")
      ->check(cli::above(0.0, "metres"));
  piv->add_option("--blocks", o->blocks,
                  "blocks of consecutive snapshots for the profiles' standard errors (batch "
                  "means; default 10)")
      ->check(cli::wholeNumber(2, 100000));
  piv->add_option("--heights", o->heights,
                  "profile heights above the bottom [m] (default 0.13,0.15)")
      ->delimiter(',');
  piv->add_option("--wall-y", o->wall_y,
                  "the front wall's plane y [m] (default: scene parameter piv_front_wall_y)");
  piv->add_option("--x-min", o->x_min, "grid's left edge [m] (default: piv_x_min)");
  piv->add_option("--x-max", o->x_max, "grid's right edge [m] (default: piv_x_max)");
  piv->add_option("--z-min", o->z_min, "grid's bottom [m] (default 0)");
  piv->add_option("--z-max", o->z_max, "grid's top [m] (default: piv_z_max)");
  piv->add_option("-o,--output", o->output,
                  "folder of the CSV files and piv.png (default RUN/piv)");
  piv->add_flag("--no-plots{false}", o->plots, "the CSV files only, no piv.png");
  commands.push_back({piv, [o] { return cosim::analysis::runPivCommand(*o, std::cout); }});
}

}  // namespace cosim::orchestrator
