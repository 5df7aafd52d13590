// The formats of `collide2d export`: a run file's frames in the shapes that
// molecular-dynamics tools read. Each writer throws std::runtime_error saying
// what failed; the command (export_command.cpp) names the files around it.
#pragma once

#include <string>

#include "collide2d/io/run_file.hpp"

namespace collide2d::cli {

// H5MD 1.1 in three dimensions (z = 0), for MDAnalysis's H5MD reader, which
// refuses a 2D box (export_h5md3d.cpp).
void write_h5md3d(const RunContents& run, const std::string& path);

// Extended XYZ text, one block per frame, for ASE and OVITO (export_extxyz.cpp).
void write_extxyz(const RunContents& run, const std::string& path);

}  // namespace collide2d::cli
