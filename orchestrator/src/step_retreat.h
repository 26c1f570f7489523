// checks.step_halvings: a run that goes unstable in a stiff stretch (the Courant check stops it,
// the coupled step's growth doubling a step) goes on by itself with a smaller coupling step.
//   1. back to the run's newest checkpoint (as cosim resume)
//   2. on with half the coupling step and half coupling.dem_steps (the DEM step kept) to the
//      first checkpoint half a checkpoint interval past the stop
//   3. on with the scene's coupling.dt again
// A stop during 2 halves again, at most step_halvings times in a row; a stop during 3 starts
// again at 1. The run folder holds one run on one time axis throughout (the run's clock,
// checkpoints.h StepClock); the run log says each change of step.
#pragma once

#include <cstdint>

#include "coupler.h"
#include "scenario.h"

namespace cosim::orchestrator {

// cosim run and cosim resume: the run, through its stiff stretches as checks.step_halvings says.
RunResult runThroughStiffStretches(Scenario sc, RunOptions opt);

// Where a stretch at the smaller step ends: the first time checkpoint + k interval (k >= 1) at
// least half an interval past the stop, and not past the end.
double stretchEnd(double checkpoint, double stopped, double interval, double end);

}  // namespace cosim::orchestrator
