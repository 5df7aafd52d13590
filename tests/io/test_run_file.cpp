// The H5MD run file: exact round trip, H5MD layout, no stray files, clear
// errors on bad files and paths, and h5py reading the result.
#include <catch2/catch.hpp>

#include "run_file_fixtures.hpp"

using namespace collide2d;
using namespace collide2d::test_io;

TEST_CASE("run file: a finished run reads back bit for bit", "[io]") {
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  const std::size_t n = 3;
  {
    RunWriter w(path, make_header(n));
    CHECK(w.partial_path() == path + ".partial");
    append(w, n, 0, 150, 0, 9000);  // past several frame chunks and two event chunks
    w.checkpoint(make_checkpoint(1.5, 100, 1));
    CHECK(fs::exists(path + ".partial"));
    CHECK_FALSE(fs::exists(path));
    w.finish(R"({"events": 9000})");
  }
  CHECK(fs::exists(path));
  CHECK_FALSE(fs::exists(path + ".partial"));
  const RunContents run = read_run_file(path);
  CHECK(run.finished);
  CHECK(run.summary_json == R"({"events": 9000})");
  require_same_header(run.header, make_header(n));
  require_content(run, n, 150, 9000);
  REQUIRE(run.last_checkpoint);
  CHECK(run.last_checkpoint->frames_written == 150);
  CHECK(run.last_checkpoint->engine_state == make_checkpoint(1.5, 100, 1).engine_state);
}

TEST_CASE("run file: layout is H5MD 1.1 as SPEC.md lists it", "[io]") {
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  const std::size_t n = 4;
  {
    RunWriter w(path, make_header(n));
    append(w, n, 0, 70, 0, 5);
    w.finish("{}");
  }
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  {
    const hid_t attr = H5Aopen_by_name(f, "/h5md", "version", H5P_DEFAULT, H5P_DEFAULT);
    REQUIRE(attr >= 0);
    int version[2] = {0, 0};
    REQUIRE(H5Aread(attr, H5T_NATIVE_INT, version) >= 0);
    CHECK(version[0] == 1);
    CHECK(version[1] == 1);
    H5Aclose(attr);
  }
  CHECK(read_string_attr(f, "/h5md/author", "name") == "tester");
  CHECK(read_string_attr(f, "/h5md/creator", "name") == "collide2d");
  CHECK(read_string_attr(f, "/h5md/creator", "version") == "0.1.0");
  {
    const hid_t attr = H5Aopen_by_name(f, "/particles/balls/box", "dimension", H5P_DEFAULT, H5P_DEFAULT);
    int dimension = 0;
    REQUIRE(H5Aread(attr, H5T_NATIVE_INT, &dimension) >= 0);
    CHECK(dimension == 2);
    H5Aclose(attr);
    const hid_t boundary = H5Aopen_by_name(f, "/particles/balls/box", "boundary", H5P_DEFAULT, H5P_DEFAULT);
    const hid_t type = H5Aget_type(boundary);
    REQUIRE(H5Tget_class(type) == H5T_STRING);
    const std::size_t size = H5Tget_size(type);
    std::vector<char> buf(2 * size);
    REQUIRE(H5Aread(boundary, type, buf.data()) >= 0);
    CHECK(std::string(buf.data()) == "none");
    CHECK(std::string(buf.data() + size) == "none");
    H5Tclose(type);
    H5Aclose(boundary);
  }
  // Every time series: its value shape and type, and step/time alongside.
  struct Expect {
    const char* group;
    std::vector<hsize_t> dims;
    H5T_class_t cls;
    std::size_t size;
    H5T_sign_t sign;
  };
  const std::vector<Expect> series = {
      {"/particles/balls/position", {70, n, 2}, H5T_FLOAT, 8, H5T_SGN_ERROR},
      {"/particles/balls/velocity", {70, n, 2}, H5T_FLOAT, 8, H5T_SGN_ERROR},
      {"/observables/energy", {70}, H5T_FLOAT, 8, H5T_SGN_ERROR},
      {"/observables/state_hash", {70}, H5T_INTEGER, 8, H5T_SGN_NONE},
  };
  auto check_dataset = [&](const std::string& name, const std::vector<hsize_t>& dims, H5T_class_t cls,
                           std::size_t size, H5T_sign_t sign) {
    INFO(name);
    const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
    REQUIRE(d >= 0);
    const hid_t space = H5Dget_space(d);
    std::vector<hsize_t> got(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
    H5Sget_simple_extent_dims(space, got.data(), nullptr);
    CHECK(got == dims);
    const hid_t type = H5Dget_type(d);
    CHECK(H5Tget_class(type) == cls);
    CHECK(H5Tget_size(type) == size);
    if (cls == H5T_INTEGER) CHECK(H5Tget_sign(type) == sign);
    H5Tclose(type);
    H5Sclose(space);
    H5Dclose(d);
  };
  for (const Expect& e : series) {
    check_dataset(std::string(e.group) + "/value", e.dims, e.cls, e.size, e.sign);
    check_dataset(std::string(e.group) + "/step", {70}, H5T_INTEGER, 8, H5T_SGN_2);
    check_dataset(std::string(e.group) + "/time", {70}, H5T_FLOAT, 8, H5T_SGN_ERROR);
  }
  check_dataset("/events/time", {5}, H5T_FLOAT, 8, H5T_SGN_ERROR);
  check_dataset("/events/impulse", {5}, H5T_FLOAT, 8, H5T_SGN_ERROR);
  for (const char* name : {"/events/kind", "/events/a", "/events/b"}) check_dataset(name, {5}, H5T_INTEGER, 4, H5T_SGN_2);
  check_dataset("/parameters/radius", {n}, H5T_FLOAT, 8, H5T_SGN_ERROR);
  check_dataset("/parameters/mass", {n}, H5T_FLOAT, 8, H5T_SGN_ERROR);
  check_dataset("/parameters/walls", {2, 4}, H5T_FLOAT, 8, H5T_SGN_ERROR);
  for (const char* name : {"/parameters/scene_json", "/parameters/options_json", "/observables/summary"})
    CHECK(H5Lexists(f, name, H5P_DEFAULT) > 0);
  CHECK(read_string_attr(f, "/parameters", "mode") == "strict");
  CHECK(read_string_attr(f, "/parameters", "compiler") == "gcc 12");
  H5Fclose(f);
}

TEST_CASE("run file: a writer dropped without finish or checkpoint leaves nothing", "[io]") {
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  {
    RunWriter w(path, make_header(2));
    append(w, 2, 0, 100, 0, 10);
    CHECK(fs::exists(path + ".partial"));
  }
  CHECK_FALSE(fs::exists(path));
  CHECK_FALSE(fs::exists(path + ".partial"));
  CHECK(fs::is_empty(tmp.dir));
}

TEST_CASE("run file: a writer dropped after a checkpoint leaves a resumable partial file", "[io]") {
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  {
    RunWriter w(path, make_header(2));
    append(w, 2, 0, 40, 0, 30);
    w.checkpoint(make_checkpoint(0.8, 10, 7));
    append(w, 2, 40, 50, 30, 35);
  }
  CHECK_FALSE(fs::exists(path));
  const RunContents run = read_run_file(path + ".partial");
  CHECK_FALSE(run.finished);
  require_content(run, 2, 40, 30);  // what the checkpoint made durable
  REQUIRE(run.last_checkpoint);
  CHECK(run.last_checkpoint->events_written == 30);
}

TEST_CASE("run file: bad files give RunFileError naming the file", "[io]") {
  TempDir tmp;
  const std::string good = tmp / "good.h5";
  {
    RunWriter w(good, make_header(2));
    append(w, 2, 0, 200, 0, 500);
    w.finish("{}");
  }
  auto write_bytes = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(tmp / name, std::ios::binary) << bytes;
    return tmp / name;
  };
  std::ifstream in(good, std::ios::binary);
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::vector<std::string> bad = {
      tmp / "missing.h5",
      write_bytes("empty.h5", ""),
      write_bytes("garbage.h5", std::string(5000, 'x')),
      write_bytes("half.h5", content.substr(0, content.size() / 2)),
      write_bytes("head.h5", content.substr(0, 100)),
      write_bytes("tail_cut.h5", content.substr(0, content.size() - 10)),
  };
  for (const std::string& path : bad) {
    INFO(path);
    const std::string message = error_of([&] { read_run_file(path); });
    CHECK(message.find(path) != std::string::npos);
  }
  // A valid HDF5 file that is not a run file.
  const std::string foreign = tmp / "foreign.h5";
  H5Fclose(H5Fcreate(foreign.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  CHECK(error_of([&] { read_run_file(foreign); }).find("no /h5md") != std::string::npos);
}

TEST_CASE("run file: an unwritable path or a bad frame gives RunFileError", "[io]") {
  TempDir tmp;
  const std::string path = tmp / "no/such/dir/run.h5";
  const std::string message = error_of([&] { RunWriter w(path, make_header(2)); });
  CHECK(message.find(path) != std::string::npos);
  CHECK_FALSE(error_of([&] { RunWriter w(tmp / "x.h5", RunHeader{}); }).empty());  // no balls
  RunWriter w(tmp / "y.h5", make_header(2));
  FrameRecord short_frame = make_frame(0, 1);
  CHECK(error_of([&] { w.append_frame(short_frame); }).find("2*2") != std::string::npos);
}

TEST_CASE("run file: h5py reads a finished file", "[io][h5py]") {
  if (std::system("/usr/bin/python3 -c 'import h5py' >/dev/null 2>&1") != 0) {
    WARN("python3 with h5py is not installed: skipped");
    return;
  }
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  {
    RunWriter w(path, make_header(3));
    append(w, 3, 0, 7, 0, 4);
    w.finish("{}");
  }
  const std::string script =
      "import h5py, sys\n"
      "f = h5py.File(sys.argv[1], 'r')\n"
      "v = f['/particles/balls/position/value'][...]\n"
      "assert v.shape == (7, 3, 2), v.shape\n"
      "assert v[2, 1, 0] == 0.1 * 2 + 1.0 / (3.0 + 2), v[2, 1, 0]\n"
      "assert list(f['/h5md'].attrs['version']) == [1, 1]\n"
      "assert f['/h5md/creator'].attrs['name'] in (b'collide2d', 'collide2d')\n"
      "assert f['/events/kind'].shape == (4,)\n";
  const std::string script_path = tmp / "check.py";
  std::ofstream(script_path) << script;
  CHECK(std::system(("/usr/bin/python3 " + script_path + " " + path).c_str()) == 0);
}
