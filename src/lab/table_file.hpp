// A small HDF5 writer for tables of results (the hard query set, studies):
// groups of parallel 1-D columns, 2-D arrays and attributes. Strings are
// variable-length UTF-8 (h5py reads them as str or bytes). Every error names
// the file and what was being written (TableFileError).
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace collide2d {

struct TableFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class TableFile {
 public:
  // Creates (or truncates) the file.
  explicit TableFile(const std::string& path);
  ~TableFile();
  TableFile(const TableFile&) = delete;
  TableFile& operator=(const TableFile&) = delete;

  // `path` is absolute ("/query/table/ns_median"); missing groups are made.
  // A 2-D array passes dims {rows, columns} with the values row by row.
  void write(const std::string& path, const std::vector<double>& values, std::vector<std::uint64_t> dims = {});
  void write(const std::string& path, const std::vector<std::int64_t>& values, std::vector<std::uint64_t> dims = {});
  void write(const std::string& path, const std::vector<std::uint64_t>& values);  // seeds
  void write(const std::string& path, const std::vector<std::string>& values);
  void group(const std::string& path);

  // Attributes on a group ("/" for the file), made if missing.
  void attribute(const std::string& group, const std::string& name, const std::string& value);
  void attribute(const std::string& group, const std::string& name, std::int64_t value);
  void attribute(const std::string& group, const std::string& name, double value);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace collide2d
