// collide2d export --format h5md3d: the run's frames as an H5MD 1.1 file in
// three dimensions, which MDAnalysis's H5MD reader opens (it refuses any box
// whose dimension is not 3). Layout:
//
//   /h5md                      attr version = [1, 1]; author (name), creator (name, version)
//   /particles/balls/box       attr dimension = 3, boundary = ["none", "none", "none"]; no edges
//   /particles/balls/position  step [F] int64, time [F] float64, value [F][N][3] float64, z = 0
//   /particles/balls/velocity  step, time (hard links to position's), value [F][N][3], z = 0
//   /particles/balls/mass, radius        [N] float64 (time-independent)
//   /observables/energy        step, time (links), value [F] float64
//   /parameters/scene_json     the scene the run was made from
//
// The box has no edges on purpose: MDAnalysis takes edges as a periodic cell
// and would then wrap distances, which a scene bounded by walls is not.
// Without edges its frames have no dimensions (None), i.e. no periodicity.
// Nothing carries a `unit`: the scene's units are its own (see the run file),
// so MDAnalysis is told convert_units=False.
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cli/export_formats.hpp"
#include "collide2d/version.hpp"

namespace collide2d::cli {
namespace {

// Owns one HDF5 identifier and closes it with the function of its kind.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("cannot " + what);
  }
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("cannot " + what);
}

Handle make_group(hid_t parent, const char* name) {
  return Handle(H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                std::string("create group ") + name);
}

void write_dataset(hid_t loc, const char* name, hid_t file_type, hid_t memory_type, const std::vector<hsize_t>& dims,
                   const void* data) {
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, "make a dataspace");
  Handle set(H5Dcreate2(loc, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
             std::string("create dataset ") + name);
  if (H5Sget_simple_extent_npoints(space) > 0)
    check(H5Dwrite(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), std::string("write ") + name);
}

// Strings as H5MD wants them: fixed length, null-terminated, UTF-8. One
// string is a scalar; several are a 1-D array padded to the longest.
void write_strings(hid_t loc, const char* name, const std::vector<std::string>& values, bool as_dataset = false) {
  std::size_t longest = 0;
  for (const std::string& v : values) longest = std::max(longest, v.size());
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "make a string type");
  check(H5Tset_size(type, longest + 1), "make a string type");
  check(H5Tset_cset(type, H5T_CSET_UTF8), "make a string type");
  std::vector<char> packed(values.size() * (longest + 1), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) values[i].copy(packed.data() + i * (longest + 1), longest);
  const hsize_t count = values.size();
  Handle space(values.size() == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr), H5Sclose,
               "make a dataspace");
  if (as_dataset) {
    Handle set(H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
               std::string("create dataset ") + name);
    check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data()), std::string("write ") + name);
  } else {
    Handle attribute(H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                     std::string("create attribute ") + name);
    check(H5Awrite(attribute, type, packed.data()), std::string("write attribute ") + name);
  }
}

// A scalar integer attribute, or a 1-D one when given several values.
void write_integers(hid_t loc, const char* name, const std::vector<int>& values) {
  const hsize_t count = values.size();
  Handle space(values.size() == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr), H5Sclose,
               "make a dataspace");
  Handle attribute(H5Acreate2(loc, name, H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                   std::string("create attribute ") + name);
  check(H5Awrite(attribute, H5T_NATIVE_INT, values.data()), std::string("write attribute ") + name);
}

// An H5MD time-dependent element whose step and time are those of `axes`.
Handle make_element_sharing_axes(hid_t parent, const char* name, hid_t axes) {
  Handle element = make_group(parent, name);
  for (const char* axis : {"step", "time"})
    check(H5Lcreate_hard(axes, axis, element, axis, H5P_DEFAULT, H5P_DEFAULT), "link step and time");
  return element;
}

// The frames' x, y as x, y, 0: [F][N][3] from [F][N][2].
std::vector<double> padded_to_3d(const std::vector<FrameRecord>& frames, const std::vector<double> FrameRecord::*field) {
  std::vector<double> out;
  for (const FrameRecord& f : frames)
    for (std::size_t k = 0; k < (f.*field).size(); k += 2) out.insert(out.end(), {(f.*field)[k], (f.*field)[k + 1], 0.0});
  return out;
}

}  // namespace

void write_h5md3d(const RunContents& run, const std::string& path) {
  // Failures become exceptions with our own message; HDF5's error stack on
  // stderr would only repeat them.
  H5E_auto2_t print = nullptr;
  void* print_data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &print, &print_data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  struct RestoreErrorPrinting {
    H5E_auto2_t print;
    void* data;
    ~RestoreErrorPrinting() { H5Eset_auto2(H5E_DEFAULT, print, data); }
  } restore{print, print_data};

  const hsize_t frames = run.frames.size(), n = run.header.radius.size();
  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "create the file");

  Handle h5md = make_group(file, "h5md");
  write_integers(h5md, "version", {1, 1});
  write_strings(make_group(h5md, "author"), "name", {run.header.author});
  Handle creator = make_group(h5md, "creator");
  write_strings(creator, "name", {"collide2d"});
  write_strings(creator, "version", {COLLIDE2D_VERSION});

  Handle particles = make_group(file, "particles");
  Handle balls = make_group(particles, "balls");
  write_strings(balls, "units", {"the scene's own (lengths, times, masses as the scene gave them; SI customary)"});
  Handle box = make_group(balls, "box");
  write_integers(box, "dimension", {3});
  write_strings(box, "boundary", {"none", "none", "none"});

  std::vector<std::int64_t> step;
  std::vector<double> time, energy;
  for (const FrameRecord& f : run.frames) step.push_back(f.step), time.push_back(f.time), energy.push_back(f.energy);
  Handle position = make_group(balls, "position");
  write_dataset(position, "step", H5T_STD_I64LE, H5T_NATIVE_INT64, {frames}, step.data());
  write_dataset(position, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {frames}, time.data());
  write_dataset(position, "value", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {frames, n, 3},
                padded_to_3d(run.frames, &FrameRecord::position).data());
  write_dataset(make_element_sharing_axes(balls, "velocity", position), "value", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                {frames, n, 3}, padded_to_3d(run.frames, &FrameRecord::velocity).data());
  write_dataset(balls, "mass", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n}, run.header.mass.data());
  write_dataset(balls, "radius", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n}, run.header.radius.data());

  Handle observables = make_group(file, "observables");
  write_dataset(make_element_sharing_axes(observables, "energy", position), "value", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                {frames}, energy.data());
  write_strings(make_group(file, "parameters"), "scene_json", {run.header.scene_json}, true);
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "write the file");
}

}  // namespace collide2d::cli
