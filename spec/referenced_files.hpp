// Files named by a job spec: meshes and clump templates. A spec sent to the server must stand
// alone (the server reads no files of the client's), so the client inlines the files it names
// before sending it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "dem.pb.h"

namespace dem::spec {

// Where a file named by a spec is: relative names are read from `base_dir` (the spec's folder),
// absolute ones, or any with no base_dir, as given.
std::filesystem::path resolve_file(const std::string& name, const std::string& base_dir);

// JSON paths of every file the spec names ("walls[0].mesh.file", "packings[1].inside.file",
// "clumpShapes[2].file").
std::vector<std::string> file_references(const api::JobSpec& spec);

// Replaces each file by its content, read relative to `base_dir`: a mesh by its vertices and
// triangles (its placing, scale, rotation and translation, kept), a clump template by its spheres
// (its scale kept), so the scene is the same. Throws SpecError naming the field and the file when
// one cannot be read.
void inline_files(api::JobSpec& spec, const std::string& base_dir);

}  // namespace dem::spec
