// SPDX-License-Identifier: MIT
// Entry point of the io layer: read a mesh file of any supported format (by extension, with
// a ".gz" wrapper allowed, and content sniffing) into an IoMesh, or explain why not.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/status.h"
#include "io/mesh_format.h"
#include "io/io_mesh.h"
#include "io/read_options.h"

namespace silk {

// .obj .ply .stl .off .gltf .glb .pmd (.xyz/.pts point clouds: a 'no faces' error), optionally followed by .gz (e.g.
// "x.ply.gz"). Unknown extensions are sniffed from the first bytes. Every error message names the file.
StatusOr<IoMesh> ReadMeshFile(const std::string& path, const ReadOptions& opts = {});

// The file's bytes, gunzipped when the path ends in ".gz" (within InflatedLimit); what every
// file reader starts from (ReadMeshFile, ReadMeshOrPointCloudFile).
StatusOr<std::string> ReadInputFileBytes(const std::string& path, const ReadOptions& opts = {});

// Same readers on bytes already in memory (fuzzers, API callers). `name` is used in error
// messages. glTF external buffers are never loaded from memory input.
StatusOr<IoMesh> ReadMeshFromMemory(const uint8_t* data, size_t size, MeshFormat fmt, const std::string& name,
                                    const ReadOptions& opts = {});

}  // namespace silk
