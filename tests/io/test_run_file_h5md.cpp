// The run file's H5MD conventions beyond SPEC.md's minimum: per-particle mass
// and radius, described event and wall columns, the units statement, UTF-8
// strings, compressed events; and files written before these existed.
#include <catch2/catch.hpp>

#include "run_file_fixtures.hpp"

using namespace collide2d;
using namespace collide2d::test_io;

namespace {

std::string finished_run(const TempDir& tmp, std::size_t n) {
  const std::string path = tmp / "run.h5";
  RunWriter w(path, make_header(n));
  append(w, n, 0, 20, 0, 3000);  // past two event chunks: compressed whole and in part
  w.finish("{}");
  return path;
}

std::vector<double> read_doubles(hid_t file, const char* path) {
  const hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  REQUIRE(d >= 0);
  const hid_t space = H5Dget_space(d);
  std::vector<double> out(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  REQUIRE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0);
  H5Sclose(space);
  H5Dclose(d);
  return out;
}

// A 1-D attribute of fixed-length strings, and whether it is UTF-8.
std::vector<std::string> read_string_list(hid_t file, const char* obj, const char* name, bool& utf8) {
  const hid_t attr = H5Aopen_by_name(file, obj, name, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(attr >= 0);
  const hid_t type = H5Aget_type(attr), space = H5Aget_space(attr);
  utf8 = H5Tget_cset(type) == H5T_CSET_UTF8;
  const std::size_t size = H5Tget_size(type), count = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
  std::vector<char> buf(size * count + 1, '\0');
  REQUIRE(H5Aread(attr, type, buf.data()) >= 0);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < count; ++i) out.emplace_back(buf.data() + i * size, strnlen(buf.data() + i * size, size));
  H5Sclose(space);
  H5Tclose(type);
  H5Aclose(attr);
  return out;
}

bool is_utf8_string(hid_t file, const char* obj, const char* attribute) {
  const hid_t o = attribute ? H5Aopen_by_name(file, obj, attribute, H5P_DEFAULT, H5P_DEFAULT)
                            : H5Dopen2(file, obj, H5P_DEFAULT);
  REQUIRE(o >= 0);
  const hid_t type = attribute ? H5Aget_type(o) : H5Dget_type(o);
  const bool utf8 = H5Tget_class(type) == H5T_STRING && H5Tget_cset(type) == H5T_CSET_UTF8;
  H5Tclose(type);
  attribute ? H5Aclose(o) : H5Dclose(o);
  return utf8;
}

}  // namespace

TEST_CASE("run file: per-particle mass and radius, described columns, units stated", "[io]") {
  TempDir tmp;
  const std::size_t n = 3;
  const std::string path = finished_run(tmp, n);
  const RunHeader header = make_header(n);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  CHECK(same_bits(read_doubles(f, "/particles/balls/mass"), header.mass));
  CHECK(same_bits(read_doubles(f, "/particles/balls/radius"), header.radius));
  CHECK(same_bits(read_doubles(f, "/parameters/wall_restitution"), header.wall_restitution));
  bool utf8 = false;
  CHECK(read_string_list(f, "/events/kind", "labels", utf8) == std::vector<std::string>{"ball-ball", "ball-wall"});
  CHECK(utf8);
  CHECK(read_string_list(f, "/parameters/walls", "columns", utf8) == std::vector<std::string>{"ax", "ay", "bx", "by"});
  CHECK(utf8);
  for (const char* obj : {"/events/time", "/events/kind", "/events/a", "/events/b", "/events/impulse", "/parameters/walls"})
    CHECK_FALSE(read_string_attr(f, obj, "description").empty());
  CHECK(read_string_attr(f, "/particles/balls", "units").find("scene's own units") != std::string::npos);
  CHECK(read_string_attr(f, "/parameters", "units") == read_string_attr(f, "/particles/balls", "units"));
  // No H5MD unit attribute anywhere: the scene does not say what its units are.
  CHECK(H5Aexists_by_name(f, "/particles/balls/position/value", "unit", H5P_DEFAULT) == 0);
  CHECK(H5Aexists_by_name(f, "/particles/balls/position/time", "unit", H5P_DEFAULT) == 0);
  // Every string is UTF-8, as H5MD asks.
  CHECK(is_utf8_string(f, "/parameters/scene_json", nullptr));
  CHECK(is_utf8_string(f, "/observables/summary", nullptr));
  CHECK(is_utf8_string(f, "/h5md/creator", "name"));
  CHECK(is_utf8_string(f, "/particles/balls/box", "boundary"));
  CHECK(is_utf8_string(f, "/particles/balls", "units"));
  H5Fclose(f);
}

TEST_CASE("run file: events are chunked, shuffled and deflated but for impulses, and frames are not", "[io]") {
  TempDir tmp;
  const std::string path = finished_run(tmp, 2);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  auto filters = [&](const char* name) {
    const hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    const hid_t dcpl = H5Dget_create_plist(d);
    CHECK(H5Pget_layout(dcpl) == H5D_CHUNKED);
    std::vector<H5Z_filter_t> ids;
    for (int i = 0; i < H5Pget_nfilters(dcpl); ++i) {
      unsigned flags = 0, info = 0;
      std::size_t n_values = 0;
      ids.push_back(H5Pget_filter2(dcpl, static_cast<unsigned>(i), &flags, &n_values, nullptr, 0, nullptr, &info));
    }
    H5Pclose(dcpl);
    H5Dclose(d);
    return ids;
  };
  for (const char* name : {"/events/time", "/events/kind", "/events/a", "/events/b"}) {
    INFO(name);
    CHECK(filters(name) == std::vector<H5Z_filter_t>{H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE});
  }
  // Impulses are doubles deflate cannot shrink (91 % of their size): stored as they are.
  CHECK(filters("/events/impulse").empty());
  CHECK(filters("/particles/balls/position/value").empty());
  H5Fclose(f);
  const RunContents run = read_run_file(path);
  require_content(run, 2, 20, 3000);  // lossless
}

TEST_CASE("run file: a file without mass, radius and wall restitution (older writers) reads back", "[io]") {
  TempDir tmp;
  const std::size_t n = 3;
  const std::string path = finished_run(tmp, n);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  REQUIRE(f >= 0);
  for (const char* name : {"/particles/balls/mass", "/particles/balls/radius", "/parameters/wall_restitution"})
    REQUIRE(H5Ldelete(f, name, H5P_DEFAULT) >= 0);
  REQUIRE(H5Adelete_by_name(f, "/events/kind", "labels", H5P_DEFAULT) >= 0);
  H5Fclose(f);
  const RunContents run = read_run_file(path);
  CHECK(run.finished);
  CHECK(run.header.wall_restitution.empty());
  CHECK(same_bits(run.header.radius, make_header(n).radius));
  require_content(run, n, 20, 3000);
}

TEST_CASE("run file: wall restitution must match the walls", "[io]") {
  TempDir tmp;
  RunHeader header = make_header(2);
  header.wall_restitution.pop_back();
  CHECK(error_of([&] { RunWriter w(tmp / "run.h5", header); }).find("wall_restitution") != std::string::npos);
  header.wall_restitution.clear();  // none at all: written without it
  {
    RunWriter w(tmp / "run.h5", header);
    w.finish("{}");
  }
  CHECK(read_run_file(tmp / "run.h5").header.wall_restitution.empty());
}
