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
#include <cstdint>
#include <string>
#include <vector>

#include "cli/export_formats.hpp"
#include "collide2d/io/run_file_hdf5.hpp"
#include "collide2d/version.hpp"

namespace collide2d::cli {
namespace {

using namespace h5;  // the run file's own HDF5 helpers: handles, groups, strings, arrays

// An H5MD time-dependent element whose step and time are those of `axes`.
Hid element_sharing_axes(hid_t parent, const char* name, hid_t axes) {
  Hid element = group(parent, name, true);
  for (const char* axis : {"step", "time"})
    check_ok(H5Lcreate_hard(axes, axis, element, axis, H5P_DEFAULT, H5P_DEFAULT), "link step and time");
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
  QuietErrors quiet;  // failures become exceptions; HDF5's stack on stderr would only repeat them
  const hsize_t frames = run.frames.size(), n = run.header.radius.size();
  Hid file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create the file");

  Hid h5md = group(file, "h5md", true);
  write_int_attribute(h5md, "version", {1, 1});
  write_string(group(h5md, "author", true), "name", run.header.author, false);
  Hid creator = group(h5md, "creator", true);
  write_string(creator, "name", "collide2d", false);
  write_string(creator, "version", COLLIDE2D_VERSION, false);

  Hid particles = group(file, "particles", true);
  Hid balls = group(particles, "balls", true);
  write_string(balls, "units", "the scene's own (lengths, times, masses as the scene gave them; SI customary)", false);
  Hid box = group(balls, "box", true);
  write_int_attribute(box, "dimension", {3});
  write_string_list(box, "boundary", {"none", "none", "none"});

  std::vector<std::int64_t> step;
  std::vector<double> time, energy;
  for (const FrameRecord& f : run.frames) step.push_back(f.step), time.push_back(f.time), energy.push_back(f.energy);
  Hid position = group(balls, "position", true);
  write_array(position, "step", H5T_STD_I64LE, H5T_NATIVE_INT64, {frames}, step.data());
  write_array(position, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {frames}, time.data());
  write_array(position, "value", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {frames, n, 3},
              padded_to_3d(run.frames, &FrameRecord::position).data());
  write_array(element_sharing_axes(balls, "velocity", position), "value", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
              {frames, n, 3}, padded_to_3d(run.frames, &FrameRecord::velocity).data());
  write_array(balls, "mass", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n}, run.header.mass.data());
  write_array(balls, "radius", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n}, run.header.radius.data());

  Hid observables = group(file, "observables", true);
  write_array(element_sharing_axes(observables, "energy", position), "value", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
              {frames}, energy.data());
  write_string(group(file, "parameters", true), "scene_json", run.header.scene_json, true);
  check_ok(H5Fflush(file, H5F_SCOPE_GLOBAL), "write the file");
}

}  // namespace collide2d::cli
