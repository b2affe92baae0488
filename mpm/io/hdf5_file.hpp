#pragma once
// A thin RAII wrapper over the HDF5 C API: just what snapshots and checkpoints need (1-D and 2-D
// datasets of doubles and 64-bit integers, scalar attributes). Files carry no modification times,
// so the same data gives byte-identical files.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace hvi::mpm::io {

class Hdf5Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Hdf5File {
 public:
  enum class Mode { create, read };
  Hdf5File(const std::string& path, Mode mode);
  ~Hdf5File();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  // Flushes and closes a written file; throws if its data did not all reach the disk (the
  // destructor cannot report that, so a writer calls this before it trusts the file). A file
  // opened to write that an exception unwinds (a refused write, a failed close) is removed, so
  // no truncated file is left to read and no space is held on a full disk.
  void close();

  // Datasets written from now on carry a Fletcher-32 checksum (chunked), which every read checks:
  // a damaged file fails to read instead of giving wrong values.
  void checksum_datasets() { checksums_ = true; }
  // Dataset of rows x columns values (columns = 1 writes a 1-D dataset).
  void write(const std::string& name, const double* data, std::size_t rows, std::size_t columns);
  void write(const std::string& name, const std::int64_t* data, std::size_t rows,
             std::size_t columns);
  void write_attribute(const std::string& name, double value);
  void write_attribute(const std::string& name, std::int64_t value);
  void write_attribute(const std::string& name, const std::string& value);

  bool has_dataset(const std::string& name) const;
  std::vector<std::string> dataset_names() const;
  // Rows and columns of a dataset.
  std::pair<std::size_t, std::size_t> shape(const std::string& name) const;
  std::vector<double> read_doubles(const std::string& name) const;
  std::vector<std::int64_t> read_integers(const std::string& name) const;
  double read_double_attribute(const std::string& name) const;
  std::int64_t read_integer_attribute(const std::string& name) const;
  std::string read_string_attribute(const std::string& name) const;
  bool has_attribute(const std::string& name) const;
  std::vector<std::string> attribute_names() const;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::int64_t file_ = -1;      // hid_t
  bool created_ = false;        // opened to write: removed if an exception unwinds it
  int exceptions_at_open_ = 0;  // std::uncaught_exceptions() when opened
  bool checksums_ = false;
};

}  // namespace hvi::mpm::io
