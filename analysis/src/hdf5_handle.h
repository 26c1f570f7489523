// RAII for HDF5 C-API identifiers and the few read/write helpers the recorder and reader share.
// Private to cosim_analysis.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cosim/util/errors.h"

namespace cosim::analysis::h5 {

class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  // Throws an Error of `kind` with `what` if `id` is HDF5's failure: input where an existing file
  // is read (missing, damaged), resource where something is created or written.
  Handle(hid_t id, Closer closer, const std::string& what, ErrorKind kind)
      : id_(id), closer_(closer) {
    if (id_ < 0) throw Error(kind, what);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), closer_(o.closer_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
      closer_ = o.closer_;
    }
    return *this;
  }
  ~Handle() { reset(); }
  void reset() {
    if (id_ >= 0 && closer_ != nullptr) closer_(id_);
    id_ = -1;
  }
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

// Silence the HDF5 error stack printer: every failure becomes an exception with our message.
void quiet();

Handle openFile(const std::string& path, unsigned flags, const std::string& purpose);
Handle createFile(const std::string& path);
Handle openGroup(hid_t loc, const std::string& name, const std::string& file);
Handle createGroup(hid_t loc, const std::string& name, const std::string& file);
bool exists(hid_t loc, const std::string& name);

void writeDoubles(hid_t loc, const std::string& name, const double* data, std::uint64_t rows,
                  std::uint64_t cols, const std::string& file);
void writeInt64s(hid_t loc, const std::string& name, const std::int64_t* data, std::uint64_t n,
                 const std::string& file);
// Reads a dataset as doubles; rows and cols receive its shape (cols = 1 for 1-D).
std::vector<double> readDoubles(hid_t loc, const std::string& name, std::uint64_t& rows,
                                std::uint64_t& cols, const std::string& file);
std::vector<std::int64_t> readInt64s(hid_t loc, const std::string& name, const std::string& file);
// The number of rows (first dimension) of a dataset, without reading it.
std::uint64_t rowsOf(hid_t loc, const std::string& name, const std::string& file);

void writeAttribute(hid_t loc, const std::string& name, double value, const std::string& file);
void writeAttribute(hid_t loc, const std::string& name, std::int64_t value,
                    const std::string& file);
void writeAttribute(hid_t loc, const std::string& name, const std::string& value,
                    const std::string& file);
// Attributes `units` and `description` on the dataset `name` under `loc` (what it holds, for a
// reader of the file without our documentation).
void describeDataset(hid_t loc, const std::string& name, const std::string& units,
                     const std::string& description, const std::string& file);
bool hasAttribute(hid_t loc, const std::string& name);
double readDoubleAttribute(hid_t loc, const std::string& name, const std::string& file);
std::string readStringAttribute(hid_t loc, const std::string& name, const std::string& file);

// Names of the direct members of a group, in creation/name order.
std::vector<std::string> members(hid_t group, const std::string& file);

}  // namespace cosim::analysis::h5
