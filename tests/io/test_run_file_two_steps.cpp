// A run file made in two steps (RunWriter::with_scene_text, then
// write_header), as `collide2d run` makes it for a scene file: the same file,
// object for object and byte for byte, as the one-step writer's; nothing
// appended before the header; nothing left behind when the header never comes.
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <vector>

#include "run_file_fixtures.hpp"

using namespace collide2d;
using namespace collide2d::test_io;

namespace {

// Every object of a file by path, with its datasets' and attributes' bytes as
// stored (the run file's strings are fixed-length, so bytes compare them).
using FileBytes = std::map<std::string, std::vector<char>>;

std::vector<char> bytes_of_dataset(hid_t d) {
  const hid_t type = H5Dget_type(d);
  const hid_t space = H5Dget_space(d);
  const hssize_t points = H5Sget_simple_extent_npoints(space);
  std::vector<char> bytes(static_cast<std::size_t>(points) * H5Tget_size(type));
  if (!bytes.empty()) REQUIRE(H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) >= 0);
  H5Sclose(space);
  H5Tclose(type);
  return bytes;
}

herr_t add_attribute(hid_t loc, const char* name, const H5A_info_t*, void* out) {
  auto& entry = *static_cast<std::pair<std::string, FileBytes*>*>(out);
  const hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  const hid_t type = H5Aget_type(a);
  const hid_t space = H5Aget_space(a);
  std::vector<char> bytes(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)) * H5Tget_size(type));
  if (!bytes.empty()) H5Aread(a, type, bytes.data());
  (*entry.second)[entry.first + "@" + name] = bytes;
  H5Sclose(space);
  H5Tclose(type);
  H5Aclose(a);
  return 0;
}

herr_t add_object(hid_t file, const char* name, const H5O_info_t* info, void* out) {
  FileBytes& all = *static_cast<FileBytes*>(out);
  const hid_t object = H5Oopen(file, name, H5P_DEFAULT);
  all[name] = info->type == H5O_TYPE_DATASET ? bytes_of_dataset(object) : std::vector<char>{};
  std::pair<std::string, FileBytes*> entry{name, &all};
  H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, nullptr, add_attribute, &entry);
  H5Oclose(object);
  return 0;
}

FileBytes file_bytes(const std::string& path) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  FileBytes all;
  REQUIRE(H5Ovisit(f, H5_INDEX_NAME, H5_ITER_INC, add_object, &all) >= 0);
  H5Fclose(f);
  return all;
}

}  // namespace

TEST_CASE("run file in two steps: the same objects and bytes as in one", "[io]") {
  TempDir tmp;
  const std::size_t n = 3;
  for (const std::string mode : {"strict", "fixed"}) {
    const bool raw = mode == "fixed";
    const RunHeader header = make_header(n, mode);
    const std::string one = tmp / ("one_" + mode + ".h5"), two = tmp / ("two_" + mode + ".h5");
    {
      RunWriter w(one, header);
      append(w, n, 0, 150, 0, 9000, raw);
      w.checkpoint(make_checkpoint(1.5, 100, 1));
      w.finish(R"({"events": 9000})");
    }
    {
      RunWriter w = RunWriter::with_scene_text(two, header.scene_json);
      RunHeader without_text = header;
      without_text.scene_json = "not this: write_header takes the text already written";
      w.write_header(without_text);
      append(w, n, 0, 150, 0, 9000, raw);
      w.checkpoint(make_checkpoint(1.5, 100, 1));
      w.finish(R"({"events": 9000})");
    }
    const FileBytes a = file_bytes(one), b = file_bytes(two);
    CHECK(a.size() > 30);  // the whole H5MD layout, not an empty visit
    for (const auto& [name, bytes] : a) {
      INFO(mode << " " << name);
      REQUIRE(b.count(name) == 1);
      CHECK(b.at(name) == bytes);
    }
    CHECK(b.size() == a.size());
    const RunContents run = read_run_file(two);
    require_same_header(run.header, header);
    require_content(run, n, 150, 9000, raw);
  }
}

TEST_CASE("run file in two steps: nothing goes in before the header", "[io]") {
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  const std::size_t n = 2;
  RunWriter w = RunWriter::with_scene_text(path, make_header(n).scene_json);
  CHECK_THROWS_AS(w.append_frame(make_frame(0, n)), RunFileError);
  CHECK_THROWS_AS(w.append_event(make_event(0)), RunFileError);
  CHECK_THROWS_AS(w.checkpoint(make_checkpoint(0.5, 10, 1)), RunFileError);
  CHECK_THROWS_AS(w.finish("{}"), RunFileError);
  w.write_header(make_header(n));
  CHECK_THROWS_AS(w.write_header(make_header(n)), RunFileError);  // once only
  append(w, n, 0, 3, 0, 3);
  w.finish("{}");
  require_content(read_run_file(path), n, 3, 3);
}

TEST_CASE("run file in two steps: a writer dropped before its header leaves nothing", "[io]") {
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  {
    RunWriter w = RunWriter::with_scene_text(path, make_header(2).scene_json);
    CHECK(fs::exists(path + ".partial"));
  }
  CHECK(fs::is_empty(tmp.dir));
}
