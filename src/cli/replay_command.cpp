// collide2d replay RUN.h5: re-simulate from the file alone, compare bit for bit.
#include <cstdio>
#include <cstring>
#include <iostream>
#include <tuple>

#include "cli/commands.hpp"
#include "cli/run_support.hpp"

namespace collide2d::cli {
namespace {

bool same_bits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }

// A raw value as its Q63.64 words and the double nearest to it.
std::string describe_raw(std::int64_t hi, std::int64_t lo) {
  char text[96];
  std::snprintf(text, sizeof text, "raw hi %lld lo 0x%016llx (~%.17g)", static_cast<long long>(hi),
                static_cast<unsigned long long>(lo), from_words(hi, lo).to_double());
  return text;
}

// The first difference in the exact values of coordinate k (x or y of ball
// k / 2), or "". A fixed-mode file written before raw values were stored has
// none: then only the doubles and the state hash are compared.
std::string raw_difference(const FrameRecord& rec, const FrameRecord& now, std::size_t k) {
  if (rec.position_raw.empty()) return "";
  for (const auto& [field, a, b] : {std::tuple{"position_raw", &rec.position_raw, &now.position_raw},
                                    std::tuple{"velocity_raw", &rec.velocity_raw, &now.velocity_raw}}) {
    if (a->size() != b->size()) return std::string(field) + ": the file holds raw values, the replay does not";
    const std::size_t w = 2 * k;  // hi, lo
    if ((*a)[w] != (*b)[w] || (*a)[w + 1] != (*b)[w + 1]) {
      char text[128];
      std::snprintf(text, sizeof text, "ball %zu, %s.%c", k / 2, field, k % 2 ? 'y' : 'x');
      return std::string(text) + ": recorded " + describe_raw((*a)[w], (*a)[w + 1]) + ", replayed " +
             describe_raw((*b)[w], (*b)[w + 1]);
    }
  }
  return "";
}

// The first difference between a recorded frame and a replayed one, or "".
// Ball by ball: the doubles, then (fixed mode) the exact values they round.
std::string frame_difference(const FrameRecord& rec, const FrameRecord& now) {
  char text[256];
  for (std::size_t k = 0; k < rec.position.size(); ++k) {
    const char* field = nullptr;
    double a = 0, b = 0;
    if (!same_bits(rec.position[k], now.position[k])) {
      field = "position";
      a = rec.position[k];
      b = now.position[k];
    } else if (!same_bits(rec.velocity[k], now.velocity[k])) {
      field = "velocity";
      a = rec.velocity[k];
      b = now.velocity[k];
    }
    if (field) {
      std::snprintf(text, sizeof text, "frame %lld (t = %.17g), ball %zu, %s.%c: recorded %.17g, replayed %.17g",
                    static_cast<long long>(rec.step), rec.time, k / 2, field, k % 2 ? 'y' : 'x', a, b);
      return text;
    }
    if (const std::string raw = raw_difference(rec, now, k); !raw.empty()) {
      std::snprintf(text, sizeof text, "frame %lld (t = %.17g), ", static_cast<long long>(rec.step), rec.time);
      return text + raw;
    }
  }
  if (rec.state_hash != now.state_hash) {
    std::snprintf(text, sizeof text, "frame %lld: state hash recorded %016llx, replayed %016llx",
                  static_cast<long long>(rec.step), static_cast<unsigned long long>(rec.state_hash),
                  static_cast<unsigned long long>(now.state_hash));
    return text;
  }
  return "";
}

int replay(const std::string& path) {
  RunContents run;
  try {
    run = read_run_file(path);
  } catch (const RunFileError& e) {
    std::cerr << e.what() << "\n";
    return exit_bad_input;
  }
  if (!run.finished) {
    std::cerr << path << ": the run is unfinished (use collide2d resume)\n";
    return exit_bad_input;
  }
  RunOptions options;
  Scene scene;
  if (!read_back_parameters(run.header, path, scene, options)) return exit_bad_input;
  std::size_t frame = 0, event = 0;
  std::string difference;
  // A run file whose scene overflows would not have been written by `run`;
  // one from elsewhere is refused as `run` would refuse its scene.
  try {
    simulate_in_mode(
        scene, options,
        [&](const FrameRecord& f) {
          if (!difference.empty()) return;
          if (frame >= run.frames.size()) difference = "the replay has more frames than the file";
          else difference = frame_difference(run.frames[frame], f);
          ++frame;
        },
        [&](const EventRecord& e) {
          if (!difference.empty()) return;
          if (event >= run.events.size()) {
            difference = "the replay has more events than the file";
          } else {
            const EventRecord& r = run.events[event];
            if (!same_bits(r.time, e.time) || r.kind != e.kind || r.a != e.a || r.b != e.b || !same_bits(r.impulse, e.impulse)) {
              char text[256];
              std::snprintf(text, sizeof text,
                            "event %zu: recorded (t = %.17g, kind %d, %d, %d, impulse %.17g), replayed (t = %.17g, kind %d, %d, %d, impulse %.17g)",
                            event, r.time, r.kind, r.a, r.b, r.impulse, e.time, e.kind, e.a, e.b, e.impulse);
              difference = text;
            }
          }
          ++event;
        });
  } catch (const FixedPointOverflow& e) {
    std::cerr << path << ": " << e.what() << " (" << fixed_range_note << ")\n";
    return exit_bad_input;
  } catch (const StrictOverflow& e) {
    std::cerr << path << ": " << e.what() << " (" << strict_range_note << ")\n";
    return exit_bad_input;
  } catch (const EngineStall& e) {
    std::cerr << path << ": " << e.what() << "\n";
    return exit_verification_failed;
  }
  if (difference.empty() && (frame != run.frames.size() || event != run.events.size()))
    difference = "the file has more frames or events than the replay";
  if (!difference.empty()) {
    std::cout << "replay " << path << ": MISMATCH at " << difference << "\n";
    return exit_verification_failed;
  }
  std::cout << "replay " << path << ": identical, " << frame << " frames and " << event << " events, bit for bit\n";
  return exit_ok;
}

}  // namespace

Runner add_replay_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("replay", "re-simulate a run from its file alone and compare every frame and "
                                               "event bit for bit (exit 1 at the first difference)");
  cmd->add_option("RUN", *path, "run file (HDF5)")->required();
  return [path] { return replay(*path); };
}

}  // namespace collide2d::cli
