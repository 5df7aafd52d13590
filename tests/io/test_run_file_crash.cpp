// Crash safety of the run file under a real kill -9 (fork, SIGKILL), and
// resuming from the partial file it leaves.
#include <catch2/catch.hpp>

#include "run_file_fixtures.hpp"

using namespace collide2d;
using namespace collide2d::test_io;

TEST_CASE("run file: kill -9 after a checkpoint keeps all up to it and resume completes the run", "[io][crash]") {
  TempDir tmp;
  const std::size_t n = 2000;  // 16 frames per chunk: many chunks and index blocks in flight at the kill
  const std::int64_t total_frames = 300, total_events = 20000;
  const std::string reference = tmp / "reference.h5", path = tmp / "run.h5";
  {
    RunWriter w(reference, make_header(n));
    append(w, n, 0, total_frames, 0, total_events);
    w.finish(R"({"done": true})");
  }
  run_and_kill([&] {
    RunWriter w(path, make_header(n));
    append(w, n, 0, 50, 0, 3000);
    w.checkpoint(make_checkpoint(1.0, 5000, 1));
    append(w, n, 50, 117, 3000, 9001);
    w.checkpoint(make_checkpoint(2.34, 3000, 2));  // its blob goes beside the first one
    append(w, n, 117, 250, 9001, 17000);           // unflushed work, lost by the kill
    die();
  });
  CHECK_FALSE(fs::exists(path));
  REQUIRE(fs::exists(path + ".partial"));
  H5E_BEGIN_TRY {  // the writer really died with the file open: its status flag is set
    const hid_t f = H5Fopen((path + ".partial").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK(f < 0);
    if (f >= 0) H5Fclose(f);
  }
  H5E_END_TRY;
  {
    const RunContents killed = read_run_file(path + ".partial");
    CHECK_FALSE(killed.finished);
    require_same_header(killed.header, make_header(n));
    require_content(killed, n, 117, 9001);
    REQUIRE(killed.last_checkpoint);
    CHECK(killed.last_checkpoint->time == 2.34);
    CHECK(killed.last_checkpoint->frames_written == 117);
    CHECK(killed.last_checkpoint->events_written == 9001);
    CHECK(killed.last_checkpoint->engine_state == make_checkpoint(2.34, 3000, 2).engine_state);
  }
  {
    ResumedRun resumed = resume_run_file(path);  // the final name also finds the partial file
    CHECK(resumed.checkpoint.frames_written == 117);
    CHECK(resumed.checkpoint.engine_state == make_checkpoint(2.34, 3000, 2).engine_state);
    CHECK(resumed.writer.frames_written() == 117);
    CHECK(resumed.writer.partial_path() == path + ".partial");
    append(resumed.writer, n, 117, total_frames, 9001, total_events);
    resumed.writer.finish(R"({"done": true})");
  }
  CHECK_FALSE(fs::exists(path + ".partial"));
  CHECK_FALSE(fs::exists(path + ".partial.resume"));
  const RunContents done = read_run_file(path), want = read_run_file(reference);
  CHECK(done.finished);
  CHECK(done.summary_json == want.summary_json);
  require_same_header(done.header, want.header);
  require_content(done, n, total_frames, total_events);
}

TEST_CASE("run file: kill -9 mid-run and again after resuming", "[io][crash]") {
  TempDir tmp;
  const std::size_t n = 5;
  const std::string path = tmp / "run.h5";
  run_and_kill([&] {
    RunWriter w(path, make_header(n));
    append(w, n, 0, 10, 0, 10);
    w.checkpoint(make_checkpoint(0.5, 64, 3));
    die();  // right after a checkpoint: nothing in flight
  });
  require_content(read_run_file(path + ".partial"), n, 10, 10);
  run_and_kill([&] {
    ResumedRun r = resume_run_file(path + ".partial");
    append(r.writer, n, 10, 30, 10, 40);
    r.writer.checkpoint(make_checkpoint(1.5, 64, 4));
    append(r.writer, n, 30, 35, 40, 41);
    die();
  });
  require_content(read_run_file(path + ".partial"), n, 30, 40);
  ResumedRun r = resume_run_file(path);
  append(r.writer, n, 30, 80, 40, 100);
  r.writer.finish("{}");
  require_content(read_run_file(path), n, 80, 100);
}

TEST_CASE("run file: nothing to resume gives RunFileError", "[io][crash]") {
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  CHECK(error_of([&] { resume_run_file(path); }).find("no such file") != std::string::npos);
  run_and_kill([&] {
    RunWriter w(path, make_header(2));
    append(w, 2, 0, 100, 0, 100);  // never checkpointed
    die();
  });
  const RunContents run = read_run_file(path + ".partial");
  CHECK(run.frames.empty());
  CHECK_FALSE(run.last_checkpoint);
  CHECK(error_of([&] { resume_run_file(path); }).find("no checkpoint") != std::string::npos);
}

TEST_CASE("run file: a file whose non-SWMR writer was killed still opens (h5clear -s)", "[io][crash]") {
  TempDir tmp;
  const std::string path = tmp / "run.h5";
  {
    RunWriter w(path, make_header(2));
    append(w, 2, 0, 20, 0, 20);
    w.finish("{}");
  }
  run_and_kill([&] {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);  // marks the superblock "open for write"
    if (f < 0) throw std::runtime_error("open");
    die();
  });
  H5E_BEGIN_TRY {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK(f < 0);  // the flag is really set
    if (f >= 0) H5Fclose(f);
  }
  H5E_END_TRY;
  const RunContents run = read_run_file(path);
  CHECK(run.finished);
  require_content(run, 2, 20, 20);
}
