#include "lab/table_file.hpp"

#include <hdf5.h>

#include "collide2d/io/run_file_hdf5.hpp"

namespace collide2d {

using namespace collide2d::h5;

struct TableFile::Impl {
  std::string path;
  Hid file;

  // Runs one write, turning an HDF5 failure into an error naming the file.
  template <class F>
  void step(const std::string& what, F f) {
    QuietErrors quiet;
    try {
      f();
    } catch (const Failure& e) {
      throw TableFileError(path + ": " + what + ": " + e.what());
    }
  }

  // The group at `path`, made (with its parents) if missing.
  Hid open_group(const std::string& path_in) {
    if (path_in == "/") return Hid(H5Gopen2(file, "/", H5P_DEFAULT), "open /");
    std::size_t pos = 0;
    while (true) {
      pos = path_in.find('/', pos + 1);
      const std::string prefix = path_in.substr(0, pos);
      if (!link_exists(file, prefix)) Hid made = h5::group(file, prefix.c_str(), true);
      if (pos == std::string::npos) break;
    }
    return h5::group(file, path_in.c_str(), false);
  }

  // The parent group of a dataset path, and the dataset's own name.
  std::pair<Hid, std::string> parent_of(const std::string& path_in) {
    const std::size_t slash = path_in.rfind('/');
    const std::string parent = slash == 0 ? "/" : path_in.substr(0, slash);
    return {open_group(parent), path_in.substr(slash + 1)};
  }

  static std::vector<hsize_t> dims_or(std::vector<std::uint64_t> dims, std::size_t n) {
    if (dims.empty()) return {static_cast<hsize_t>(n)};
    std::uint64_t product = 1;
    for (const std::uint64_t d : dims) product *= d;
    if (product != n) throw Failure("dimensions do not match the number of values");
    return {dims.begin(), dims.end()};
  }

  Hid varlen_string_type() {
    Hid t(H5Tcopy(H5T_C_S1), "string type");
    check_ok(H5Tset_size(t, H5T_VARIABLE), "string size");
    check_ok(H5Tset_cset(t, H5T_CSET_UTF8), "string cset");
    return t;
  }

  void write_attribute(const std::string& group_path, const std::string& name, hid_t ftype, hid_t mtype,
                       const void* data) {
    Hid g = open_group(group_path);
    if (H5Aexists(g, name.c_str()) > 0) check_ok(H5Adelete(g, name.c_str()), "replace attribute " + name);
    Hid space(H5Screate(H5S_SCALAR), "dataspace");
    Hid a(H5Acreate2(g, name.c_str(), ftype, space, H5P_DEFAULT, H5P_DEFAULT), "attribute " + name);
    check_ok(H5Awrite(a, mtype, data), "write attribute " + name);
  }
};

TableFile::TableFile(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->step("create", [&] {
    Hid fapl = latest_format_fapl();
    impl_->file = Hid(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "create file");
  });
}

TableFile::~TableFile() = default;

void TableFile::write(const std::string& path, const std::vector<double>& values, std::vector<std::uint64_t> dims) {
  impl_->step("write " + path, [&] {
    auto [parent, name] = impl_->parent_of(path);
    write_array(parent, name.c_str(), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, Impl::dims_or(dims, values.size()), values.data());
  });
}

void TableFile::write(const std::string& path, const std::vector<std::int64_t>& values, std::vector<std::uint64_t> dims) {
  impl_->step("write " + path, [&] {
    auto [parent, name] = impl_->parent_of(path);
    write_array(parent, name.c_str(), H5T_STD_I64LE, H5T_NATIVE_INT64, Impl::dims_or(dims, values.size()), values.data());
  });
}

void TableFile::write(const std::string& path, const std::vector<std::uint64_t>& values) {
  impl_->step("write " + path, [&] {
    auto [parent, name] = impl_->parent_of(path);
    write_array(parent, name.c_str(), H5T_STD_U64LE, H5T_NATIVE_UINT64, Impl::dims_or({}, values.size()), values.data());
  });
}

void TableFile::write(const std::string& path, const std::vector<std::string>& values) {
  impl_->step("write " + path, [&] {
    auto [parent, name] = impl_->parent_of(path);
    std::vector<const char*> pointers;
    for (const std::string& v : values) pointers.push_back(v.c_str());
    Hid type = impl_->varlen_string_type();
    write_array(parent, name.c_str(), type, type, {static_cast<hsize_t>(values.size())}, pointers.data());
  });
}

void TableFile::group(const std::string& path) {
  impl_->step("group " + path, [&] { Hid g = impl_->open_group(path); });
}

void TableFile::attribute(const std::string& group, const std::string& name, const std::string& value) {
  impl_->step("attribute " + group + " " + name, [&] {
    Hid type = impl_->varlen_string_type();
    const char* pointer = value.c_str();
    impl_->write_attribute(group, name, type, type, &pointer);
  });
}

void TableFile::attribute(const std::string& group, const std::string& name, std::int64_t value) {
  impl_->step("attribute " + group + " " + name,
              [&] { impl_->write_attribute(group, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value); });
}

void TableFile::attribute(const std::string& group, const std::string& name, double value) {
  impl_->step("attribute " + group + " " + name,
              [&] { impl_->write_attribute(group, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value); });
}

}  // namespace collide2d
