// Where the shipped datasets are (the hard query set, the named scenes), so
// that `study` and `hardset` work from any folder: the first of
//   1. $COLLIDE2D_DATASETS,
//   2. the source tree this program was built from (its datasets/ folder),
//   3. an installed share/collide2d/datasets beside the program's bin/,
//   4. ./datasets.
// A path given on the command line is always taken as given.
#pragma once

#include <string>

namespace collide2d::cli {

// The datasets folder, or "" if none of the places above has one.
std::string datasets_dir();

// `relative` ("hard/hard_queries.jsonl") inside the datasets folder; if there
// is none, `relative` under ./datasets, so that the error names a path.
std::string dataset_path(const std::string& relative);

}  // namespace collide2d::cli
