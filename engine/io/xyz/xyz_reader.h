// SPDX-License-Identifier: MIT
// Strict reader of plain-text point clouds (.xyz, .pts): one point per line, "x y z" or
// "x y z nx ny nz" (docs/io.md "Point clouds"); what a scan exported without faces looks like.
#pragma once
#include <string>
#include <string_view>

#include "core/status.h"
#include "io/io_point_cloud.h"
#include "io/read_options.h"

namespace silk {

// Values are separated by spaces, tabs or commas; '#' starts a comment; blank lines and CRLF
// are fine. The first data line may be a single point count (Leica PTS), checked against the
// points that follow. Every point line has the same number of values: 3 (no normals) or 6
// (the last three a unit normal, within 10 %); any other count, a bad or non-finite number, a
// normal that is not unit length (colours) is an error naming the file and line. Nothing is
// reserved beyond what the text's line count allows; max_vertices caps the points.
StatusOr<IoPointCloud> ReadXyz(std::string_view text, const std::string& name, const ReadOptions& opts = {});

}  // namespace silk
