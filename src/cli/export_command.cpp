// collide2d export RUN.h5 --format h5md3d|extxyz -o OUT: a run's frames for
// molecular-dynamics tools (MDAnalysis; ASE, OVITO). The run file itself is
// 2D H5MD; these readers want 3D, so z = 0 everywhere. Formats: export_formats.hpp.
#include <filesystem>
#include <iostream>
#include <map>

#include "cli/commands.hpp"
#include "cli/export_formats.hpp"
#include "cli/output_path.hpp"

namespace collide2d::cli {
namespace {

namespace fs = std::filesystem;

using Writer = void (*)(const RunContents&, const std::string&);
const std::map<std::string, Writer> formats = {{"h5md3d", write_h5md3d}, {"extxyz", write_extxyz}};

struct ExportOptions {
  std::string run, format, out;
};

int export_run(const ExportOptions& o) {
  const auto format = formats.find(o.format);
  if (format == formats.end()) {
    std::cerr << o.run << ": cannot export to format \"" << o.format << "\" (h5md3d or extxyz)\n";
    return exit_bad_input;
  }
  if (const std::string problem = output_path_problem(o.out, {o.run}); !problem.empty()) {
    std::cerr << problem << "\n";
    return exit_bad_input;
  }
  RunContents run;
  try {
    run = read_run_file(o.run);
  } catch (const RunFileError& e) {
    std::cerr << e.what() << "\n";
    return exit_bad_input;
  }
  if (run.frames.empty()) {
    std::cerr << o.run << ": no frames to export (an interrupted run before its first checkpoint)\n";
    return exit_bad_input;
  }
  if (!run.finished)
    std::cerr << "export: " << o.run << " is unfinished; exporting its frames up to the last checkpoint\n";

  // Written under another name and renamed at the end, so that a failed
  // export leaves nothing under OUT (nor a stale file that looks complete).
  const std::string partial = o.out + ".partial";
  try {
    format->second(run, partial);
    fs::rename(partial, o.out);
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove(partial, ec);
    std::cerr << o.out << ": " << e.what() << "\n";
    return exit_bad_input;
  }
  std::cout << "export " << o.run << " -> " << o.out << " (" << o.format << ", " << run.frames.size() << " frames of "
            << run.header.radius.size() << " balls)\n";
  return exit_ok;
}

}  // namespace

Runner add_export_command(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand("export", "write a run's frames for molecular-dynamics tools, in 3D with z = 0");
  cmd->add_option("RUN", o->run, "run file (HDF5)")->required();
  cmd->add_option("--format", o->format,
                  "h5md3d: H5MD 1.1 with a 3D box, for MDAnalysis (load with convert_units=False) and other H5MD "
                  "readers; extxyz: extended XYZ text, one block per frame with Time=, for ASE and OVITO")
      ->required();
  cmd->add_option("-o", o->out, "output file; written as OUT.partial and renamed when complete")->required();
  return [o] { return export_run(*o); };
}

}  // namespace collide2d::cli
