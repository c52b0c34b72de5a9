// Mesh files named by a job spec. A spec sent to the server must stand alone (the server reads no
// files of the client's), so the client inlines the meshes it names before sending it.
#pragma once

#include <string>
#include <vector>

#include "dem.pb.h"

namespace dem::spec {

// JSON paths of every mesh given by file ("walls[0].mesh.file", "packings[1].inside.file").
std::vector<std::string> mesh_file_references(const api::JobSpec& spec);

// Replaces each mesh file by its vertices and triangles, read relative to `base_dir`; the placing
// (scale, rotation, translation) is kept, so the scene is the same. Throws SpecError naming the
// field and the file when one cannot be read.
void inline_mesh_files(api::JobSpec& spec, const std::string& base_dir);

}  // namespace dem::spec
