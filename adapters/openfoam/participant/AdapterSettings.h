// The participant's `options:` node of a scenario (Welcome.config_yaml) for cosimFoam: gas
// properties, voidage settings, patch names, declared with their defaults and meaning in
// adapterSettingSpecs() (docs/openfoam.md shows that table). Every key is checked; an unknown key
// or a value of the wrong kind is an error naming the key. C++17, no OpenFOAM header.
#pragma once

#include <string>
#include <vector>

#include "GasDomain.h"
#include "cosim/util/adapter_options.h"

namespace cosim::foam {

struct AdapterSettings {
  GasSettings gas;
  // "auto": run blockMesh when constant/polyMesh is missing and system/blockMeshDict exists;
  // "blockMesh": always run it; "existing": use the mesh as it is.
  std::string mesh = "auto";
};

const std::vector<util::OptionSpec>& adapterSettingSpecs();

// species: Welcome.species. Throws cosim::InputError naming the key on bad input.
AdapterSettings parseAdapterSettings(const std::string& yaml, bool species);

}  // namespace cosim::foam
