// HDF5 helpers of the run file; see run_file_hdf5.hpp.
#include "collide2d/io/run_file_hdf5.hpp"

#include <algorithm>
#include <cctype>

namespace collide2d::h5 {

// The most bytes a chunk of a run file's series holds (run_file.cpp sizes
// the frames' chunks to it as well): one fits HDF5's default 1 MiB chunk cache.
constexpr hsize_t kWidestChunkBytes = 512 * 1024;

namespace {

// The innermost message on HDF5's error stack: the one that says what went
// wrong (errno and file name, "truncated file", a status flag), not the API
// function that passed it up.
std::string hdf5_detail() {
  std::string detail;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* out) -> herr_t {
        if (e->desc != nullptr && *e->desc != '\0') *static_cast<std::string*>(out) = e->desc;
        return 0;
      },
      &detail);
  H5Eclear2(H5E_DEFAULT);
  return detail;
}

// Selects rows [at, at + n) of a dataset and the matching memory space.
std::pair<Hid, Hid> row_selection(hid_t d, hsize_t at, hsize_t n) {
  const auto dims = shape(d);
  Hid fspace(H5Dget_space(d), "dataspace");
  std::vector<hsize_t> start(dims.size(), 0), count = dims;
  start[0] = at;
  count[0] = n;
  check_ok(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr), "select rows");
  Hid mspace(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), "dataspace");
  return {std::move(fspace), std::move(mspace)};
}

// HDF5's innermost message in the words of a user: its internals (struct
// fields such as "sblock->base_addr", open flags) mean nothing outside HDF5.
// The operating system's own message is kept where HDF5 quotes it.
std::string plain_reason(const std::string& detail) {
  auto number_after = [&](const std::string& key) -> std::string {
    const std::size_t at = detail.find(key);
    if (at == std::string::npos) return "";
    std::size_t end = at + key.size();
    while (end < detail.size() && std::isdigit(static_cast<unsigned char>(detail[end]))) ++end;
    return detail.substr(at + key.size(), end - at - key.size());
  };
  if (detail.rfind("truncated file", 0) == 0) {
    const std::string have = number_after("eof = "), want = number_after("stored_eof = ");
    return "the file is truncated" + (have.empty() || want.empty() ? std::string() : ": " + have + " of " + want + " bytes");
  }
  if (const std::size_t at = detail.find("error message = '"); at != std::string::npos) {
    const std::size_t from = at + 17, to = detail.find('\'', from);
    return detail.substr(from, to == std::string::npos ? std::string::npos : to - from);
  }
  // run_file_read.cpp's says_status_flag() looks for "already open for write".
  if (detail.find("already open for write") != std::string::npos)
    return "the file is marked already open for write: its writer is still running or was killed";
  if (detail.find("lock") != std::string::npos) return "the file is locked by another program";
  if (detail.find("already open") != std::string::npos) return "the file is open in another program";
  return "its HDF5 structures are damaged";
}

}  // namespace

std::string describe_failure(const std::string& what) {
  const std::string detail = hdf5_detail();
  return detail.empty() ? what : what + " (" + plain_reason(detail) + ")";
}

void fail(const std::string& what) { throw Failure(describe_failure(what)); }

hid_t check_id(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void check_ok(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

void close_any(hid_t id) {
  switch (H5Iget_type(id)) {
    case H5I_FILE: H5Fclose(id); break;
    case H5I_GROUP: H5Gclose(id); break;
    case H5I_DATASET: H5Dclose(id); break;
    case H5I_DATASPACE: H5Sclose(id); break;
    case H5I_DATATYPE: H5Tclose(id); break;
    case H5I_ATTR: H5Aclose(id); break;
    case H5I_GENPROP_LST: H5Pclose(id); break;
    default: H5Idec_ref(id); break;
  }
}

Hid group(hid_t loc, const char* name, bool create) {
  if (create) return Hid(H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), std::string("create ") + name);
  return Hid(H5Gopen2(loc, name, H5P_DEFAULT), std::string("missing group ") + name);
}

Hid dataset(hid_t loc, const char* path) {
  return Hid(H5Dopen2(loc, path, H5P_DEFAULT), std::string("missing dataset ") + path);
}

// H5Lexists fails rather than answering "no" when a parent group is missing,
// so the path is checked one component at a time.
bool link_exists(hid_t file, const std::string& path) {
  std::size_t pos = 0;
  while ((pos = path.find('/', pos + 1)) != std::string::npos)
    if (H5Lexists(file, path.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
  return H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0;
}

Hid string_type(std::size_t length) {
  Hid type(H5Tcopy(H5T_C_S1), "string type");
  check_ok(H5Tset_size(type, length + 1), "string type");
  check_ok(H5Tset_strpad(type, H5T_STR_NULLTERM), "string type");
  check_ok(H5Tset_cset(type, H5T_CSET_UTF8), "string type");
  return type;
}

void write_string(hid_t loc, const char* name, const std::string& value, bool as_dataset) {
  Hid type = string_type(value.size());
  Hid space(H5Screate(H5S_SCALAR), "dataspace");
  const std::string what = std::string("write ") + name;
  if (as_dataset) {
    Hid d(H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), what);
    check_ok(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, value.c_str()), what);
  } else {
    Hid a(H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT), what);
    check_ok(H5Awrite(a, type, value.c_str()), what);
  }
}

void write_string_list(hid_t loc, const char* name, const std::vector<std::string>& values) {
  std::size_t longest = 0;
  for (const std::string& v : values) longest = std::max(longest, v.size());
  Hid type = string_type(longest);
  std::vector<char> packed(values.size() * (longest + 1), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) values[i].copy(packed.data() + i * (longest + 1), longest);
  const hsize_t count = values.size();
  Hid space(H5Screate_simple(1, &count, nullptr), "dataspace");
  const std::string what = std::string("write ") + name;
  Hid a(H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT), what);
  check_ok(H5Awrite(a, type, packed.data()), what);
}

void write_int_attribute(hid_t loc, const char* name, const std::vector<int>& values) {
  const hsize_t count = values.size();
  Hid space(count == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr), "dataspace");
  const std::string what = std::string("write ") + name;
  Hid a(H5Acreate2(loc, name, H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT), what);
  check_ok(H5Awrite(a, H5T_NATIVE_INT, values.data()), what);
}

// Reads a scalar string attribute or dataset, fixed- or variable-length (other
// H5MD writers use either).
std::string read_string(hid_t loc, const char* name, bool as_dataset) {
  const std::string what =
      std::string(as_dataset ? "missing or bad string dataset " : "missing or bad attribute ") + name;
  Hid obj(as_dataset ? H5Dopen2(loc, name, H5P_DEFAULT) : H5Aopen(loc, name, H5P_DEFAULT), what);
  Hid ftype(as_dataset ? H5Dget_type(obj) : H5Aget_type(obj), what);
  Hid space(as_dataset ? H5Dget_space(obj) : H5Aget_space(obj), what);
  if (H5Tget_class(ftype) != H5T_STRING || H5Sget_simple_extent_npoints(space) != 1) fail(what);
  auto read = [&](hid_t mtype, void* buf) {
    check_ok(as_dataset ? H5Dread(obj, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) : H5Aread(obj, mtype, buf), what);
  };
  // HDF5 converts between strings of one character set only: the memory
  // type takes the file's (h5py writes ASCII unless told otherwise).
  const H5T_cset_t cset = H5Tget_cset(ftype);
  if (H5Tis_variable_str(ftype) > 0) {
    Hid mtype(H5Tcopy(H5T_C_S1), what);
    check_ok(H5Tset_size(mtype, H5T_VARIABLE), what);
    check_ok(H5Tset_cset(mtype, cset), what);
    char* p = nullptr;
    read(mtype, &p);
    std::string s = p != nullptr ? p : "";
    H5free_memory(p);
    return s;
  }
  const std::size_t size = H5Tget_size(ftype);
  Hid mtype = string_type(size);  // one byte more than stored: room for a NUL in any case
  check_ok(H5Tset_cset(mtype, cset), what);
  std::vector<char> buf(size + 1, '\0');
  read(mtype, buf.data());
  return std::string(buf.data());
}

void write_array(hid_t loc, const char* name, hid_t ftype, hid_t mtype, std::vector<hsize_t> dims, const void* data) {
  Hid space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "dataspace");
  Hid d(H5Dcreate2(loc, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), std::string("create ") + name);
  if (H5Sget_simple_extent_npoints(space) > 0)
    check_ok(H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), std::string("write ") + name);
}

std::vector<hsize_t> shape(hid_t d) {
  Hid space(H5Dget_space(d), "dataspace");
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) fail("dataspace");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) check_ok(H5Sget_simple_extent_dims(space, dims.data(), nullptr), "dataspace");
  return dims;
}

// Unlimited along the first axis only: HDF5 then indexes the chunks with an
// extensible array, the structure SWMR appends are designed for.
//
// Compression: shuffle groups the bytes of equal significance (the zero high
// bytes of small indices, the shared exponents of nearby times) so that
// deflate at its fastest level finds them; both are lossless and in every
// HDF5 build that has zlib (without it the series is stored as it is). Under
// SWMR a compressed chunk rewritten with another size moves and HDF5 never
// frees its old place (a reader may hold the old index; measured: the file
// grows by that chunk), so a chunk a checkpoint wrote half full is never
// overwritten and stays readable after kill -9.
Hid create_series(hid_t loc, const char* name, hid_t ftype, std::vector<hsize_t> row_shape, hsize_t chunk_rows,
                  bool compressed) {
  std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{chunk_rows};
  for (auto x : row_shape) dims.push_back(x), maxdims.push_back(x), chunk.push_back(x);
  // A row wider than a chunk should be (a frame of a large scene: 16 MB
  // for a million balls' positions) is cut along its first axis, the balls:
  // HDF5 stages a chunk it cannot cache in a buffer of its own size, which
  // was 16 MB more of a large run's peak at every frame.
  if (!row_shape.empty()) {
    hsize_t row_bytes = H5Tget_size(ftype);
    for (std::size_t a = 1; a < row_shape.size(); ++a) row_bytes *= row_shape[a];
    const hsize_t most = std::max<hsize_t>(1, kWidestChunkBytes / (chunk_rows * row_bytes));
    chunk[1] = std::min(chunk[1], most);
  }
  Hid space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()), "dataspace");
  Hid dcpl(H5Pcreate(H5P_DATASET_CREATE), "dcpl");
  check_ok(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), "chunk");
  if (compressed && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    check_ok(H5Pset_shuffle(dcpl), "shuffle filter");
    check_ok(H5Pset_deflate(dcpl, 1), "deflate filter");
  }
  return Hid(H5Dcreate2(loc, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), std::string("create ") + name);
}

// Writes `n` rows at row `at`, growing the extent first if they end past it.
// Under SWMR this is the one kind of change allowed: raw data and a larger
// extent, never new objects.
void write_rows(hid_t d, hid_t mtype, hsize_t at, hsize_t n, const void* data) {
  if (n == 0) return;
  auto dims = shape(d);
  if (dims.empty()) fail("write rows into a scalar");
  if (at + n > dims[0]) {
    dims[0] = at + n;
    check_ok(H5Dset_extent(d, dims.data()), "extend dataset");
  }
  auto [fspace, mspace] = row_selection(d, at, n);
  check_ok(H5Dwrite(d, mtype, mspace, fspace, H5P_DEFAULT, data), "write rows");
}

void write_row_part(hid_t d, hid_t mtype, hsize_t at, hsize_t first, hsize_t n, const void* data) {
  if (n == 0) return;
  auto dims = shape(d);
  if (dims.size() < 2 || first + n > dims[1]) fail("write past the end of a row");
  if (at + 1 > dims[0]) {
    dims[0] = at + 1;
    check_ok(H5Dset_extent(d, dims.data()), "extend dataset");
  }
  Hid fspace(H5Dget_space(d), "dataspace");
  std::vector<hsize_t> start(dims.size(), 0), count = dims;
  start[0] = at, count[0] = 1;
  start[1] = first, count[1] = n;
  check_ok(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr), "select a row's part");
  Hid mspace(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), "dataspace");
  check_ok(H5Dwrite(d, mtype, mspace, fspace, H5P_DEFAULT, data), "write a row's part");
}

hsize_t chunk_extent(hid_t d, int axis) {
  Hid dcpl(H5Dget_create_plist(d), "dataset creation properties");
  std::vector<hsize_t> chunk(static_cast<std::size_t>(axis) + 8, 0);
  const int rank = H5Pget_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data());
  if (rank <= axis) fail("not chunked along that axis");
  return chunk[static_cast<std::size_t>(axis)];
}

void read_rows(hid_t d, hid_t mtype, hsize_t at, hsize_t n, void* out) {
  if (n == 0) return;
  const auto dims = shape(d);
  if (dims.empty() || at + n > dims[0]) fail("read past the end of a dataset");
  auto [fspace, mspace] = row_selection(d, at, n);
  check_ok(H5Dread(d, mtype, mspace, fspace, H5P_DEFAULT, out), "read rows");
}

Hid create_element(hid_t parent, const char* name, hid_t axes, hid_t ftype, std::vector<hsize_t> row_shape,
                   hsize_t chunk_rows) {
  Hid g = group(parent, name, true);
  for (const char* axis : {"step", "time"})
    check_ok(H5Lcreate_hard(axes, axis, g, axis, H5P_DEFAULT, H5P_DEFAULT), "link time axis");
  create_series(g, "value", ftype, std::move(row_shape), chunk_rows);
  return g;
}

// SWMR needs the 1.10 format (checksummed metadata); 1.10 readers and h5py
// built on them read it.
Hid latest_format_fapl() {
  Hid fapl(H5Pcreate(H5P_FILE_ACCESS), "fapl");
  check_ok(H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), "libver bounds");
  return fapl;
}

// The raw series are optional: both or neither (one alone is a damaged file).
Series open_series(hid_t f) {
  const bool raw = link_exists(f, kPositionRawPath), raw_velocity = link_exists(f, kVelocityRawPath);
  if (raw != raw_velocity) fail("only one of position_raw and velocity_raw exists");
  return Series{dataset(f, "/particles/balls/position/step"),
                dataset(f, "/particles/balls/position/time"),
                dataset(f, "/particles/balls/position/value"),
                dataset(f, "/particles/balls/velocity/value"),
                dataset(f, "/observables/energy/value"),
                dataset(f, "/observables/state_hash/value"),
                raw ? dataset(f, kPositionRawPath) : Hid{},
                raw ? dataset(f, kVelocityRawPath) : Hid{},
                dataset(f, "/events/time"),
                dataset(f, "/events/kind"),
                dataset(f, "/events/a"),
                dataset(f, "/events/b"),
                dataset(f, "/events/impulse"),
                dataset(f, "/checkpoint/time"),
                dataset(f, "/checkpoint/frames_written"),
                dataset(f, "/checkpoint/events_written"),
                dataset(f, "/checkpoint/engine_state_offset"),
                dataset(f, "/checkpoint/engine_state_size"),
                dataset(f, "/checkpoint/engine_state")};
}

}  // namespace collide2d::h5
