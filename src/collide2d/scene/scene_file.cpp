#include "collide2d/scene/scene_file.hpp"

#include <istream>
#include <limits>

#include <nlohmann/json.hpp>

namespace collide2d {

Scene scene_from_file_as_written(const std::string& path, std::size_t expected_balls, const TextDigest& written) {
  HashedFileBuf file(path);
  if (!file.is_open()) throw SceneError("", "cannot open file");
  std::istream in(&file);
  // A refused scene is explained from the whole text, as scene_from_text does.
  Scene scene = scene_from_stream(in, expected_balls, [&] { parse_json_text(read_text_file(path)); });
  // The parser may stop at the end of the JSON value; the rest of the file
  // must be digested too, or bytes appended after it would go unseen.
  in.clear();
  in.ignore(std::numeric_limits<std::streamsize>::max());
  if (!(file.digest() == written)) throw SceneError("", "changed while it was read; run again");
  return scene;
}

}  // namespace collide2d
