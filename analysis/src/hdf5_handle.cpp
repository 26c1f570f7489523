#include "hdf5_handle.h"

#include "cosim/util/errors.h"

namespace cosim::analysis::h5 {

void quiet() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {
// File access without HDF5's file locks: a user looking at particles.h5 (ParaView, h5py, a
// report) while the run goes must not make the next snapshot fail. The recorder writes each
// snapshot in one short open-write-close, so readers at worst see the previous snapshot set.
Handle accessWithoutLocks() {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose,
              "HDF5: cannot create a file access property list", ErrorKind::resource);
  H5Pset_file_locking(fapl, false, true);
  return fapl;
}
}  // namespace

Handle openFile(const std::string& path, unsigned flags, const std::string& purpose) {
  quiet();
  Handle fapl = accessWithoutLocks();
  return Handle(H5Fopen(path.c_str(), flags, fapl), H5Fclose,
                "cannot open HDF5 file " + path + " " + purpose +
                    ": the file is missing, not HDF5, damaged, or open for writing elsewhere in "
                    "this process",
                ErrorKind::input);
}

Handle createFile(const std::string& path) {
  quiet();
  Handle fapl = accessWithoutLocks();
  return Handle(
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose,
      "cannot create HDF5 file " + path + ": check that the run folder exists and is writable",
      ErrorKind::resource);
}

Handle openGroup(hid_t loc, const std::string& name, const std::string& file) {
  return Handle(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), H5Gclose,
                file + ": group '" + name + "' is missing (not a cosim particles file?)",
                ErrorKind::input);
}

Handle createGroup(hid_t loc, const std::string& name, const std::string& file) {
  return Handle(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                file + ": cannot create group '" + name + "'", ErrorKind::resource);
}

bool exists(hid_t loc, const std::string& name) {
  return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
}

namespace {
void writeDataset(hid_t loc, const std::string& name, hid_t type, const void* data, int rank,
                  const hsize_t* dims, const std::string& file) {
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose, file + ": cannot create dataspace",
               ErrorKind::resource);
  Handle set(H5Dcreate2(loc, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose, file + ": cannot create dataset '" + name + "'", ErrorKind::resource);
  hsize_t total = 1;
  for (int i = 0; i < rank; ++i) total *= dims[i];
  if (total > 0 && H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    throw ResourceError(file + ": cannot write dataset '" + name + "' (disk full?)");
  }
}

Handle openDataset(hid_t loc, const std::string& name, const std::string& file, int& rank,
                   hsize_t* dims) {
  Handle set(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose,
             file + ": dataset '" + name + "' is missing", ErrorKind::input);
  Handle space(H5Dget_space(set), H5Sclose, file + ": cannot read the shape of '" + name + "'",
               ErrorKind::input);
  rank = H5Sget_simple_extent_ndims(space);
  if (rank < 1 || rank > 2) {
    throw InputError(file + ": dataset '" + name + "' has rank " + std::to_string(rank) +
                     ", expected 1 (scalar per particle) or 2 (vector per particle)");
  }
  H5Sget_simple_extent_dims(space, dims, nullptr);
  return set;
}
}  // namespace

void writeDoubles(hid_t loc, const std::string& name, const double* data, std::uint64_t rows,
                  std::uint64_t cols, const std::string& file) {
  hsize_t dims[2] = {rows, cols};
  writeDataset(loc, name, H5T_NATIVE_DOUBLE, data, cols == 1 ? 1 : 2, dims, file);
}

void writeInt64s(hid_t loc, const std::string& name, const std::int64_t* data, std::uint64_t n,
                 const std::string& file) {
  hsize_t dims[1] = {n};
  writeDataset(loc, name, H5T_NATIVE_INT64, data, 1, dims, file);
}

std::vector<double> readDoubles(hid_t loc, const std::string& name, std::uint64_t& rows,
                                std::uint64_t& cols, const std::string& file) {
  int rank = 0;
  hsize_t dims[2] = {0, 1};
  Handle set = openDataset(loc, name, file, rank, dims);
  rows = dims[0];
  cols = rank == 2 ? dims[1] : 1;
  std::vector<double> out(static_cast<std::size_t>(rows * cols));
  if (!out.empty() &&
      H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    throw InputError(file + ": cannot read dataset '" + name + "'");
  }
  return out;
}

std::uint64_t rowsOf(hid_t loc, const std::string& name, const std::string& file) {
  int rank = 0;
  hsize_t dims[2] = {0, 1};
  openDataset(loc, name, file, rank, dims);
  return dims[0];
}

std::vector<std::int64_t> readInt64s(hid_t loc, const std::string& name, const std::string& file) {
  int rank = 0;
  hsize_t dims[2] = {0, 1};
  Handle set = openDataset(loc, name, file, rank, dims);
  std::vector<std::int64_t> out(static_cast<std::size_t>(dims[0] * (rank == 2 ? dims[1] : 1)));
  if (!out.empty() &&
      H5Dread(set, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    throw InputError(file + ": cannot read dataset '" + name + "'");
  }
  return out;
}

namespace {
void writeAttr(hid_t loc, const std::string& name, hid_t type, const void* value,
               const std::string& file) {
  if (H5Aexists(loc, name.c_str()) > 0) H5Adelete(loc, name.c_str());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, file + ": cannot create dataspace",
               ErrorKind::resource);
  Handle attr(H5Acreate2(loc, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              file + ": cannot create attribute '" + name + "'", ErrorKind::resource);
  if (H5Awrite(attr, type, value) < 0)
    throw ResourceError(file + ": cannot write attribute '" + name + "'");
}
}  // namespace

void writeAttribute(hid_t loc, const std::string& name, double value, const std::string& file) {
  writeAttr(loc, name, H5T_NATIVE_DOUBLE, &value, file);
}

void writeAttribute(hid_t loc, const std::string& name, std::int64_t value,
                    const std::string& file) {
  writeAttr(loc, name, H5T_NATIVE_INT64, &value, file);
}

void writeAttribute(hid_t loc, const std::string& name, const std::string& value,
                    const std::string& file) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, file + ": cannot create string type",
              ErrorKind::resource);
  H5Tset_size(type, value.empty() ? 1 : value.size());
  H5Tset_strpad(type, H5T_STR_NULLPAD);
  writeAttr(loc, name, type, value.empty() ? "" : value.data(), file);
}

void describeDataset(hid_t loc, const std::string& name, const std::string& units,
                     const std::string& description, const std::string& file) {
  Handle set(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose,
             file + ": dataset '" + name + "' is missing", ErrorKind::input);
  writeAttribute(set, "units", units, file);
  writeAttribute(set, "description", description, file);
}

bool hasAttribute(hid_t loc, const std::string& name) { return H5Aexists(loc, name.c_str()) > 0; }

double readDoubleAttribute(hid_t loc, const std::string& name, const std::string& file) {
  Handle attr(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose,
              file + ": attribute '" + name + "' is missing", ErrorKind::input);
  double v = 0;
  if (H5Aread(attr, H5T_NATIVE_DOUBLE, &v) < 0)
    throw InputError(file + ": cannot read attribute '" + name + "'");
  return v;
}

std::string readStringAttribute(hid_t loc, const std::string& name, const std::string& file) {
  Handle attr(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose,
              file + ": attribute '" + name + "' is missing", ErrorKind::input);
  Handle type(H5Aget_type(attr), H5Tclose, file + ": cannot read the type of '" + name + "'",
              ErrorKind::input);
  if (H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) > 0) {
    throw InputError(file + ": attribute '" + name + "' is not a fixed-length string");
  }
  std::string s(H5Tget_size(type), '\0');
  if (H5Aread(attr, type, s.data()) < 0)
    throw InputError(file + ": cannot read attribute '" + name + "'");
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

std::vector<std::string> members(hid_t group, const std::string& file) {
  H5G_info_t info;
  if (H5Gget_info(group, &info) < 0) throw InputError(file + ": cannot list a group");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    ssize_t len =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) throw InputError(file + ": cannot read a member name");
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                       H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    names.push_back(name);
  }
  return names;
}

}  // namespace cosim::analysis::h5
