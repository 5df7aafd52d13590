// collide2d export --format extxyz: extended XYZ, the text format of ASE and
// OVITO. One block per frame:
//
//   N
//   Lattice="Lx 0 0 0 Ly 0 0 0 Lz" Origin="x0 y0 z0" Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:masses:R:1 Time=t Step=s pbc="F F F"
//   X x y 0 vx vy 0 r m        (one line per ball)
//
// Column names are the ones both readers know: OVITO maps pos, velo, radius
// and species to its Position, Velocity, Radius and Particle Type; ASE maps
// pos and species to positions and symbols, takes `masses` as the atoms'
// masses, and keeps velo and radius as per-atom arrays. The species is "X",
// ASE's dummy element, for every ball. Numbers have 17 significant digits, so
// every double reads back exactly.
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "cli/export_formats.hpp"

namespace collide2d::cli {
namespace {

// The smallest box holding every wall and every ball's disk in every frame:
// the cell OVITO draws and ASE reports. Non-periodic (pbc F), so nothing
// depends on it beyond display.
struct Extent {
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  void cover(double x, double y, double r) {
    lo[0] = std::fmin(lo[0], x - r), hi[0] = std::fmax(hi[0], x + r);
    lo[1] = std::fmin(lo[1], y - r), hi[1] = std::fmax(hi[1], y + r);
  }
};

Extent scene_extent(const RunContents& run) {
  Extent e;
  for (const auto& w : run.header.walls) e.cover(w[0], w[1], 0), e.cover(w[2], w[3], 0);
  for (const FrameRecord& f : run.frames)
    for (std::size_t i = 0; i < run.header.radius.size(); ++i)
      e.cover(f.position[2 * i], f.position[2 * i + 1], run.header.radius[i]);
  return e;
}

struct CloseFile {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

void write_extxyz(const RunContents& run, const std::string& path) {
  std::unique_ptr<std::FILE, CloseFile> out(std::fopen(path.c_str(), "w"));
  if (!out) throw std::runtime_error("cannot create the file");
  const std::vector<double>& radius = run.header.radius;
  const std::vector<double>& mass = run.header.mass;
  const Extent box = scene_extent(run);
  // The plane z = 0 in the middle of a slab as thick as the largest ball.
  double largest = 0;
  for (double r : radius) largest = std::fmax(largest, r);
  for (const FrameRecord& f : run.frames) {
    std::fprintf(out.get(),
                 "%zu\nLattice=\"%.17g 0 0 0 %.17g 0 0 0 %.17g\" Origin=\"%.17g %.17g %.17g\" "
                 "Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:masses:R:1 Time=%.17g Step=%lld pbc=\"F F F\"\n",
                 radius.size(), box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], 2 * largest, box.lo[0], box.lo[1],
                 -largest, f.time, static_cast<long long>(f.step));
    for (std::size_t i = 0; i < radius.size(); ++i)
      std::fprintf(out.get(), "X %.17g %.17g 0 %.17g %.17g 0 %.17g %.17g\n", f.position[2 * i], f.position[2 * i + 1],
                   f.velocity[2 * i], f.velocity[2 * i + 1], radius[i], mass[i]);
  }
  if (std::ferror(out.get()) != 0 || std::fclose(out.release()) != 0) throw std::runtime_error("write error");
}

}  // namespace collide2d::cli
