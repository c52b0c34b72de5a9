#include "spec/referenced_files.hpp"

#include <filesystem>
#include <functional>

#include "mesh/mesh_io.hpp"
#include "spec/clump_template.hpp"
#include "spec/spec_loader.hpp"

namespace dem::spec {
namespace {

// Calls `visit` with each mesh of the spec and its JSON path.
void for_each_mesh(api::JobSpec& spec, const std::function<void(api::Mesh&, const std::string&)>& visit) {
  for (int k = 0; k < spec.walls_size(); ++k)
    if (spec.walls(k).has_mesh())
      visit(*spec.mutable_walls(k)->mutable_mesh(), "walls[" + std::to_string(k) + "].mesh");
  for (int k = 0; k < spec.packings_size(); ++k)
    if (spec.packings(k).has_inside())
      visit(*spec.mutable_packings(k)->mutable_inside(), "packings[" + std::to_string(k) + "].inside");
  for (int k = 0; k < spec.lattices_size(); ++k)
    if (spec.lattices(k).has_inside())
      visit(*spec.mutable_lattices(k)->mutable_inside(), "lattices[" + std::to_string(k) + "].inside");
  for (int k = 0; k < spec.stages_size(); ++k)
    for (int j = 0; j < spec.stages(k).add_walls_size(); ++j)
      if (spec.stages(k).add_walls(j).has_mesh())
        visit(*spec.mutable_stages(k)->mutable_add_walls(j)->mutable_mesh(),
              "stages[" + std::to_string(k) + "].addWalls[" + std::to_string(j) + "].mesh");
}

}  // namespace

std::filesystem::path resolve_file(const std::string& name, const std::string& base_dir) {
  return base_dir.empty() || std::filesystem::path(name).is_absolute() ? std::filesystem::path(name)
                                                                       : std::filesystem::path(base_dir) / name;
}

std::vector<std::string> file_references(const api::JobSpec& spec) {
  std::vector<std::string> paths;
  api::JobSpec copy = spec;  // for_each_mesh visits mutable meshes; this only reads
  for_each_mesh(copy, [&](api::Mesh& mesh, const std::string& path) {
    if (!mesh.file().empty()) paths.push_back(path + ".file");
  });
  for (int k = 0; k < spec.clump_shapes_size(); ++k)
    if (!spec.clump_shapes(k).file().empty()) paths.push_back("clumpShapes[" + std::to_string(k) + "].file");
  return paths;
}

void inline_files(api::JobSpec& spec, const std::string& base_dir) {
  std::vector<std::string> problems;
  for_each_mesh(spec, [&](api::Mesh& mesh, const std::string& path) {
    // both given: left as it is, for the loader to say so (appended, the file's triangles would
    // number the wrong vertices)
    if (mesh.file().empty() || mesh.vertices_size() > 0 || mesh.triangles_size() > 0) return;
    const std::filesystem::path file = resolve_file(mesh.file(), base_dir);
    TriangleMesh read;
    try {
      if (mesh.format() == api::Mesh::STL)
        read = read_stl(file.string());
      else if (mesh.format() == api::Mesh::LEGACY)
        read = read_legacy_mesh(file.string());
      else
        read = read_mesh(file.string());
    } catch (const MeshError& e) {
      problems.push_back(path + ".file: " + e.what());
      return;
    }
    mesh.clear_file();
    mesh.clear_format();
    for (const Vec3& v : read.vertices) {
      api::Vec3* out = mesh.add_vertices();
      out->set_x(v.x());
      out->set_y(v.y());
      out->set_z(v.z());
    }
    for (const auto& t : read.triangles) {  // inline triangles are 1-based, as in the legacy file
      api::Triangle* out = mesh.add_triangles();
      out->set_i(t[0] + 1);
      out->set_j(t[1] + 1);
      out->set_k(t[2] + 1);
    }
  });
  for (int k = 0; k < spec.clump_shapes_size(); ++k) {
    api::ClumpShape& shape = *spec.mutable_clump_shapes(k);
    if (shape.file().empty() || shape.spheres_size() > 0) continue;  // both given: the loader says so
    try {
      for (const MemberSphere& m : read_clump_template(resolve_file(shape.file(), base_dir).string())) {
        api::Sphere* out = shape.add_spheres();
        out->mutable_center()->set_x(m.centre.x());
        out->mutable_center()->set_y(m.centre.y());
        out->mutable_center()->set_z(m.centre.z());
        out->set_radius(m.radius);
      }
      shape.clear_file();
    } catch (const std::runtime_error& e) {
      problems.push_back("clumpShapes[" + std::to_string(k) + "].file: " + e.what());
    }
  }
  if (!problems.empty()) throw SpecError(problems);
}

}  // namespace dem::spec
