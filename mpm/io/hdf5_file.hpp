#pragma once
// A thin RAII wrapper over the HDF5 C API: just what snapshots and checkpoints need (1-D and 2-D
// datasets of doubles and 64-bit integers, scalar attributes). Files carry no modification times,
// so the same data gives byte-identical files. The ranks of a run spread over an MPI job open one
// file together (SharedFileAccess) and each writes its own rows of every dataset.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace hvi::mpm::io {

class Hdf5Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How the ranks of a run open one file together and write it collectively (MPI-IO, given by the
// driver that joined the MPI job: cases/parallel/). The solver and its output know no MPI.
class SharedFileAccess {
 public:
  virtual ~SharedFileAccess() = default;
  // Sets a file-access property list (an hid_t) to open the file on every rank of the job.
  virtual void set_file_access(std::int64_t fapl) const = 0;
  // Sets a dataset-transfer property list (an hid_t) to write collectively.
  virtual void set_transfer(std::int64_t dxpl) const = 0;
};

class Hdf5File {
 public:
  // append: an existing file, to add attributes (read and written by this process alone).
  enum class Mode { create, read, append };
  // With `shared`, a file created by every rank at once: each call that creates a dataset or
  // writes is collective, and each rank writes its own rows (write_rows). Attributes are best
  // added afterwards, by one rank, in append mode.
  Hdf5File(const std::string& path, Mode mode, const SharedFileAccess* shared = nullptr);
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
  // A dataset of `total` rows x columns, of which this process writes `rows` rows from row
  // `first` on (the ranks of a shared file each theirs; collective).
  struct Rows {
    std::size_t first, rows, total;
  };
  void write_rows(const std::string& name, const double* data, Rows rows, std::size_t columns);
  void write_rows(const std::string& name, const std::int64_t* data, Rows rows,
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
  // Rows [first, first + count) of a dataset, all its columns.
  std::vector<double> read_doubles(const std::string& name, std::size_t first,
                                   std::size_t count) const;
  std::vector<std::int64_t> read_integers(const std::string& name, std::size_t first,
                                          std::size_t count) const;
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
  const SharedFileAccess* shared_ = nullptr;
};

}  // namespace hvi::mpm::io
