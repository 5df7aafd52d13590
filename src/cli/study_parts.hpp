// The finished parts of a study, kept while it runs, so that a study that is
// killed or fails half way loses only the part it was working on. The parts
// file (OUT.parts.jsonl, beside the output) is JSON Lines: first the options
// the study runs with, then one line per finished part, written and flushed
// as each part ends (cli/journal.hpp):
//   {"options": {...}}
//   {"part": "query_unit", "unit": 3, "rows": [...], "per_query": {...}}
//   {"part": "scene", "name": "gas", "runs": [...]}
// A query unit is one method in one mode (lab/query_study.hpp).
// `collide2d study --resume` with the same options reads it and runs only the
// parts it lacks. Doubles are written exactly (shortest round-trip decimal);
// NaN and infinities, which JSON cannot hold, as the strings "nan", "inf",
// "-inf". When the study's HDF5 file is in place, the parts file is removed.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lab/query_study.hpp"
#include "lab/scene_study.hpp"

namespace collide2d::cli {

struct StudyParts {
  std::map<std::size_t, QueryStudyUnitResult> query_units;   // by unit number
  std::map<std::string, std::vector<SceneStudyRun>> scenes;  // by scene name
};

std::string study_parts_path(const std::string& output);

// Reads a parts file written with `options`; throws std::runtime_error naming
// the file if it cannot be read or was written with other options.
StudyParts read_study_parts(const std::string& path, const nlohmann::json& options);

// A finished part as its line of the parts file, and back: the lines also
// carry parts from rank to rank in `mpirun collide2d study`.
nlohmann::json query_unit_part(std::size_t unit, const QueryStudyUnitResult& result);
nlohmann::json scene_part(const std::string& name, const std::vector<SceneStudyRun>& runs);
// Adds a part's line to `parts`; throws std::runtime_error on a malformed line.
void add_study_part(StudyParts& parts, const nlohmann::json& line);

}  // namespace collide2d::cli
