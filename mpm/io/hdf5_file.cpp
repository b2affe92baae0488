#include "mpm/io/hdf5_file.hpp"

#include <algorithm>

#include <exception>
#include <filesystem>

#include <hdf5.h>

namespace hvi::mpm::io {
namespace {

// Closes an HDF5 handle at scope exit.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

// Why the last HDF5 call failed, from the library's error stack: the operating system's message
// where a file driver recorded one ("No space left on device"), else the innermost description.
std::string reason() {
  struct Found {
    std::string innermost, system;
  } found;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
        auto& f = *static_cast<Found*>(data);
        const std::string desc = e->desc ? e->desc : "";
        if (!desc.empty()) f.innermost = desc;
        const std::string tag = "error message = '";
        if (const auto at = desc.find(tag); at != std::string::npos) {
          const auto end = desc.find('\'', at + tag.size());
          f.system =
              desc.substr(at + tag.size(), end == std::string::npos ? end : end - at - tag.size());
        }
        return 0;
      },
      &found);
  return !found.system.empty() ? found.system : found.innermost;
}

[[noreturn]] void fail(const std::string& what, const std::string& path) {
  const std::string why = reason();
  throw Hdf5Error("HDF5: cannot " + what + " in '" + path + "'" + (why.empty() ? "" : ": " + why));
}

hid_t check(hid_t id, const std::string& what, const std::string& path) {
  if (id < 0) fail(what, path);
  return id;
}

void check_status(herr_t status, const std::string& what, const std::string& path) {
  if (status < 0) fail(what, path);
}

// Selects rows [first, first + count) of a dataset of `columns` columns (none if count is 0).
void select_rows(hid_t space, std::size_t first, std::size_t count, std::size_t columns) {
  if (count == 0) {
    H5Sselect_none(space);
    return;
  }
  const hsize_t start[2] = {first, 0}, size[2] = {count, columns};
  H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, size, nullptr);
}

// The rows' values in memory: count x columns (a one-row space with nothing selected for none).
hid_t memory_space(std::size_t count, std::size_t columns) {
  const hsize_t dims[2] = {std::max<std::size_t>(count, 1), columns};
  const hid_t space = H5Screate_simple(columns == 1 ? 1 : 2, dims, nullptr);
  if (count == 0) H5Sselect_none(space);
  return space;
}

void write_dataset(hid_t file, const std::string& path, const std::string& name, hid_t type,
                   const void* data, Hdf5File::Rows rows, std::size_t columns, bool checksum,
                   const SharedFileAccess* shared) {
  const hsize_t dims[2] = {rows.total, columns};
  const int rank = columns == 1 ? 1 : 2;
  Handle space{check(H5Screate_simple(rank, dims, nullptr), "create dataspace", path), H5Sclose};
  Handle dcpl{H5Pcreate(H5P_DATASET_CREATE), H5Pclose};
  H5Pset_obj_track_times(dcpl.id, false);
  // Space taken when the dataset is made and never pre-filled: the layout a shared file needs
  // (MPI-IO), so one rank and many lay a file out alike.
  H5Pset_alloc_time(dcpl.id, H5D_ALLOC_TIME_EARLY);
  H5Pset_fill_time(dcpl.id, H5D_FILL_TIME_NEVER);
  if (checksum && rows.total * columns > 0) {
    // Chunks of up to 65,536 rows, each with its Fletcher-32 checksum.
    const hsize_t chunk[2] = {std::min<hsize_t>(rows.total, 65536), columns};
    check_status(H5Pset_chunk(dcpl.id, rank, chunk), "chunk dataset '" + name + "'", path);
    check_status(H5Pset_fletcher32(dcpl.id), "checksum dataset '" + name + "'", path);
  }
  Handle set{
      check(H5Dcreate2(file, name.c_str(), type, space.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT),
            "create dataset '" + name + "'", path),
      H5Dclose};
  if (rows.total * columns == 0) return;
  select_rows(space.id, rows.first, rows.rows, columns);
  Handle memory{memory_space(rows.rows, columns), H5Sclose};
  Handle dxpl{H5Pcreate(H5P_DATASET_XFER), H5Pclose};
  if (shared) shared->set_transfer(dxpl.id);
  const double none = 0.0;  // a valid address for a rank that writes no rows
  check_status(H5Dwrite(set.id, type, memory.id, space.id, dxpl.id, rows.rows > 0 ? data : &none),
               "write dataset '" + name + "'", path);
}

void write_attr(hid_t file, const std::string& path, const std::string& name, hid_t type,
                const void* data) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{check(H5Acreate2(file, name.c_str(), type, space.id, H5P_DEFAULT, H5P_DEFAULT),
                    "create attribute '" + name + "'", path),
              H5Aclose};
  check_status(H5Awrite(attr.id, type, data), "write attribute '" + name + "'", path);
}

}  // namespace

Hdf5File::Hdf5File(const std::string& path, Mode mode, const SharedFileAccess* shared)
    : path_(path),
      created_(mode != Mode::read),
      exceptions_at_open_(std::uncaught_exceptions()),
      shared_(shared) {
  // A file whose close failed (its last writes refused by a full disk) stays in HDF5's table, and
  // the library's exit handler (1.10) crashes closing it again; every file here is closed by its
  // owner, so the process exits without that handler and keeps its exit code. Must precede the
  // library's first call.
  static const bool no_exit_handler = H5dont_atexit() >= 0;
  (void)no_exit_handler;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions, not stderr dumps
  if (mode == Mode::create) {
    Handle fcpl{H5Pcreate(H5P_FILE_CREATE), H5Pclose};
    Handle fapl{H5Pcreate(H5P_FILE_ACCESS), H5Pclose};
    // The oldest format that holds our data gives stable bytes across library versions.
    H5Pset_libver_bounds(fapl.id, H5F_LIBVER_EARLIEST, H5F_LIBVER_V18);
    if (shared) shared->set_file_access(fapl.id);
    file_ = check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.id, fapl.id), "create file", path);
  } else if (mode == Mode::append) {
    Handle fapl{H5Pcreate(H5P_FILE_ACCESS), H5Pclose};
    H5Pset_libver_bounds(fapl.id, H5F_LIBVER_EARLIEST, H5F_LIBVER_V18);
    file_ = check(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.id), "open file", path);
  } else {
    file_ = check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open file", path);
  }
}

Hdf5File::~Hdf5File() {
  if (file_ >= 0) H5Fclose(file_);
  if (created_ && std::uncaught_exceptions() > exceptions_at_open_) {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
}

void Hdf5File::close() {
  if (file_ < 0) return;
  const hid_t file = file_;
  file_ = -1;
  if (H5Fflush(file, H5F_SCOPE_LOCAL) < 0) {
    H5Fclose(file);
    fail("flush file", path_);
  }
  check_status(H5Fclose(file), "close file", path_);
}

void Hdf5File::write(const std::string& name, const double* data, std::size_t rows,
                     std::size_t columns) {
  write_rows(name, data, {0, rows, rows}, columns);
}

void Hdf5File::write(const std::string& name, const std::int64_t* data, std::size_t rows,
                     std::size_t columns) {
  write_rows(name, data, {0, rows, rows}, columns);
}

void Hdf5File::write_rows(const std::string& name, const double* data, Rows rows,
                          std::size_t columns) {
  write_dataset(file_, path_, name, H5T_NATIVE_DOUBLE, data, rows, columns, checksums_, shared_);
}

void Hdf5File::write_rows(const std::string& name, const std::int64_t* data, Rows rows,
                          std::size_t columns) {
  write_dataset(file_, path_, name, H5T_NATIVE_INT64, data, rows, columns, checksums_, shared_);
}

void Hdf5File::write_attribute(const std::string& name, double value) {
  write_attr(file_, path_, name, H5T_NATIVE_DOUBLE, &value);
}

void Hdf5File::write_attribute(const std::string& name, std::int64_t value) {
  write_attr(file_, path_, name, H5T_NATIVE_INT64, &value);
}

void Hdf5File::write_attribute(const std::string& name, const std::string& value) {
  Handle type{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(type.id, value.size() + 1);
  write_attr(file_, path_, name, type.id, value.c_str());
}

bool Hdf5File::has_dataset(const std::string& name) const {
  return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
}

std::vector<std::string> Hdf5File::dataset_names() const {
  std::vector<std::string> names;
  H5Literate(
      file_, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
        static_cast<std::vector<std::string>*>(out)->emplace_back(name);
        return 0;
      },
      &names);
  return names;
}

std::pair<std::size_t, std::size_t> Hdf5File::shape(const std::string& name) const {
  Handle set{
      check(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), "open dataset '" + name + "'", path_),
      H5Dclose};
  Handle space{H5Dget_space(set.id), H5Sclose};
  hsize_t dims[2] = {0, 1};
  const int rank = H5Sget_simple_extent_dims(space.id, dims, nullptr);
  return {dims[0], rank == 2 ? dims[1] : 1};
}

namespace {
template <class T>
std::vector<T> read_some(hid_t file, const std::string& path, const std::string& name, hid_t type,
                         std::size_t first, std::size_t count, std::size_t columns) {
  Handle set{check(H5Dopen2(file, name.c_str(), H5P_DEFAULT), "open dataset '" + name + "'", path),
             H5Dclose};
  std::vector<T> data(count * columns);
  if (data.empty()) return data;
  Handle space{H5Dget_space(set.id), H5Sclose};
  select_rows(space.id, first, count, columns);
  Handle memory{memory_space(count, columns), H5Sclose};
  check_status(H5Dread(set.id, type, memory.id, space.id, H5P_DEFAULT, data.data()),
               "read dataset '" + name + "'", path);
  return data;
}
}  // namespace

std::vector<double> Hdf5File::read_doubles(const std::string& name, std::size_t first,
                                           std::size_t count) const {
  return read_some<double>(file_, path_, name, H5T_NATIVE_DOUBLE, first, count, shape(name).second);
}

std::vector<std::int64_t> Hdf5File::read_integers(const std::string& name, std::size_t first,
                                                  std::size_t count) const {
  return read_some<std::int64_t>(file_, path_, name, H5T_NATIVE_INT64, first, count,
                                 shape(name).second);
}

std::vector<double> Hdf5File::read_doubles(const std::string& name) const {
  return read_doubles(name, 0, shape(name).first);
}

std::vector<std::int64_t> Hdf5File::read_integers(const std::string& name) const {
  return read_integers(name, 0, shape(name).first);
}

bool Hdf5File::has_attribute(const std::string& name) const {
  return H5Aexists(file_, name.c_str()) > 0;
}

double Hdf5File::read_double_attribute(const std::string& name) const {
  Handle attr{
      check(H5Aopen(file_, name.c_str(), H5P_DEFAULT), "open attribute '" + name + "'", path_),
      H5Aclose};
  double v = 0;
  check_status(H5Aread(attr.id, H5T_NATIVE_DOUBLE, &v), "read attribute '" + name + "'", path_);
  return v;
}

std::int64_t Hdf5File::read_integer_attribute(const std::string& name) const {
  Handle attr{
      check(H5Aopen(file_, name.c_str(), H5P_DEFAULT), "open attribute '" + name + "'", path_),
      H5Aclose};
  std::int64_t v = 0;
  check_status(H5Aread(attr.id, H5T_NATIVE_INT64, &v), "read attribute '" + name + "'", path_);
  return v;
}

std::string Hdf5File::read_string_attribute(const std::string& name) const {
  Handle attr{
      check(H5Aopen(file_, name.c_str(), H5P_DEFAULT), "open attribute '" + name + "'", path_),
      H5Aclose};
  Handle type{H5Aget_type(attr.id), H5Tclose};
  std::string v(H5Tget_size(type.id), '\0');
  Handle mem{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(mem.id, v.size());
  check_status(H5Aread(attr.id, mem.id, v.data()), "read attribute '" + name + "'", path_);
  while (!v.empty() && v.back() == '\0') v.pop_back();
  return v;
}

std::vector<std::string> Hdf5File::attribute_names() const {
  std::vector<std::string> names;
  H5Aiterate2(
      file_, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
        static_cast<std::vector<std::string>*>(out)->emplace_back(name);
        return 0;
      },
      &names);
  return names;
}

}  // namespace hvi::mpm::io
