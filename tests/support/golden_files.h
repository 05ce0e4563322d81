// SPDX-License-Identifier: MIT
// Readers for the official reference files in shared/spec: token lists, processed-face lists
// (grid coordinates) and INDEX.tsv rows, plus the canonical face form used to compare them.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/io_mesh.h"

namespace silk::testing {

// One decimal id per line. Returns false if the file cannot be read.
bool ReadTokenFile(const std::string& path, std::vector<int32_t>* ids);

// A face as 9 grid integers x1 y1 z1 x2 y2 z2 x3 y3 z3, rotated so its smallest corner
// (as (x, y, z)) comes first: equal winding <=> equal array.
using GridFace = std::array<int32_t, 9>;
GridFace CanonicalFace(const std::array<std::array<int32_t, 3>, 3>& corners);
// The same face with reversed winding, canonical.
GridFace ReversedFace(const GridFace& f);
// Unordered corner set (sorted corners), to compare ignoring winding.
GridFace UnorientedFace(const GridFace& f);
bool ReadProcessedFile(const std::string& path, std::vector<GridFace>* faces);  // missing file -> empty, true

// A tab-separated file with a header row (golden-dev INDEX.tsv, corpus/dev MANIFEST.tsv) as
// rows of column -> value; empty lines skipped, missing file -> no rows.
std::vector<std::map<std::string, std::string>> ReadTsvRows(const std::string& path);

// The reference drivers' plain OBJ parse: every `v` line, every `f` line's first index of
// each group minus one; nothing welded or cleaned (spec/golden/README.md step 1).
bool ReadPlainObj(const std::string& path, silk::IoMesh* mesh);

// Names of the golden-dev meshes the official code encodes (INDEX.tsv status "ok").
std::vector<std::string> GoldenDevOkNames();

// The 14 hand-made golden names in shared/spec/golden/.
std::vector<std::string> GoldenNames();

}  // namespace silk::testing
