// SPDX-License-Identifier: MIT
// MeshFormat: the input formats the io layer reads, and how a format is chosen from a file
// name (extension) and, when the extension says nothing, from the first bytes.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace silk {

// kXyz is a point cloud (.xyz, .pts: io/xyz/xyz_reader.h); read as a mesh it has no faces.
enum class MeshFormat { kObj, kPly, kStl, kOff, kGltf, kGlb, kPmd, kXyz };

const char* MeshFormatName(MeshFormat f);

// Format from the file extension (case-insensitive), ignoring a trailing ".gz".
std::optional<MeshFormat> MeshFormatFromPath(const std::string& path);

// True when the path ends in ".gz" (case-insensitive).
bool HasGzipSuffix(const std::string& path);

// Format from magic bytes ("ply", "OFF", "glTF", "solid", "{", "PSMD"); nullopt when unsure.
std::optional<MeshFormat> SniffMeshFormat(const uint8_t* data, size_t size);

}  // namespace silk
