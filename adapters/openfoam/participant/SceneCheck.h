// What cosimFoam can tell about a scene before OpenFOAM starts (`cosim validate`, through
// cosimFoam --check-options, and again by the run itself before blockMesh/decomposePar): the
// options, the case folder, its mesh or blockMeshDict, the decomposition against the MPI ranks,
// and the patch names the options give. C++17, no OpenFOAM header.
#pragma once

#include <filesystem>

#include "AdapterSettings.h"
#include "cosim.pb.h"

namespace cosim::foam {

// The case in `dir` as the run would prepare it. Throws cosim::InputError naming the file or
// option on refusal.
void checkCase(const AdapterSettings& settings, int ranks, const std::filesystem::path& dir);

// The whole check of a Welcome as the run would receive it (its workdir holds the case).
void checkScene(const cosim::wire::Welcome& welcome, int ranks);

// numberOfSubdomains of a decomposeParDict; -1 when it says none.
int subdomainsOf(const std::filesystem::path& dict);

}  // namespace cosim::foam
