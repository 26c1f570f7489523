// GasDomain::create: loads the OpenFOAM module (libcosimFoamGas.so) at run time, after main has
// set the OpenFOAM environment, and calls its factory. Looked up next to the executable
// (../lib/ or the same folder) unless COSIM_FOAM_GAS_LIBRARY names the file.
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "GasDomain.h"
#include "cosim/util/errors.h"

namespace cosim::foam {
namespace fs = std::filesystem;

namespace {

fs::path moduleFile() {
  if (const char* env = std::getenv("COSIM_FOAM_GAS_LIBRARY")) return env;
  const fs::path exeDir = fs::read_symlink("/proc/self/exe").parent_path();
  for (const fs::path& p :
       {exeDir / ".." / "lib" / "libcosimFoamGas.so", exeDir / "libcosimFoamGas.so"}) {
    if (fs::exists(p)) return p;
  }
  throw ResourceError("cosimFoam: libcosimFoamGas.so not found in " +
                      (exeDir / ".." / "lib").string() + " nor " + exeDir.string() +
                      " (build the cosim_foam_gas target, or set COSIM_FOAM_GAS_LIBRARY)");
}

}  // namespace

std::unique_ptr<GasDomain> GasDomain::create(int argc, char** argv, const GasSettings& settings) {
  static void* handle = nullptr;
  if (handle == nullptr) {
    const fs::path file = moduleFile();
    handle = dlopen(file.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (handle == nullptr) {
      throw ResourceError("cosimFoam: cannot load " + file.string() + ": " + dlerror());
    }
  }
  using Factory = GasDomain* (*)(int, char**, const GasSettings*);
  auto factory = reinterpret_cast<Factory>(dlsym(handle, "cosimFoamCreateGas"));
  if (factory == nullptr) {
    throw ResourceError("cosimFoam: libcosimFoamGas.so has no cosimFoamCreateGas");
  }
  return std::unique_ptr<GasDomain>(factory(argc, argv, &settings));
}

}  // namespace cosim::foam
