// Readers and writers of the legacy text files (docs/formats.md; PDEM-EGD and BallastDEM manuals).
// Frames hold values already in the file's units: the caller converts from SI.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace dem::legacy {

using Vec3 = Eigen::Vector3d;

enum class NumberFormat {
  Scientific,   // %.6e for every real: 7 significant digits at any scale
  LegacyFixed,  // the fixed widths of the manuals' samples
  Full,         // %.16e: 17 significant digits, every double read back exactly
};

struct AnimationPlate {
  int id = 0;
  std::array<Vec3, 4> corners;
};

struct AnimationTriangle {
  int id = 0;
  std::array<Vec3, 3> corners;
};

struct AnimationParticle {
  int id = 0;  // 1-based
  Vec3 position = Vec3::Zero();
  double diameter = 0;
  Vec3 velocity = Vec3::Zero();
  int contacts = 0;
  Vec3 angular_velocity = Vec3::Zero();
  int part = 0;
};

struct AnimationFrame {
  std::array<double, 6> domain{};   // xmin xmax ymin ymax zmin zmax
  std::array<double, 4> scalars{};  // time, plate displacement, plate force, kinetic energy
  std::int64_t step = 0;
  std::vector<AnimationPlate> plates;
  std::vector<AnimationTriangle> triangles;
  std::vector<AnimationParticle> particles;
};

// ANIMATION_2D.dat (project-defined: both manuals' viewers read a "2D Data structure" they never print;
// docs/formats.md section 3a): a 2D run's frames, ANIMATION_3D.dat's layout in the x-z plane. A point is (x, z).
using Vec2 = Eigen::Vector2d;

struct AnimationSegment {  // where a plate or a moving mesh's triangle crosses the plane
  int id = 0;
  std::array<Vec2, 2> ends;
};

struct AnimationDisc {
  int id = 0;  // 1-based
  Vec2 position = Vec2::Zero();
  double diameter = 0;
  Vec2 velocity = Vec2::Zero();
  int contacts = 0;
  double spin = 0;  // rad/s about +y, right-handed (turns +z towards +x)
  int part = 0;
};

struct Animation2DFrame {
  std::array<double, 4> domain{};   // xmin xmax zmin zmax
  std::array<double, 4> scalars{};  // as ANIMATION_3D.dat's
  std::int64_t step = 0;
  std::vector<AnimationSegment> plates;
  std::vector<AnimationSegment> triangles;
  std::vector<AnimationDisc> discs;
};

struct ForceChain {
  int i = 0;  // 1-based, i < j
  int j = 0;
  double normal_force = 0;
  double tangential_force = 0;
};

struct ForceChainFrame {
  std::int64_t step = 0;
  std::vector<ForceChain> chains;
};

template <class Frame>
struct ReadResult {
  std::vector<Frame> frames;  // every complete frame
  bool truncated = false;     // the file ended inside a frame (the writer was killed)
  std::string problem;        // why reading stopped early, with the line number; empty if clean
};

// Wall_Animation_3D.dat (project-defined, legacy-formats.md section 5): per frame "3DW: step NW",
// then NW lines, each a plate ("id rplate" + 4 corners) or a triangle ("id tri" + 3 corners) in the
// format of ANIMATION_3D.dat; plates first.
struct WallFrame {
  std::int64_t step = 0;
  std::vector<AnimationPlate> plates;
  std::vector<AnimationTriangle> triangles;
};

// Wall_ForceChain_3D.dat: per frame "3DWF: step NC", then NC lines "i wall Fn Ft" (1-based particle
// id, 1-based wall number in the job spec's order), sorted by i then wall.
struct WallForceChain {
  int i = 0;
  int wall = 0;
  double normal_force = 0;
  double tangential_force = 0;
};

struct WallForceChainFrame {
  std::int64_t step = 0;
  std::vector<WallForceChain> chains;
};

// Force_Displacement.dat: one row per output time, "time displacement force" (s, file length
// unit, N) of the loading plate.
struct ForceDisplacementRow {
  double time = 0;
  double displacement = 0;
  double force = 0;
};

// Parses a Fortran-style real: 7.547503e+002, 1.0E9, 1.0D9, 1.0d-3, .5, 5., +3, -3.25, and the
// exponent without a letter that Fortran prints for three-digit exponents (1.0-100 = 1.0e-100).
// Nothing else may follow. Rejects nan, inf and values outside the range of double. Locale-independent.
std::optional<double> parse_fortran_real(std::string_view token);

// Writers append one whole frame with a single fwrite; the caller flushes after it and checks
// ferror(out). Values are written as given: the caller passes chains sorted by i with i < j, ids
// 1-based, and finite values (a NaN would be written as printf writes it, "nan", which the readers
// reject). Numbers are separated by single spaces, lines end in '\n'. NumberFormat::Scientific
// prints every real as %.6e; LegacyFixed prints the manuals' widths: domain and plate/triangle
// corners %.3f, scalars %.4f, particle position, velocity and angular velocity %.2f, diameter
// %.4f, forces %.2f. Integers are plain decimals. The text never depends on the locale.
void write_animation_frame(std::FILE* out, const AnimationFrame& frame, NumberFormat format);
void write_force_chain_frame(std::FILE* out, const ForceChainFrame& frame, NumberFormat format);

// Readers: tokens are separated by any run of spaces, tabs or '\r' (CRLF files read fine); blank
// lines are ignored; reals may be Fortran style (parse_fortran_real); integer columns (ids, step,
// counts, nc, part) also accept integral reals such as "3.0". The force-chain column i-1 is skipped.
// They never throw on bad content. They return every complete frame and stop at the first problem:
// - the input ends inside a frame: truncated = true, problem names the frame's first line and the
//   last line read. A last line without '\n' is never used, even when it would complete the frame:
//   writers end every line with '\n', so that line is one a writer was stopped in, and its last
//   number may be cut short. Such a line alone after the last complete frame also sets truncated.
// - a line is malformed (wrong number of values, a value that is not a number, a wrong keyword, a
//   negative count, a new frame header before the frame is complete): truncated = false, problem
//   is "line N: ..." saying what is wrong. Nothing after that line is read, since the frame
//   boundaries after it cannot be trusted.
ReadResult<AnimationFrame> read_animation(std::istream& in);
ReadResult<ForceChainFrame> read_force_chains(std::istream& in);

// ANIMATION_2D.dat, with the writers' and readers' rules above (the 3D widths for the same quantities).
void write_animation_2d_frame(std::FILE* out, const Animation2DFrame& frame, NumberFormat format);
ReadResult<Animation2DFrame> read_animation_2d(std::istream& in);

void write_wall_frame(std::FILE* out, const WallFrame& frame, NumberFormat format);
void write_wall_force_chain_frame(std::FILE* out, const WallForceChainFrame& frame, NumberFormat format);
void write_force_displacement_row(std::FILE* out, const ForceDisplacementRow& row, NumberFormat format);
ReadResult<WallFrame> read_wall_frames(std::istream& in);
ReadResult<WallForceChainFrame> read_wall_force_chains(std::istream& in);
// Each row is one "frame" here: a cut last row sets truncated, like the other readers.
ReadResult<ForceDisplacementRow> read_force_displacement(std::istream& in);

// The statistics files of section 5 (Masscenter.dat, Disp_Max.dat, Coord_OL.dat, Fragments.dat):
// one row per output time, a fixed number of reals. The reader checks the column count.
void write_row(std::FILE* out, const std::vector<double>& values, NumberFormat format);
ReadResult<std::vector<double>> read_rows(std::istream& in, std::size_t columns);

}  // namespace dem::legacy
