// collide2d bench sim: collisions per CPU second of whole `collide2d run`
// processes (each run in a child process, writing its run file, so that the
// CPU time and peak memory are the run's own), as CSV
// scene,n,eta,mode,collisions,wall_s,cpu_s,collisions_per_s,bytes_per_ball.
// collisions: ball–ball and ball–wall; cpu_s: user + system time of the run;
// bytes_per_ball: its peak resident memory above that of a run of four
// discs (the program and its libraries), per ball, run-file buffers included.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli/parse_options.hpp"

namespace collide2d::cli {

struct BenchSimOptions {
  std::vector<std::int64_t> sizes{1000, 10000};
  std::vector<double> etas{0.1, 0.3, 0.45};
  bool large = false;             // also N = 10^5 and 10^6
  std::vector<std::string> modes = number_mode_names();
  double collisions = 1e6;        // a gas run is sized to make about this many
  double speed = 1;               // of every disc at the start
  bool settling = true;           // the Abound and settling-pile rows
  std::string keep;               // folder to keep the scenes and run files in (empty: a temporary one, removed)
};

int run_bench_sim(const BenchSimOptions& o);

}  // namespace collide2d::cli
