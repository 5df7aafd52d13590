// A scene file read twice (scene_file.hpp): the hash fed in pieces is the
// hash of the whole, the stream's digest is the text's, and a file changed
// between the two reads is refused.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "collide2d/scene/scene_file.hpp"

using namespace collide2d;

namespace {

std::string some_text(std::size_t n) {
  std::string s(n, '\0');
  std::uint64_t x = 0x9e3779b97f4a7c15ULL;
  for (char& c : s) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    c = static_cast<char>(x >> 56);
  }
  return s;
}

struct SceneFile {
  std::string path;
  explicit SceneFile(const std::string& text) {
    static int counter = 0;
    path = (std::filesystem::temp_directory_path() /
            ("collide2d_scene_file_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".json"))
               .string();
    write(text);
  }
  void write(const std::string& text) const { std::ofstream(path, std::ios::binary) << text; }
  ~SceneFile() { std::filesystem::remove(path); }
};

// Three balls in a box, with a comment-free tail of whitespace.
std::string small_scene(double vx) {
  return R"({"name": "three", "gravity": [0, -1], "walls": [{"a": [0, 0], "b": [10, 0]}], "balls": [)"
         R"({"position": [1, 1], "velocity": [)" +
         std::to_string(vx) + R"(, 0], "radius": 0.5}, {"position": [3, 1], "velocity": [0, 0], "radius": 0.5},)"
                              R"({"position": [5, 1], "velocity": [0, 0], "radius": 0.5}]}  )"
                              "\n";
}

}  // namespace

TEST_CASE("scene file: the hash fed in whole-word pieces is the hash of the whole", "[scene]") {
  const std::string text = some_text(100003);  // not a multiple of eight
  const TextDigest whole = digest_of(text);
  for (const std::size_t piece : {8u, 64u, 65536u}) {
    std::uint64_t h = kTextHashStart;
    for (std::size_t at = 0; at < text.size(); at += piece)
      hash_text(h, text.data() + at, std::min(piece, text.size() - at));
    CHECK(h == whole.hash);
  }
  // One changed byte anywhere changes the hash (the step is a bijection of h).
  for (const std::size_t at : {std::size_t{0}, std::size_t{7}, std::size_t{50000}, text.size() - 1}) {
    std::string changed = text;
    changed[at] = static_cast<char>(changed[at] ^ 1);
    CHECK(digest_of(changed).hash != whole.hash);
  }
}

TEST_CASE("scene file: the stream's digest is the digest of the file's text", "[scene]") {
  const std::string text = some_text(3 * 65536 + 5);  // three whole refills and a short one
  SceneFile file(text);
  HashedFileBuf buf(file.path);
  REQUIRE(buf.is_open());
  std::istream in(&buf);
  std::string read_back((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(read_back == text);
  CHECK(buf.digest() == digest_of(text));
}

TEST_CASE("scene file: parsed as written gives the scene of its text; a changed file is refused", "[scene]") {
  const std::string text = small_scene(1.5);
  SceneFile file(text);
  const Scene expected = scene_from_text(text);
  const Scene parsed = scene_from_file_as_written(file.path, count_ball_positions(text), digest_of(text));
  CHECK(scene_to_json(parsed) == scene_to_json(expected));

  const auto refusal = [&](const std::string& now_in_file) -> std::string {
    file.write(now_in_file);
    try {
      scene_from_file_as_written(file.path, 3, digest_of(text));
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  };
  // Same length, one digit changed: a valid scene, but not the one kept.
  CHECK_THAT(refusal(small_scene(2.5)), Catch::Contains("changed while it was read"));
  // Bytes appended after the JSON value (whitespace, valid JSON still).
  CHECK_THAT(refusal(text + std::string(70000, ' ')), Catch::Contains("changed while it was read"));
  // The file gone.
  std::filesystem::remove(file.path);
  CHECK_THROWS_AS(scene_from_file_as_written(file.path, 3, digest_of(text)), SceneError);
}
