#include "RankBridge.h"

#include <mpi.h>

#include <cstdlib>

namespace cosim::foam {

RankBridge::RankBridge(bool parallel) : parallel_(parallel) {
  if (parallel_) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
}

RankCommand RankBridge::command(RankCommand cmd) const {
  if (!parallel_) return cmd;
  int code = static_cast<int>(cmd);
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return static_cast<RankCommand>(code);
}

void RankBridge::share(double& value) const {
  if (parallel_) MPI_Bcast(&value, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

void RankBridge::share(std::string& value) const {
  if (!parallel_) return;
  long long n = static_cast<long long>(value.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  value.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(value.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
}

void RankBridge::share(std::vector<double>& values) const {
  if (!parallel_) return;
  long long n = static_cast<long long>(values.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  values.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(values.data(), static_cast<int>(n), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

void RankBridge::share(std::vector<std::int64_t>& values) const {
  if (!parallel_) return;
  long long n = static_cast<long long>(values.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  values.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(values.data(), static_cast<int>(n), MPI_INT64_T, 0, MPI_COMM_WORLD);
}

void RankBridge::share(std::vector<std::string>& values) const {
  if (!parallel_) return;
  long long n = static_cast<long long>(values.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  values.resize(static_cast<std::size_t>(n));
  for (auto& v : values) share(v);
}

void RankBridge::abortAll(int code) const {
  if (parallel_) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace cosim::foam
