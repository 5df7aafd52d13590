#include "cli/bench_sim.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "cli/commands.hpp"
#include "cli/run_support.hpp"
#include "collide2d/scene/builtin_scene.hpp"
#include "lab/bench_scenes.hpp"

extern char** environ;

namespace collide2d::cli {
namespace {

namespace fs = std::filesystem;

struct Measured {
  bool ok = false;
  std::int64_t collisions = 0;
  double wall_s = 0, cpu_s = 0, peak_bytes = 0;
  std::string problem;
};

// From a run's printed summary: its collisions ("events      N (ball-ball X,
// ball-wall Y)") and, where it printed it ("memory      peak X MiB
// resident"), its peak resident memory in bytes (left as it was otherwise).
// False if it has no events line.
bool read_run_summary(const std::string& path, std::int64_t& collisions, double& peak_bytes) {
  std::ifstream in(path);
  std::string line;
  bool found = false;
  while (std::getline(in, line)) {
    long long events = 0, ball_ball = 0, ball_wall = 0;
    double mib = 0;
    if (std::sscanf(line.c_str(), "events %lld (ball-ball %lld, ball-wall %lld)", &events, &ball_ball, &ball_wall) == 3) {
      collisions = ball_ball + ball_wall;
      found = true;
    } else if (std::sscanf(line.c_str(), "memory peak %lf MiB", &mib) == 1) {
      peak_bytes = mib * 1024.0 * 1024.0;
    }
  }
  return found;
}

// Runs `collide2d run SCENE -o RUN --mode MODE` (the scene's whole duration)
// as a child and measures it: wall time around it, CPU time from wait4's
// resource usage of that child alone, peak resident memory from the child's
// summary.
Measured measure_run(const fs::path& scene, const fs::path& run, const std::string& mode) {
  Measured m;
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const fs::path out = run.string() + ".txt";
  std::vector<std::string> args = {self, "run", scene.string(), "-o", run.string(), "--mode", mode};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const auto start = std::chrono::steady_clock::now();
  const int spawned = posix_spawn(&pid, self.c_str(), &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0) {
    m.problem = "cannot start " + self;
    return m;
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  m.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  m.cpu_s = seconds(usage.ru_utime) + seconds(usage.ru_stime);
  m.peak_bytes = 1024.0 * static_cast<double>(usage.ru_maxrss);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    m.problem = "the run failed (exit status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
    return m;
  }
  // The child's own peak as it printed it: wait4's ru_maxrss also counts the
  // memory this process had when it started the child (posix_spawn shares it
  // until the exec), which for a bench of large gases is most of it.
  m.ok = read_run_summary(out.string(), m.collisions, m.peak_bytes);
  if (!m.ok) m.problem = "no summary in " + out.string();
  return m;
}

struct Case {
  Scene scene;
  double eta;  // < 0: not a gas
};

}  // namespace

int run_bench_sim(const BenchSimOptions& o) {
  std::vector<std::int64_t> sizes = o.sizes;
  if (o.large) sizes.insert(sizes.end(), {100000, 1000000});
  std::vector<Case> cases;
  for (std::int64_t n : sizes)
    for (double eta : o.etas) {
      if (!(eta > 0 && eta < 0.7)) {
        std::cerr << "collide2d bench sim: packing fraction " << eta << " outside (0, 0.7)\n";
        return exit_bad_input;
      }
      const double duration = o.collisions / hard_disk_collision_rate(n, eta, o.speed);
      cases.push_back({hard_disk_gas(n, eta, o.speed, duration, 20), eta});
    }
  if (o.settling) {
    cases.push_back({scene_from_text(builtin_abound_scene_json()), -1});
    cases.push_back({scene_from_text(builtin_pile_scene_json()), -1});
  }

  fs::path folder = o.keep;
  const bool temporary = folder.empty();
  if (temporary) {
    std::string pattern = (fs::temp_directory_path() / "collide2d-bench-XXXXXX").string();
    if (!mkdtemp(pattern.data())) {
      std::cerr << "collide2d bench sim: cannot make a temporary folder\n";
      return exit_bad_input;
    }
    folder = pattern;
  }
  fs::create_directories(folder);

  // The memory of the program itself (code, libraries, HDF5's caches): the
  // peak of a run of four discs, taken off every peak below so that
  // bytes_per_ball is what the balls and their events cost.
  std::map<std::string, double> baseline;
  {
    const fs::path scene = folder / "baseline.json";
    std::ofstream(scene) << scene_to_json_one_ball_a_line(hard_disk_gas(4, 0.1, o.speed, 1, 20));
    for (const std::string& mode : o.modes) {
      const Measured m = measure_run(scene, folder / ("baseline-" + mode + ".h5"), mode);
      if (!m.ok) {
        std::cerr << "bench sim: a run of four discs failed: " << m.problem << "\n";
        return exit_verification_failed;
      }
      baseline[mode] = m.peak_bytes;
    }
  }

  std::printf("scene,n,eta,mode,collisions,wall_s,cpu_s,collisions_per_s,bytes_per_ball\n");
  std::fflush(stdout);
  int failures = 0, k = 0;
  const int total = static_cast<int>(cases.size() * o.modes.size());
  for (const Case& c : cases) {
    const std::string& name = c.scene.name;
    const std::size_t n = c.scene.balls.size();
    const fs::path scene = folder / (name + ".json");
    std::ofstream(scene) << scene_to_json_one_ball_a_line(c.scene);
    for (const std::string& mode : o.modes) {
      std::cerr << "bench sim: " << ++k << " of " << total << ": " << name << " (" << n << " balls), " << mode << "\n";
      const fs::path run = folder / (name + "-" + mode + ".h5");
      const Measured m = measure_run(scene, run, mode);
      if (!m.ok) {
        std::cerr << "bench sim: " << name << " " << mode << ": " << m.problem << "\n";
        ++failures;
        continue;
      }
      std::printf("%s,%zu,%s,%s,%lld,%.3f,%.3f,%.0f,%.0f\n", name.c_str(), n,
                  c.eta < 0 ? "" : std::to_string(c.eta).substr(0, 4).c_str(), mode.c_str(),
                  static_cast<long long>(m.collisions), m.wall_s, m.cpu_s, static_cast<double>(m.collisions) / m.cpu_s,
                  (m.peak_bytes - baseline[mode]) / static_cast<double>(n));
      std::fflush(stdout);
      if (temporary) {
        fs::remove(run);
        fs::remove(run.string() + ".txt");
      }
    }
    if (temporary) fs::remove(scene);
  }
  if (temporary) fs::remove_all(folder);
  return failures == 0 ? exit_ok : exit_verification_failed;
}

}  // namespace collide2d::cli
