// The narrow interface between the protocol side of cosimFoam (no OpenFOAM header) and its
// OpenFOAM side (mesh, fields, equations). Every method is collective: under MPI all ranks call
// it (RankBridge forwards rank 0's commands and small arguments); the particles and their terms
// are rank 0's, which sends each other rank those that reach its part of the mesh (place,
// advance: the others pass none); results are complete on rank 0. C++17, plain standard types
// only.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cosim::foam {

// Physical and numerical settings of the gas (from the participant's `options:`).
struct GasSettings {
  double temperature = 300.0;     // [K] isothermal perfect gas
  double molar_mass = 0.0280134;  // [kg/mol] N2
  double viscosity = 1.8e-5;      // [Pa s] dynamic
  double schmidt = 1.0;           // [-] precursor diffusivity Gamma = mu / Sc
  double min_voidage = 0.35;      // [-] lower bound of the voidage
  int voidage_divisions = 3;      // satellite points per parcel = divisions^3
  bool species = false;           // solve the precursor equation (scene has mass transfer)
  // Start from the isothermal hydrostatic pressure p_out exp(psi g.(x - x_out)) instead of the
  // p field of the start time (a uniform p makes the gas column fall and ring acoustically).
  bool hydrostatic_start = false;
  // The linear solvers' residual lines ("Solving for p, Initial residual = ...") go to the log
  // for every N-th gas step only (1: every step, OpenFOAM's own behaviour). They are most of
  // fluid.log: 1.35 kB a step in the coating bed, 13 MB per simulated second at 1e-4 s steps.
  int solver_log_every = 1;
  std::vector<std::string> inlet_patches{"inlet"};    // for pressure_drop
  std::vector<std::string> outlet_patches{"outlet"};  // for pressure_drop
  // The start time folder is a checkpoint's (cosim resume): its voidage, epsRho and epsRhoY are
  // the previous step's values, the old times of the next step; no hydrostatic start.
  bool resuming = false;
};

// Particles of one coupling step, in the order the orchestrator sent them.
struct ParticleSet {
  std::vector<std::int64_t> ids;
  std::vector<double> position;  // 3n [m]
  std::vector<double> radius;    // n [m]
  std::vector<double> velocity;  // 3n [m/s] (zeros when not sent)
  std::size_t size() const { return ids.size(); }
};

// Result of one CFD step: sent as the FluidReport of Advanced (proto/cosim.proto, where each
// quantity is documented).
struct StepResult {
  std::vector<double> precursor_removed;  // n [kg] per particle (empty without species)
  double pressure_drop = 0.0;
  double max_courant = 0.0;
  double voidage_min = 0.0;
  double gas_mass_in = 0.0, gas_mass_out = 0.0, gas_mass_held = 0.0;
  double solve_seconds = 0.0;
  bool species = false;  // the precursor balance below is set
  double precursor_in = 0.0, precursor_out = 0.0, precursor_held = 0.0;
  double precursor_held_start = 0.0;
  double precursor_removed_cells = 0.0, precursor_removed_total = 0.0;
  double precursor_min = 0.0, precursor_max = 0.0;
};

class GasDomain {
 public:
  virtual ~GasDomain() = default;

  // Builds the OpenFOAM objects for the case in the current directory. argv is what
  // Foam::argList parses (program name, -parallel, ...).
  static std::unique_ptr<GasDomain> create(int argc, char** argv, const GasSettings& settings);

  // Locates the particles (seeded by the cell each id had last time), divides their volume
  // over the cells (voidage) and remembers the division for the exchange terms of advance().
  // Returns the indices of particles whose centre is in no cell.
  virtual std::vector<std::size_t> place(const ParticleSet& particles) = 0;

  // Starts placing these particles ahead, while advance() runs (coupling scheme overlapped);
  // the next place() with exactly these particles takes the result. Serial runs only.
  virtual void prepare(const ParticleSet& particles) = 0;

  // Fields at the particles placed last (cosim::field names, components interleaved); lost
  // particles get zeros.
  virtual std::map<std::string, std::vector<double>> sample(
      const std::vector<std::string>& names) const = 0;

  // One CFD step of dt with drag coefficients K [kg/s] of the placed particles (may be empty:
  // no momentum exchange) and precursor transfer coefficients k [kg/s] (empty: no sink).
  virtual StepResult advance(double dt, const std::vector<double>& K,
                             const std::vector<double>& k) = 0;

  // Writes every field now (end of run) into the current time folder.
  virtual void writeNow() = 0;
  // Writes the fields into `path`/<time>/ for a restart; returns the folder written.
  virtual std::vector<std::string> checkpoint(const std::string& path) = 0;

  virtual double time() const = 0;
};

}  // namespace cosim::foam

// Entry point of the OpenFOAM module (libcosimFoamGas.so), looked up by GasDomain::create.
extern "C" cosim::foam::GasDomain* cosimFoamCreateGas(int argc, char** argv,
                                                      const cosim::foam::GasSettings* settings);
