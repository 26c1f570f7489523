#include "stability.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cosim/link/fields.h"

namespace cosim::orchestrator {

StabilityReport checkBeforeRun(const Scenario& sc, const SceneModels& /*models*/, const Plan& /*plan*/,
                               const link::ParticleData& s) {
  StabilityReport r;
  std::ostringstream os;
  const double dem_dt = sc.dt / sc.dem_steps;
  os << "coupling interval " << sc.dt << " s, " << sc.dem_steps << " DEM steps of " << dem_dt << " s, "
     << s.size() << " particles";
  r.lines.push_back(os.str());
  if (s.size() == 0) {
    r.lines.push_back("warning: the particle participant reports no particles at start");
  }
  return r;
}

}  // namespace cosim::orchestrator
