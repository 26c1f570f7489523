// The physical memory of this host: the bound that the scene checks hold a mesh or a number of
// MPI ranks against before anything starts (docs/when-things-go-wrong.md).
#pragma once

namespace cosim::util {

// Physical memory of this host [bytes]; 0 when the system does not say.
double hostMemoryBytes();

}  // namespace cosim::util
