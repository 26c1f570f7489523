// The particle state goes to the orchestrator in ascending id order.
#pragma once

#include <cstddef>
#include <vector>

namespace cosim::liggghts {

// The order of records (stride `per`, the id first, as a double) by ascending id: order[k] is
// the record that comes k-th. LIGGGHTS numbers its atoms 1..N, so the ids usually fill a range
// not much wider than their count (also after some left the domain): each record is then put at
// its id's slot in one pass; ids spread more than twice their count, or repeated, are sorted.
std::vector<std::size_t> orderById(const std::vector<double>& records, std::size_t per);

}  // namespace cosim::liggghts
