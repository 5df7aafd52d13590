// The outcome record (outcome_record.cpp): two fake outcomes appended to a
// temporary file read back field by field with the HDF5 C API.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "collide2d/io/run_file_hdf5.hpp"
#include "outcome_record.hpp"

using namespace collide2d::properties;
namespace h5 = collide2d::h5;

namespace {

// Sets an environment variable for the life of the object, then restores it.
struct ScopedEnv {
  std::string name;
  std::string old;
  bool had = false;
  ScopedEnv(const char* n, const std::string& value) : name(n) {
    if (const char* v = std::getenv(n)) had = true, old = v;
    setenv(n, value.c_str(), 1);
  }
  ~ScopedEnv() { had ? (void)setenv(name.c_str(), old.c_str(), 1) : (void)unsetenv(name.c_str()); }
};

PropertyOutcome fake_passing() {
  PropertyOutcome o;
  o.property = "energy is kept in elastic scenes";
  o.mode = "strict";
  o.seed = 18446744073709551557ull;  // needs all 64 bits
  o.max_success = 100;
  o.max_size = 100;
  o.cases = 100;
  o.discarded = 37;
  o.rejected = 2;
  o.discard_reasons = {{"restitution", 30}, {"no collision to judge", 7}};
  o.seconds = 1.25;
  o.distribution = {{"ball-wall, hit", 60}, {"ball-ball, no hit", 40}};
  return o;
}

PropertyOutcome fake_failing() {
  PropertyOutcome o;
  o.property = "bisection misses are classified";
  o.mode = "fixed";
  o.seed = 7;
  o.max_success = 1000;
  o.max_size = 50;
  o.cases = 12;
  o.failures = 1;
  o.gave_up = true;
  o.seconds = 0.5;
  o.counterexample = "ball_wall ball{p=(0, 1) v=(0, -1)}\n  ünïcode survives";
  return o;
}

template <class T>
T number_attribute(hid_t loc, const char* name, hid_t type) {
  h5::Hid a(H5Aopen(loc, name, H5P_DEFAULT), name);
  T value{};
  h5::check_ok(H5Aread(a, type, &value), name);
  return value;
}

// A variable-length UTF-8 string attribute (h5::read_string asks for ASCII).
std::string text_attribute(hid_t loc, const char* name) {
  h5::Hid a(H5Aopen(loc, name, H5P_DEFAULT), name);
  h5::Hid type(H5Tcopy(H5T_C_S1), "string type");
  h5::check_ok(H5Tset_size(type, H5T_VARIABLE), "string type");
  h5::check_ok(H5Tset_cset(type, H5T_CSET_UTF8), "string type");
  char* p = nullptr;
  h5::check_ok(H5Aread(a, type, &p), name);
  std::string s = p != nullptr ? p : "";
  H5free_memory(p);
  return s;
}

hsize_t links(hid_t g) {
  H5G_info_t info{};
  h5::check_ok(H5Gget_info(g, &info), "info");
  return info.nlinks;
}

}  // namespace

TEST_CASE("outcome record: two outcomes appended to a new file read back", "[outcome_record]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("collide2d_outcome_" + std::to_string(::getpid()) + ".h5");
  std::filesystem::remove(path);
  {
    ScopedEnv env("COLLIDE2D_PROPERTY_RECORD", path.string());
    ScopedEnv label("COLLIDE2D_PROPERTY_RUN_LABEL", "unit test");
    record_property_outcome(fake_passing());
    record_property_outcome(fake_failing());
  }
  REQUIRE(std::filesystem::exists(path));
  h5::QuietErrors quiet;
  h5::Hid file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open");
  CHECK(text_attribute(file, "format") == "collide2d property outcomes 1");
  h5::Hid runs = h5::group(file, "/runs", false);
  REQUIRE(links(runs) == 1);  // one process: one run
  h5::Hid run = h5::group(runs, "000000", false);
  CHECK(text_attribute(run, "label") == "unit test");
  CHECK(number_attribute<std::int32_t>(run, "cores", H5T_NATIVE_INT32) >= 1);
  CHECK(!text_attribute(run, "compiler").empty());
  CHECK(!text_attribute(run, "hostname").empty());
  REQUIRE(links(run) == 2);

  h5::Hid first = h5::group(run, "000000", false);
  CHECK(text_attribute(first, "property") == "energy is kept in elastic scenes");
  CHECK(text_attribute(first, "mode") == "strict");
  CHECK(number_attribute<std::uint64_t>(first, "seed", H5T_NATIVE_UINT64) == 18446744073709551557ull);
  CHECK(number_attribute<std::int32_t>(first, "cases", H5T_NATIVE_INT32) == 100);
  CHECK(number_attribute<std::int32_t>(first, "failures", H5T_NATIVE_INT32) == 0);
  CHECK(number_attribute<std::int32_t>(first, "judged", H5T_NATIVE_INT32) == 100);
  CHECK(number_attribute<std::int32_t>(first, "discarded", H5T_NATIVE_INT32) == 37);
  CHECK(number_attribute<std::int32_t>(first, "rejected", H5T_NATIVE_INT32) == 2);
  {
    h5::Hid reasons = h5::dataset(first, "discard_counts");
    REQUIRE(h5::shape(reasons) == std::vector<hsize_t>{2});
    std::int64_t r[2];
    h5::check_ok(H5Dread(reasons, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, r), "read discard counts");
    CHECK(r[0] == 7);   // "no collision to judge"
    CHECK(r[1] == 30);  // "restitution"
  }
  CHECK(number_attribute<double>(first, "seconds", H5T_NATIVE_DOUBLE) == 1.25);
  CHECK(text_attribute(first, "counterexample").empty());
  h5::Hid counts = h5::dataset(first, "distribution_counts");
  REQUIRE(h5::shape(counts) == std::vector<hsize_t>{2});
  std::int64_t c[2];
  h5::check_ok(H5Dread(counts, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, c), "read counts");
  // Sorted by tag: "ball-ball, no hit" before "ball-wall, hit".
  CHECK(c[0] == 40);
  CHECK(c[1] == 60);

  h5::Hid second = h5::group(run, "000001", false);
  CHECK(text_attribute(second, "property") == "bisection misses are classified");
  CHECK(number_attribute<std::int32_t>(second, "failures", H5T_NATIVE_INT32) == 1);
  CHECK(number_attribute<std::int32_t>(second, "gave_up", H5T_NATIVE_INT32) == 1);
  CHECK(number_attribute<std::int32_t>(second, "max_success", H5T_NATIVE_INT32) == 1000);
  CHECK(text_attribute(second, "counterexample") == fake_failing().counterexample);
  CHECK(h5::shape(h5::dataset(second, "distribution_tags")) == std::vector<hsize_t>{0});
  CHECK(h5::shape(h5::dataset(second, "discard_reasons")) == std::vector<hsize_t>{0});
  CHECK(number_attribute<std::int32_t>(second, "discarded", H5T_NATIVE_INT32) == 0);
  file.reset();
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + ".lock");
}

TEST_CASE("outcome record: an unwritable file is reported, never thrown", "[outcome_record]") {
  ScopedEnv env("COLLIDE2D_PROPERTY_RECORD", "/nonexistent-directory/outcomes.h5");
  CHECK_NOTHROW(record_property_outcome(fake_passing()));
}

// Hidden (not run by ctest directly): writes the two fake outcomes into the
// file named by COLLIDE2D_PROPERTY_RECORD, for tests of
// analysis/summarise_properties.py (tests/analysis/test_summarise_properties.sh).
TEST_CASE("outcome record: demo outcomes into COLLIDE2D_PROPERTY_RECORD", "[.outcome_demo]") {
  record_property_outcome(fake_passing());
  record_property_outcome(fake_failing());
}
