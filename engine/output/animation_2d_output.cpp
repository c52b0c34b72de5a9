#include "output/animation_2d_output.hpp"

#include <vector>

namespace dem {

std::optional<std::array<Vec3, 2>> trace_on_plane(const Vec3* corners, int count) {
  std::vector<Vec3> crossings;
  for (int k = 0; k < count; ++k) {
    const Vec3 &a = corners[k], &b = corners[(k + 1) % count];
    if (a.y() == 0) crossings.push_back(a);
    if ((a.y() < 0 && b.y() > 0) || (a.y() > 0 && b.y() < 0)) {
      const double s = a.y() / (a.y() - b.y());
      Vec3 x = a + s * (b - a);
      x.y() = 0;
      crossings.push_back(x);
    }
  }
  std::optional<std::array<Vec3, 2>> best;
  double longest = 0;
  for (std::size_t i = 0; i < crossings.size(); ++i)
    for (std::size_t j = i + 1; j < crossings.size(); ++j) {
      const double length = (crossings[i] - crossings[j]).squaredNorm();
      if (length > longest) {
        longest = length;
        best = std::array<Vec3, 2>{crossings[i], crossings[j]};
      }
    }
  return best;
}

Animation2DWriter::Animation2DWriter(const std::string& path, const Simulation& sim, bool append)
    : file_(path, append) {
  const std::array<double, 6> box = frame_domain(sim);
  domain_ = {box[0], box[1], box[4], box[5]};
}

legacy::Animation2DFrame Animation2DWriter::make_frame(const Simulation& sim, const std::array<double, 4>& domain) {
  // the 3D frame's scalars and walls (in the file's unit, which leaves where they cross y = 0 unchanged), cut by
  // the plane
  auto in_plane = [](const Vec3& x) { return legacy::Vec2(x.x(), x.z()); };
  const legacy::AnimationFrame full = AnimationWriter::make_frame(sim, {});
  legacy::Animation2DFrame frame;
  frame.domain = domain;
  frame.scalars = full.scalars;
  frame.step = full.step;
  for (const legacy::AnimationPlate& plate : full.plates)
    if (const auto trace = trace_on_plane(plate.corners.data(), 4))
      frame.plates.push_back({plate.id, {in_plane((*trace)[0]), in_plane((*trace)[1])}});
  for (const legacy::AnimationTriangle& triangle : full.triangles)
    if (const auto trace = trace_on_plane(triangle.corners.data(), 3))
      frame.triangles.push_back({triangle.id, {in_plane((*trace)[0]), in_plane((*trace)[1])}});
  frame.discs.reserve(full.particles.size());
  for (const legacy::AnimationParticle& p : full.particles)
    frame.discs.push_back({p.id,
                           {p.position.x(), p.position.z()},
                           p.diameter,
                           {p.velocity.x(), p.velocity.z()},
                           p.contacts,
                           p.angular_velocity.y(),
                           p.part});
  return frame;
}

void Animation2DWriter::frame(const Simulation& sim) {
  legacy::write_animation_2d_frame(file_.get(), make_frame(sim, domain_), file_format(sim));
  file_.flush();
}

}  // namespace dem
