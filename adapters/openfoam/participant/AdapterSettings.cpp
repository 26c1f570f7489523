#include "AdapterSettings.h"

namespace cosim::foam {

const std::vector<util::OptionSpec>& adapterSettingSpecs() {
  static const std::vector<util::OptionSpec> s = {
      {"temperature", "300", "[K] the isothermal perfect gas's temperature, 1 .. 1e4"},
      {"molar_mass", "0.0280134", "[kg/mol] the gas's molar mass (N2), 1e-4 .. 1"},
      {"viscosity", "1.8e-5", "[Pa s] the gas's dynamic viscosity, 1e-8 .. 1e3"},
      {"schmidt", "1", "the precursor's diffusivity is viscosity / schmidt, 1e-6 .. 1e6"},
      {"min_voidage", "0.35", "lower bound of the voidage, 0.01 .. 1"},
      {"voidage_divisions", "3",
       "satellite points per parcel = divisions^3 for the voidage and the forces, 1 .. 9"},
      {"inlet_patches", "[inlet]",
       "a patch name or a list: pressure_drop is the mean pressure over these ..."},
      {"outlet_patches", "[outlet]", "... minus the mean over these (area-weighted)"},
      {"mesh", "auto",
       "auto (run blockMesh when constant/polyMesh is missing and system/blockMeshDict exists) | "
       "blockMesh (always run it) | existing (use the mesh as it is)"},
      {"hydrostatic_start", "false",
       "true: start from the isothermal hydrostatic pressure p_out exp(psi g.(x - x_out)) "
       "instead of 0/p (a uniform p makes the gas column fall and ring)"},
      {"solver_log_every", "1",
       "the linear solvers' residual lines in fluid.log for every N-th gas step only, 1 .. 1e9 "
       "(1: every step, as OpenFOAM does); the gas is computed the same to the bit"},
  };
  return s;
}

AdapterSettings parseAdapterSettings(const std::string& yaml, bool species) {
  const util::AdapterOptions o(yaml, "fluid", "cosimFoam", adapterSettingSpecs(),
                               "docs/openfoam.md");
  AdapterSettings s;
  GasSettings& g = s.gas;
  g.species = species;
  g.temperature = o.number("temperature", g.temperature, 1, 1e4);
  g.molar_mass = o.number("molar_mass", g.molar_mass, 1e-4, 1);
  g.viscosity = o.number("viscosity", g.viscosity, 1e-8, 1e3);
  g.schmidt = o.number("schmidt", g.schmidt, 1e-6, 1e6);
  g.min_voidage = o.number("min_voidage", g.min_voidage, 0.01, 1);
  g.voidage_divisions = o.whole("voidage_divisions", g.voidage_divisions, 1, 9);
  g.solver_log_every = o.whole("solver_log_every", g.solver_log_every, 1, 1000000000);
  g.inlet_patches = o.names("inlet_patches", g.inlet_patches);
  g.outlet_patches = o.names("outlet_patches", g.outlet_patches);
  g.hydrostatic_start = o.flag("hydrostatic_start", g.hydrostatic_start);
  s.mesh = o.choice("mesh", s.mesh, {"auto", "blockMesh", "existing"});
  return s;
}

}  // namespace cosim::foam
