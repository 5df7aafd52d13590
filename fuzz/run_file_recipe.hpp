// The structure-aware half of fuzz_run_file: decodes a fuzz input into a
// well-formed HDF5 file shaped like a run file (docs/formats/run-file.md),
// whose groups, datasets, attributes, types, shapes and values the input
// chooses. Most choices keep what RunWriter would write; each can instead
// drop the object, give it another type (strings for numbers, floats for
// integers), another rank or row shape, another row count (truncated or
// inconsistent series, a checkpoint past the data), an enormous extent with
// no data behind it, or values such as NaN, infinities and int64 extremes.
// The scene and options JSON may disagree with /parameters or not parse.
//
// Why not raw bytes: those mostly exercise HDF5's own checksums and decoders,
// and what goes wrong in there (a leak on its error path, fuzz/README.md,
// "Raw bytes") is not ours to fix. A valid HDF5 file with fuzzer-chosen
// content exercises what is ours: the run file reader's validation.
#pragma once

#include <fuzzer/FuzzedDataProvider.h>

#include <string>

namespace collide2d::fuzz {

// Writes the file at `path` (overwritten). Aborts if HDF5 refuses what the
// recipe asks for: the recipe must only build valid HDF5.
void write_run_file_recipe(FuzzedDataProvider& in, const std::string& path);

}  // namespace collide2d::fuzz
