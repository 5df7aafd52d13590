// The finished parts of a study, kept while it runs, so that a study that is
// killed or fails half way loses only the part it was working on. The parts
// file (OUT.parts.jsonl, beside the output) is JSON Lines: first the options
// the study runs with, then one line per finished part, written and flushed
// as each part ends:
//   {"options": {...}}
//   {"part": "query", "rows": [...], "per_query": [...]}
//   {"part": "scene", "name": "gas", "runs": [...]}
// `collide2d study --resume` with the same options reads it and runs only the
// parts it lacks. Doubles are written exactly (shortest round-trip decimal);
// NaN and infinities, which JSON cannot hold, as the strings "nan", "inf",
// "-inf". When the study's HDF5 file is in place, the parts file is removed.
#pragma once

#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lab/query_study.hpp"
#include "lab/scene_study.hpp"

namespace collide2d::cli {

struct StudyParts {
  bool has_query_level = false;
  QueryStudy query;
  std::map<std::string, std::vector<SceneStudyRun>> scenes;  // by scene name
};

std::string study_parts_path(const std::string& output);

// Reads a parts file written with `options`; throws std::runtime_error naming
// the file if it cannot be read or was written with other options.
StudyParts read_study_parts(const std::string& path, const nlohmann::json& options);

// Appends finished parts to a parts file, one flushed line each.
class StudyPartsWriter {
 public:
  // Starts a new parts file (truncating) with the options line, or, with
  // `append`, continues an existing one. Throws std::runtime_error naming it.
  StudyPartsWriter(const std::string& path, const nlohmann::json& options, bool append);
  void query_level(const QueryStudy& study);
  void scene(const std::string& name, const std::vector<SceneStudyRun>& runs);

 private:
  void write_line(const nlohmann::json& line);
  std::string path_;
  std::ofstream out_;
};

}  // namespace collide2d::cli
