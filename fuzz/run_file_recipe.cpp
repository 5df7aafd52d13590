// A run file from a fuzz input; see run_file_recipe.hpp. The layout follows
// RunWriter (src/collide2d/io/run_file.cpp) object by object, and every
// object goes through put_numbers or put_string, which is where the fuzzer
// chooses how it departs from what the writer would have written.
#include "run_file_recipe.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace collide2d::fuzz {
namespace {

[[noreturn]] void recipe_failed(const std::string& what) {
  std::fprintf(stderr, "run_file_recipe: HDF5 refused %s (the recipe must build valid HDF5)\n", what.c_str());
  std::abort();
}

hid_t ok(hid_t id, const std::string& what) {
  if (id < 0) recipe_failed(what);
  return id;
}

// Closes any identifier it owns (files, groups, datasets, types, lists).
struct Id {
  hid_t id = -1;
  Id(hid_t i, const std::string& what) : id(ok(i, what)) {}
  ~Id() {
    if (id >= 0) H5Idec_ref(id);
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  operator hid_t() const { return id; }
};

// How an object departs from what RunWriter writes. Most inputs keep most
// objects as written, so that the reader gets far enough to check the rest.
enum class Layout {
  as_written,
  absent,
  scalar,           // rank 0: one value
  other_rows,       // a row count of its own (0 .. rows + 3)
  huge_rows,        // 2^20 .. 2^62 rows, nothing written (a corrupt extent)
  extra_axis,       // one more axis
  other_row_shape,  // the last axis one longer or shorter
  as_strings,       // a string type where numbers belong
  as_other_number,  // floats for integers, integers for floats
};

Layout pick_layout(FuzzedDataProvider& in) {
  const int v = in.ConsumeIntegral<std::uint8_t>();
  if (v < 240) return Layout::as_written;
  return static_cast<Layout>(1 + (v - 240) % 8);
}

// Values a lossy or careless path would stumble on.
double pick_double(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 9)) {
    case 0: return std::numeric_limits<double>::quiet_NaN();
    case 1: return std::numeric_limits<double>::infinity();
    case 2: return -std::numeric_limits<double>::infinity();
    case 3: return std::numeric_limits<double>::max();
    case 4: return std::numeric_limits<double>::denorm_min();
    case 5: return -0.0;
    case 6: return in.ConsumeFloatingPoint<double>();
    default: return in.ConsumeIntegralInRange<int>(-2, 12) * 0.25;
  }
}

std::int64_t pick_int(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 9)) {
    case 0: return std::numeric_limits<std::int64_t>::max();
    case 1: return std::numeric_limits<std::int64_t>::min();
    case 2: return -1;
    case 3: return std::int64_t{1} << in.ConsumeIntegralInRange<int>(31, 62);
    case 4: return in.ConsumeIntegral<std::int64_t>();
    default: return in.ConsumeIntegralInRange<int>(0, 8);
  }
}

// With probability about 1/8, a value of the fuzzer's choosing instead.
// (Throughout, a choice of 0, which is what an exhausted input gives, means
// "as RunWriter writes it".)
template <class T>
T perhaps_corrupt(FuzzedDataProvider& in, T meant) {
  if (in.ConsumeIntegralInRange<int>(0, 7) != 7) return meant;
  if constexpr (std::is_floating_point_v<T>) return pick_double(in);
  else return static_cast<T>(pick_int(in));
}

template <class T>
hid_t memory_type() {
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  else if constexpr (std::is_same_v<T, std::int64_t>) return H5T_NATIVE_INT64;
  else if constexpr (std::is_same_v<T, std::uint64_t>) return H5T_NATIVE_UINT64;
  else if constexpr (std::is_same_v<T, std::int32_t>) return H5T_NATIVE_INT32;
  else return H5T_NATIVE_UINT8;
}

hsize_t product(const std::vector<hsize_t>& dims) {
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  return n;
}

// A dataset `name` meant to be `dims` of `file_type` holding `values`
// (row-major, product(dims) of them), laid out as the fuzzer picks. Time
// series are chunked and extendible like the writer's; `compressed` adds its
// shuffle and deflate filters.
template <class T>
void put_numbers(FuzzedDataProvider& in, hid_t loc, const char* name, hid_t file_type, std::vector<hsize_t> dims,
                 std::vector<T> values, bool compressed = false) {
  const Layout layout = pick_layout(in);
  if (layout == Layout::absent) return;
  bool write = true;
  hid_t ftype = file_type;
  switch (layout) {
    case Layout::scalar: dims.clear(); break;
    case Layout::other_rows:
      if (!dims.empty()) dims[0] = in.ConsumeIntegralInRange<hsize_t>(0, dims[0] + 3);
      break;
    case Layout::huge_rows:
      if (!dims.empty()) dims[0] = hsize_t{1} << in.ConsumeIntegralInRange<int>(20, 62), write = false;
      break;
    case Layout::extra_axis: dims.push_back(in.ConsumeIntegralInRange<hsize_t>(1, 3)); break;
    case Layout::other_row_shape:
      if (dims.size() >= 2) dims.back() = in.ConsumeBool() || dims.back() == 0 ? dims.back() + 1 : dims.back() - 1;
      else dims.push_back(2);
      break;
    case Layout::as_strings: write = false; break;
    case Layout::as_other_number:
      ftype = H5Tget_class(file_type) == H5T_FLOAT ? H5T_STD_I64LE : H5T_IEEE_F64LE;
      break;
    default: break;
  }
  // A huge extent times its row shape must still be a valid HDF5 extent:
  // under 2^62 bytes in all.
  if (layout == Layout::huge_rows) {
    const hsize_t row_bytes = 8 * std::max<hsize_t>(1, product({dims.begin() + 1, dims.end()}));
    dims[0] = std::min(dims[0], (hsize_t{1} << 62) / row_bytes);
  }

  Id string4(H5Tcopy(H5T_C_S1), "string type");
  H5Tset_size(string4, 4);
  if (layout == Layout::as_strings) ftype = string4;

  const bool series = !dims.empty();
  std::vector<hsize_t> maxdims = dims, chunk = dims;
  Id dcpl(H5Pcreate(H5P_DATASET_CREATE), "dcpl");
  if (series) {
    maxdims[0] = H5S_UNLIMITED;
    chunk[0] = 64;
    for (hsize_t& c : chunk) c = c == 0 ? 1 : c;
    ok(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), std::string("chunk ") + name);
    if (compressed && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
      H5Pset_shuffle(dcpl);
      H5Pset_deflate(dcpl, 1);
    }
  }
  Id space(series ? H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data())
                  : H5Screate(H5S_SCALAR),
           std::string("dataspace of ") + name);
  Id d(H5Dcreate2(loc, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), std::string("create ") + name);
  const hsize_t count = product(dims);
  if (!write || count == 0) return;
  values.resize(count);  // a changed shape keeps the values it has, zeros after
  ok(H5Dwrite(d, memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), std::string("write ") + name);
}

// A scalar string attribute or dataset, as the writer stores it (fixed
// length) or as another H5MD writer may (variable length), or not a single
// string at all.
void put_string(FuzzedDataProvider& in, hid_t loc, const char* name, const std::string& value, bool as_dataset) {
  enum { fixed_length, variable_length, absent, a_number, two_strings };
  int form = in.ConsumeIntegralInRange<int>(0, 31);
  if (form > two_strings) form = fixed_length;
  if (form == absent) return;
  Id type(H5Tcopy(form == a_number ? H5T_STD_I32LE : H5T_C_S1), "string type");
  if (form == fixed_length || form == two_strings) H5Tset_size(type, value.size() + 1);
  if (form == variable_length) H5Tset_size(type, H5T_VARIABLE);
  if (form != a_number) H5Tset_cset(type, H5T_CSET_UTF8);
  const hsize_t two = 2;
  Id space(form == two_strings ? H5Screate_simple(1, &two, nullptr) : H5Screate(H5S_SCALAR), "string space");
  const std::string what = std::string("string ") + name;
  const hid_t obj = as_dataset ? H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)
                               : H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  Id o(obj, what);
  const std::string twice = value + '\0' + value;
  const char* text = value.c_str();
  const int number = 7;
  const void* buf = form == variable_length ? static_cast<const void*>(&text)
                    : form == a_number      ? static_cast<const void*>(&number)
                    : form == two_strings   ? static_cast<const void*>(twice.c_str())
                                            : static_cast<const void*>(value.c_str());
  ok(as_dataset ? H5Dwrite(o, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) : H5Awrite(o, type, buf), what);
}

// The groups of the file, open until it is complete. A group the fuzzer
// drops is -1, and whatever would have gone into it is skipped.
struct Groups {
  FuzzedDataProvider& in;
  std::vector<std::unique_ptr<Id>> open;
  hid_t make(hid_t loc, const char* name) {
    if (loc < 0 || in.ConsumeIntegralInRange<int>(0, 31) == 31) return -1;
    open.push_back(std::make_unique<Id>(H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                        std::string("group ") + name));
    return *open.back();
  }
};

// /h5md's version attribute: two int32 [1, minor], or another version,
// another count, a scalar, a float, or none.
void put_version(FuzzedDataProvider& in, hid_t h5md) {
  int form = in.ConsumeIntegralInRange<int>(0, 31);
  if (form > 5) form = 0;
  if (form == 1) return;
  const int values[3] = {form == 2 ? in.ConsumeIntegralInRange<int>(-1, 3) : 1, in.ConsumeIntegralInRange<int>(0, 2), 0};
  const hsize_t count = form == 3 ? 3 : 2;
  Id space(form == 4 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr), "version space");
  Id a(H5Acreate2(h5md, "version", form == 5 ? H5T_IEEE_F64LE : H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT),
       "version");
  ok(H5Awrite(a, H5T_NATIVE_INT, values), "write version");
}

std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// The scene of the header (radius and mass per ball, walls), spread out so
// that nothing overlaps, or one that disagrees with it, or any text.
std::string scene_json(FuzzedDataProvider& in, const std::vector<double>& radius, const std::vector<double>& mass,
                       const std::vector<double>& walls) {
  const int variant = in.ConsumeIntegralInRange<int>(0, 11);
  if (variant == 11) return in.ConsumeRandomLengthString(256);
  std::size_t balls = radius.size();
  if (variant == 10) balls = balls > 0 && in.ConsumeBool() ? balls - 1 : balls + 1;  // another ball count
  std::string s = R"({"name": "fuzz", "duration": 0.1, "balls": [)";
  for (std::size_t i = 0; i < balls; ++i) {
    const double r = i < radius.size() && std::isfinite(radius[i]) && radius[i] > 0 ? radius[i] : 0.5;
    const double m = i < mass.size() && std::isfinite(mass[i]) && mass[i] > 0 ? mass[i] : 1.0;
    s += std::string(i ? ", " : "") + R"({"position": [)" + number_text(10.0 * static_cast<double>(i) + 1e3 * r) +
         R"(, 0], "velocity": [1, 0], "radius": )" + number_text(variant == 9 ? r * 2 : r) +
         R"(, "mass": )" + number_text(m) + "}";
  }
  s += R"(], "walls": [)";
  for (std::size_t j = 0; j + 4 <= walls.size(); j += 4) {
    s += std::string(j ? ", " : "") + R"({"a": [)" + number_text(walls[j]) + ", " + number_text(walls[j + 1]) +
         R"(], "b": [)" + number_text(walls[j + 2]) + ", " + number_text(walls[j + 3]) + "]}";
  }
  return s + "]}";
}

std::string options_json(FuzzedDataProvider& in, const std::string& mode) {
  switch (in.ConsumeIntegralInRange<int>(0, 11)) {
    case 11: return in.ConsumeRandomLengthString(128);
    case 10: return R"({"engine": "event", "mode": ")" + mode + R"(", "method": "analytic"})";  // fields missing
    case 9: return R"({"engine": "event", "mode": ")" + mode +
                   R"(", "method": "analytic", "until": "soon", "dt": 0.02, "eps": 1e-9})";
    case 8: return R"({"engine": "warp", "mode": ")" + mode +
                   R"(", "method": "analytic", "until": -1, "dt": 0.02, "eps": 1e-9})";
    default:
      return R"({"engine": "event", "mode": ")" + mode +
             R"(", "method": "analytic", "until": -1, "dt": 0.02, "eps": 1e-9, "checkpoint_every": 0.05})";
  }
}

}  // namespace

void write_run_file_recipe(FuzzedDataProvider& in, const std::string& path) {
  const std::size_t n = (in.ConsumeIntegralInRange<std::size_t>(0, 4) + 1) % 5;  // 0 balls: the last choice
  const std::size_t n_walls = in.ConsumeIntegralInRange<std::size_t>(0, 3);
  const hsize_t frames = in.ConsumeIntegralInRange<hsize_t>(0, 5);
  const hsize_t events = in.ConsumeIntegralInRange<hsize_t>(0, 5);
  const hsize_t checkpoints = in.ConsumeIntegralInRange<hsize_t>(0, 3);
  const bool finished = in.ConsumeBool();
  const int mode_choice = in.ConsumeIntegralInRange<int>(0, 4);
  const std::string mode = mode_choice == 3 ? "fixed" : mode_choice == 4 ? in.ConsumeRandomLengthString(8) : "strict";
  const bool raw = (mode == "fixed") != (in.ConsumeIntegralInRange<int>(0, 7) == 7);

  std::vector<double> radius, mass, walls;
  for (std::size_t i = 0; i < n; ++i) {
    radius.push_back(perhaps_corrupt(in, 0.5 + 0.25 * static_cast<double>(i)));
    mass.push_back(perhaps_corrupt(in, 1.0 + static_cast<double>(i)));
  }
  for (std::size_t j = 0; j < n_walls; ++j) {
    const double y = -10.0 - static_cast<double>(j);
    for (double v : {0.0, y, 1.0 + static_cast<double>(j), y}) walls.push_back(perhaps_corrupt(in, v));
  }

  Id fapl(H5Pcreate(H5P_FILE_ACCESS), "fapl");
  if (in.ConsumeBool()) H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);
  Id file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "create the file");
  Groups g{in, {}};

  if (const hid_t h5md = g.make(file, "h5md"); h5md >= 0) {
    put_version(in, h5md);
    if (const hid_t author = g.make(h5md, "author"); author >= 0) put_string(in, author, "name", "fuzz", false);
    if (const hid_t creator = g.make(h5md, "creator"); creator >= 0) {
      put_string(in, creator, "name", "collide2d", false);
      put_string(in, creator, "version", "0.1.0", false);
    }
  }

  if (const hid_t balls = g.make(g.make(file, "particles"), "balls"); balls >= 0) {
    if (const hid_t position = g.make(balls, "position"); position >= 0) {
      std::vector<std::int64_t> step;
      std::vector<double> time;
      for (hsize_t k = 0; k < frames; ++k) {
        step.push_back(perhaps_corrupt(in, static_cast<std::int64_t>(k)));
        time.push_back(perhaps_corrupt(in, 0.02 * static_cast<double>(k)));
      }
      put_numbers(in, position, "step", H5T_STD_I64LE, {frames}, step);
      put_numbers(in, position, "time", H5T_IEEE_F64LE, {frames}, time);
      std::vector<double> xy(frames * n * 2);
      for (double& x : xy) x = perhaps_corrupt(in, 1.0);
      put_numbers(in, position, "value", H5T_IEEE_F64LE, {frames, n, 2}, xy);
    }
    if (const hid_t velocity = g.make(balls, "velocity"); velocity >= 0) {
      std::vector<double> v(frames * n * 2);
      for (double& x : v) x = perhaps_corrupt(in, 0.5);
      put_numbers(in, velocity, "value", H5T_IEEE_F64LE, {frames, n, 2}, v);
    }
    if (raw) {
      for (const char* name : {"position_raw", "velocity_raw"}) {
        const hid_t group = g.make(balls, name);
        if (group < 0) continue;
        std::vector<std::int64_t> words(frames * n * 4);
        for (std::int64_t& w : words) w = perhaps_corrupt(in, std::int64_t{1});
        put_numbers(in, group, "value", H5T_STD_I64LE, {frames, n, 2, 2}, words);
      }
    }
  }

  if (const hid_t observables = g.make(file, "observables"); observables >= 0) {
    if (const hid_t energy = g.make(observables, "energy"); energy >= 0) {
      std::vector<double> e(frames);
      for (double& x : e) x = perhaps_corrupt(in, 2.5);
      put_numbers(in, energy, "value", H5T_IEEE_F64LE, {frames}, e);
    }
    if (const hid_t hash = g.make(observables, "state_hash"); hash >= 0) {
      std::vector<std::uint64_t> h(frames);
      for (std::uint64_t& x : h) x = perhaps_corrupt(in, std::uint64_t{0xcbf29ce484222325ULL});
      put_numbers(in, hash, "value", H5T_STD_U64LE, {frames}, h);
    }
    if (finished) put_string(in, observables, "summary", R"({"events": 0})", true);
  }

  if (const hid_t ev = g.make(file, "events"); ev >= 0) {
    const bool compressed = in.ConsumeBool();
    std::vector<double> time, impulse;
    std::vector<std::int32_t> kind, a, b;
    for (hsize_t k = 0; k < events; ++k) {
      const bool with_wall = n_walls > 0 && (n < 2 || in.ConsumeBool());
      time.push_back(perhaps_corrupt(in, 0.01 * static_cast<double>(k)));
      kind.push_back(perhaps_corrupt(in, with_wall ? 1 : 0));
      a.push_back(perhaps_corrupt(in, 0));
      b.push_back(perhaps_corrupt(in, with_wall ? 0 : 1));
      impulse.push_back(perhaps_corrupt(in, 1.0));
    }
    put_numbers(in, ev, "time", H5T_IEEE_F64LE, {events}, time, compressed);
    put_numbers(in, ev, "kind", H5T_STD_I32LE, {events}, kind, compressed);
    put_numbers(in, ev, "a", H5T_STD_I32LE, {events}, a, compressed);
    put_numbers(in, ev, "b", H5T_STD_I32LE, {events}, b, compressed);
    put_numbers(in, ev, "impulse", H5T_IEEE_F64LE, {events}, impulse, compressed);
  }

  if (const hid_t parameters = g.make(file, "parameters"); parameters >= 0) {
    put_string(in, parameters, "scene_json", scene_json(in, radius, mass, walls), true);
    put_string(in, parameters, "options_json", options_json(in, mode), true);
    put_string(in, parameters, "mode", mode, false);
    put_string(in, parameters, "compiler", "clang", false);
    put_numbers(in, parameters, "radius", H5T_IEEE_F64LE, {n}, radius);
    put_numbers(in, parameters, "mass", H5T_IEEE_F64LE, {n}, mass);
    put_numbers(in, parameters, "walls", H5T_IEEE_F64LE, {n_walls, 4}, walls);
    if (in.ConsumeBool()) {
      std::vector<double> e(n_walls);
      for (double& x : e) x = perhaps_corrupt(in, 0.9);
      put_numbers(in, parameters, "wall_restitution", H5T_IEEE_F64LE, {n_walls}, e);
    }
  }

  // Checkpoint records as RunWriter::checkpoint makes them: counts that grow,
  // each engine state beside the previous one (or at 0 when it fits there).
  if (const hid_t cp = g.make(file, "checkpoint"); cp >= 0) {
    std::vector<double> time;
    std::vector<std::int64_t> frames_written, events_written, offset, size;
    std::int64_t state_offset = 0, state_size = 0, state_bytes = 0;
    for (hsize_t k = 0; k < checkpoints; ++k) {
      const std::int64_t s = in.ConsumeIntegralInRange<std::int64_t>(0, 24);
      const std::int64_t at = s <= state_offset ? 0 : state_offset + state_size;
      state_offset = at, state_size = s, state_bytes = std::max(state_bytes, at + s);
      time.push_back(perhaps_corrupt(in, 0.05 * static_cast<double>(k + 1)));
      frames_written.push_back(perhaps_corrupt(in, static_cast<std::int64_t>(frames * (k + 1) / checkpoints)));
      events_written.push_back(perhaps_corrupt(in, static_cast<std::int64_t>(events * (k + 1) / checkpoints)));
      offset.push_back(perhaps_corrupt(in, at));
      size.push_back(perhaps_corrupt(in, s));
    }
    put_numbers(in, cp, "time", H5T_IEEE_F64LE, {checkpoints}, time);
    put_numbers(in, cp, "frames_written", H5T_STD_I64LE, {checkpoints}, frames_written);
    put_numbers(in, cp, "events_written", H5T_STD_I64LE, {checkpoints}, events_written);
    put_numbers(in, cp, "engine_state_offset", H5T_STD_I64LE, {checkpoints}, offset);
    put_numbers(in, cp, "engine_state_size", H5T_STD_I64LE, {checkpoints}, size);
    std::vector<std::uint8_t> state(static_cast<std::size_t>(state_bytes));
    for (std::uint8_t& byte : state) byte = in.ConsumeIntegral<std::uint8_t>();
    put_numbers(in, cp, "engine_state", H5T_STD_U8LE, {static_cast<hsize_t>(state_bytes)}, state);
  }
}

}  // namespace collide2d::fuzz
