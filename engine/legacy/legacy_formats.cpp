// Writers and readers of ANIMATION_3D.dat and ForceChain_3D.dat (docs/formats.md, sections 3 and 4).
#include "legacy/legacy_formats.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>
#include <utility>

namespace dem::legacy {
namespace {

constexpr std::string_view animation_header = "3DA:";
constexpr std::string_view animation_2d_header = "2DA:";
constexpr std::string_view force_chain_header = "3DF:";
constexpr std::string_view wall_header = "3DW:";
constexpr std::string_view wall_force_chain_header = "3DWF:";
constexpr std::string_view plate_word = "rplate";
constexpr std::string_view triangle_word = "tri";

// ---------------------------------------------------------------------------------------------
// Writing

// How one real is printed: the text printf gives for "%.<precision>e" or "%.<precision>f".
// std::to_chars produces exactly that text, is much faster than printf and, unlike printf, can
// never print a decimal comma because of the process's locale.
struct RealStyle {
  std::chars_format format;
  int precision;
};

constexpr RealStyle scientific{std::chars_format::scientific, 6};
constexpr RealStyle full{std::chars_format::scientific, 16};  // 17 significant digits: round-trips a double

// The style of a real: scientific (7 digits), full (17) or the legacy fixed width of that column.
RealStyle style_of(NumberFormat format, RealStyle legacy_width) {
  switch (format) {
    case NumberFormat::Scientific:
      return scientific;
    case NumberFormat::Full:
      return full;
    case NumberFormat::LegacyFixed:
      return legacy_width;
  }
  return scientific;
}

constexpr RealStyle fixed(int decimals) { return {std::chars_format::fixed, decimals}; }

// One frame's text, built in memory so that it reaches the file in a single fwrite: a viewer
// following a running job never sees a frame we only half wrote.
class FrameText {
 public:
  // A scientific particle line is about 150 characters: one allocation for the whole frame.
  explicit FrameText(std::size_t line_count) { text_.reserve(line_count * 160 + 64); }

  void word(std::string_view value) {
    separate();
    text_.append(value);
  }

  void integer(long long value) {
    separate();
    char digits[32];
    const auto result = std::to_chars(digits, digits + sizeof digits, value);
    text_.append(digits, result.ptr);
  }

  void real(double value, RealStyle style) {
    separate();
    // Large enough for "%.6f" of the largest double (309 integer digits).
    char digits[400];
    const auto result = std::to_chars(digits, digits + sizeof digits, value, style.format, style.precision);
    text_.append(digits, result.ptr);
  }

  void reals(const Vec3& value, RealStyle style) {
    for (int axis = 0; axis < 3; ++axis) real(value[axis], style);
  }

  void end_line() {
    text_.push_back('\n');
    at_line_start_ = true;
  }

  void write_to(std::FILE* out) const { std::fwrite(text_.data(), 1, text_.size(), out); }

 private:
  // Single spaces between values, none at the end of a line.
  void separate() {
    if (!at_line_start_) text_.push_back(' ');
    at_line_start_ = false;
  }

  std::string text_;
  bool at_line_start_ = true;
};

struct AnimationStyles {
  RealStyle domain;
  RealStyle scalar;
  RealStyle corner;  // plate and triangle corners
  RealStyle position;
  RealStyle diameter;
  RealStyle velocity;
  RealStyle angular_velocity;
};

AnimationStyles animation_styles(NumberFormat format) {
  // The fixed widths are those of BallastDEM's sample frame (manual figure 3.5).
  return {style_of(format, fixed(3)), style_of(format, fixed(4)), style_of(format, fixed(3)),
          style_of(format, fixed(2)), style_of(format, fixed(4)), style_of(format, fixed(2)),
          style_of(format, fixed(2))};
}

RealStyle force_style(NumberFormat format) {
  // PDEM-EGD's sample (manual section 3.2 item 6) prints forces with two decimals.
  return style_of(format, fixed(2));
}

// ---------------------------------------------------------------------------------------------
// Reading: lines and tokens

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Reads the input line by line and splits each line into whitespace-separated tokens.
// std::getline scans the stream buffer directly, so this costs little more than the copy.
class TokenLines {
 public:
  explicit TokenLines(std::istream& in) : in_(in) {}

  // Moves to the next line that holds tokens. Returns false at the end of the input, and also for a
  // last line without '\n': every writer ends its lines with '\n', so such a line is one a writer
  // was stopped in the middle of, and its last number may be cut short ("3.25" read as "3.2").
  bool next() {
    while (std::getline(in_, line_)) {
      ++line_number_;
      const bool has_line_end = !in_.eof();
      split_line();
      if (tokens_.empty()) continue;
      if (!has_line_end) {
        unfinished_last_line_ = true;
        return false;
      }
      return true;
    }
    return false;
  }

  const std::vector<std::string_view>& tokens() const { return tokens_; }
  std::string_view token(std::size_t index) const { return tokens_[index]; }
  std::size_t token_count() const { return tokens_.size(); }

  // The current line's number (1-based, blank lines counted); at the end, the last line read.
  std::int64_t line_number() const { return line_number_; }

  bool unfinished_last_line() const { return unfinished_last_line_; }

 private:
  void split_line() {
    tokens_.clear();
    const std::string_view text = line_;
    std::size_t position = 0;
    while (position < text.size()) {
      while (position < text.size() && is_blank(text[position])) ++position;
      const std::size_t start = position;
      while (position < text.size() && !is_blank(text[position])) ++position;
      if (position > start) tokens_.push_back(text.substr(start, position - start));
    }
  }

  std::istream& in_;
  std::string line_;
  std::vector<std::string_view> tokens_;
  std::int64_t line_number_ = 0;
  bool unfinished_last_line_ = false;
};

// ---------------------------------------------------------------------------------------------
// Reading: numbers

// Integers in id, step and count columns. Old programs sometimes wrote them as reals ("3.0",
// "1.0E3"): those are accepted when their value is integral.
std::optional<std::int64_t> parse_integer(std::string_view token) {
  std::string_view digits = token;
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error == std::errc{} && end == digits.data() + digits.size()) return value;

  const std::optional<double> real = parse_fortran_real(token);
  if (!real || *real != std::trunc(*real)) return std::nullopt;
  constexpr double two_to_63 = 9223372036854775808.0;  // exact in a double
  if (!(*real >= -two_to_63 && *real < two_to_63)) return std::nullopt;
  return static_cast<std::int64_t>(*real);
}

// Keeps error messages readable when a line holds binary junk or one enormous token.
std::string quoted(std::string_view token) {
  constexpr std::size_t shown = 40;
  // appended, not "'" + std::string(...): GCC 12 warns falsely (-Wrestrict) on that at -O3
  std::string out = "'";
  out.append(token.substr(0, shown));
  out.append(token.size() <= shown ? "'" : "...'");
  return out;
}

std::string line_prefix(std::int64_t line_number) { return "line " + std::to_string(line_number) + ": "; }

// Converts the current line's tokens to values, keeping the first problem met. After a problem the
// getters return 0, so a caller converts a whole line and checks ok() once.
class LineValues {
 public:
  explicit LineValues(const TokenLines& lines) : lines_(lines) {}

  double real(std::size_t column) {
    const std::optional<double> value = parse_fortran_real(lines_.token(column));
    if (!value) return fail(column, "is not a number");
    return *value;
  }

  Vec3 vec3(std::size_t first_column) { return {real(first_column), real(first_column + 1), real(first_column + 2)}; }

  std::int64_t integer64(std::size_t column) {
    const std::optional<std::int64_t> value = parse_integer(lines_.token(column));
    if (!value) return fail(column, "is not an integer");
    return *value;
  }

  int integer(std::size_t column) {
    const std::int64_t value = integer64(column);
    if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max()) {
      return fail(column, "is out of the range of an int");
    }
    return static_cast<int>(value);
  }

  // A number of lines that follow; capped at INT_MAX because ids are ints.
  std::size_t count(std::size_t column) {
    const int value = integer(column);
    if (value < 0) {
      fail(column, "is a negative count");
      return 0;
    }
    return static_cast<std::size_t>(value);
  }

  bool ok() const { return problem_.empty(); }
  const std::string& problem() const { return problem_; }

 private:
  int fail(std::size_t column, std::string_view what) {
    if (problem_.empty()) {
      problem_ = line_prefix(lines_.line_number()) + "column " + std::to_string(column + 1) + " (" +
                 quoted(lines_.token(column)) + ") " + std::string(what);
    }
    return 0;
  }

  const TokenLines& lines_;
  std::string problem_;
};

// ---------------------------------------------------------------------------------------------
// Reading: frames

// Why a frame could not be read.
struct Stop {
  bool truncated = false;
  std::string problem;
};

Stop malformed(std::string problem) { return {false, std::move(problem)}; }

// What line a frame expects next, for messages: "particle line 12 of 400".
struct Expected {
  std::string_view name;    // "particle line"
  std::string_view layout;  // "id x y z D vx vy vz nc wx wy wz part"
  std::size_t columns;
  std::size_t index = 0;  // 1-based index among repeated lines; 0 for a line that occurs once
  std::size_t total = 0;

  std::string describe() const {
    std::string text(name);
    if (index > 0) text.append(" ").append(std::to_string(index)).append(" of ").append(std::to_string(total));
    return text;
  }
};

// Reads the lines of one frame after its header, with messages that say where the frame began.
class FrameLines {
 public:
  FrameLines(TokenLines& lines, std::string_view header)
      : lines_(lines), header_(header), first_line_(lines.line_number()) {}

  // Moves to the next line and checks its column count; on failure, says why in a Stop.
  std::optional<Stop> next(const Expected& expected) {
    if (!lines_.next()) return ended(expected);
    if (lines_.token_count() == expected.columns) return std::nullopt;
    if (lines_.token(0) == header_) {
      return malformed(line_prefix(lines_.line_number()) +
                       "a new frame starts here, but the frame that starts at line " + std::to_string(first_line_) +
                       " is incomplete: its " + expected.describe() + " is missing");
    }
    return malformed(line_prefix(lines_.line_number()) + "expected " + std::to_string(expected.columns) +
                     " values on the " + expected.describe() + " (" + std::string(expected.layout) + "), found " +
                     std::to_string(lines_.token_count()));
  }

  // Moves to the next line whatever its column count (the caller checks it): fails only at the end
  // of the input or at the next frame's header.
  std::optional<Stop> next_any(const Expected& expected) {
    if (!lines_.next()) return ended(expected);
    if (lines_.token(0) == header_) {
      return malformed(line_prefix(lines_.line_number()) +
                       "a new frame starts here, but the frame that starts at line " + std::to_string(first_line_) +
                       " is incomplete: its " + expected.describe() + " is missing");
    }
    return std::nullopt;
  }

  std::size_t token_count() const { return lines_.token_count(); }
  std::string_view token(std::size_t k) const { return lines_.token(k); }
  std::int64_t line_number() const { return lines_.line_number(); }

  // Checks the word in a column (the "rplate" of a plate line).
  std::optional<Stop> check_word(std::size_t column, std::string_view word) const {
    if (lines_.token(column) == word) return std::nullopt;
    return malformed(line_prefix(lines_.line_number()) + "column " + std::to_string(column + 1) + " is " +
                     quoted(lines_.token(column)) + ", expected '" + std::string(word) + "'");
  }

  LineValues values() const { return LineValues(lines_); }

 private:
  Stop ended(const Expected& expected) const {
    std::string problem = "the file ends inside the frame that starts at line " + std::to_string(first_line_) +
                          ": its " + expected.describe() + " is missing";
    if (lines_.unfinished_last_line()) {
      problem += "; the last line (line " + std::to_string(lines_.line_number()) +
                 ") has no line end, the writer was stopped while writing it";
    } else {
      problem += " (the last line is line " + std::to_string(lines_.line_number()) + ")";
    }
    return {true, std::move(problem)};
  }

  TokenLines& lines_;
  std::string_view header_;
  std::int64_t first_line_;
};

std::optional<Stop> check_frame_header(const TokenLines& lines, std::string_view header, std::size_t columns,
                                       std::string_view layout) {
  if (lines.token(0) == header && lines.token_count() == columns) return std::nullopt;
  return malformed(line_prefix(lines.line_number()) + "expected the frame header '" + std::string(layout) +
                   "', found " + quoted(lines.token(0)) + (lines.token_count() > 1 ? " and more" : ""));
}

// Reads frames until the input ends or a frame cannot be read. `read_frame` reads one frame whose
// header line is the current line.
template <class Frame, class ReadFrame>
ReadResult<Frame> read_frames(std::istream& in, ReadFrame read_frame) {
  ReadResult<Frame> result;
  TokenLines lines(in);
  while (lines.next()) {
    Frame frame;
    if (std::optional<Stop> stop = read_frame(lines, frame)) {
      result.truncated = stop->truncated;
      result.problem = std::move(stop->problem);
      return result;
    }
    result.frames.push_back(std::move(frame));
  }
  if (lines.unfinished_last_line()) {
    result.truncated = true;
    result.problem = "the file ends inside a frame header: the last line (line " + std::to_string(lines.line_number()) +
                     ") has no line end, the writer was stopped while writing it";
  }
  return result;
}

// Reserving from a count read in the file: a corrupt count must not allocate gigabytes up front.
std::size_t safe_reserve(std::size_t count) { return std::min<std::size_t>(count, std::size_t{1} << 20); }

// ---------------------------------------------------------------------------------------------
// ANIMATION_3D.dat

constexpr std::string_view plate_layout = "id rplate x1 y1 z1 x2 y2 z2 x3 y3 z3 x4 y4 z4";
constexpr std::string_view triangle_layout = "id tri x1 y1 z1 x2 y2 z2 x3 y3 z3";
constexpr std::string_view particle_layout = "id x y z D vx vy vz nc wx wy wz part";

// Plate and triangle lines: "id WORD" then the corners, three numbers each.
template <class Polygon>
std::optional<Stop> read_polygons(FrameLines& frame_lines, std::string_view what, std::string_view layout,
                                  std::string_view word, std::size_t count, std::vector<Polygon>& out) {
  constexpr std::size_t corners = std::tuple_size_v<decltype(Polygon::corners)>;
  out.reserve(safe_reserve(count));
  for (std::size_t k = 0; k < count; ++k) {
    if (auto stop = frame_lines.next({what, layout, 2 + 3 * corners, k + 1, count})) return stop;
    if (auto stop = frame_lines.check_word(1, word)) return stop;
    LineValues values = frame_lines.values();
    Polygon& polygon = out.emplace_back();
    polygon.id = values.integer(0);
    for (std::size_t corner = 0; corner < corners; ++corner) polygon.corners[corner] = values.vec3(2 + 3 * corner);
    if (!values.ok()) return malformed(values.problem());
  }
  return std::nullopt;
}

// The four lines an animation frame (3D or 2D) opens with after its header: the domain, the scalars, the count
// of triangle (2D: segment) lines, and "step NP NW".
struct FrameCounts {
  std::size_t triangles = 0, particles = 0, plates = 0;
};

template <std::size_t DomainValues>
std::optional<Stop> read_frame_opening(FrameLines& frame_lines, std::string_view domain_layout,
                                       std::string_view triangle_count_name, std::array<double, DomainValues>& domain,
                                       std::array<double, 4>& scalars, std::int64_t& step, FrameCounts& counts) {
  if (auto stop = frame_lines.next({"domain line", domain_layout, DomainValues})) return stop;
  LineValues domain_values = frame_lines.values();
  for (std::size_t k = 0; k < DomainValues; ++k) domain[k] = domain_values.real(k);
  if (!domain_values.ok()) return malformed(domain_values.problem());

  if (auto stop = frame_lines.next({"scalar line", "s1 s2 s3 s4", 4})) return stop;
  LineValues scalar_values = frame_lines.values();
  for (std::size_t k = 0; k < scalars.size(); ++k) scalars[k] = scalar_values.real(k);
  if (!scalar_values.ok()) return malformed(scalar_values.problem());

  if (auto stop = frame_lines.next({triangle_count_name, "NT", 1})) return stop;
  LineValues triangle_count_values = frame_lines.values();
  counts.triangles = triangle_count_values.count(0);
  if (!triangle_count_values.ok()) return malformed(triangle_count_values.problem());

  if (auto stop = frame_lines.next({"count line", "step NP NW", 3})) return stop;
  LineValues count_values = frame_lines.values();
  step = count_values.integer64(0);
  counts.particles = count_values.count(1);
  counts.plates = count_values.count(2);
  if (!count_values.ok()) return malformed(count_values.problem());
  return std::nullopt;
}

std::optional<Stop> read_animation_frame(TokenLines& lines, AnimationFrame& frame) {
  if (auto stop = check_frame_header(lines, animation_header, 1, animation_header)) return stop;
  FrameLines frame_lines(lines, animation_header);
  FrameCounts counts;
  if (auto stop = read_frame_opening(frame_lines, "xmin xmax ymin ymax zmin zmax", "triangle count line", frame.domain,
                                     frame.scalars, frame.step, counts))
    return stop;
  const std::size_t particle_count = counts.particles, plate_count = counts.plates, triangle_count = counts.triangles;

  if (auto stop = read_polygons(frame_lines, "plate line", plate_layout, plate_word, plate_count, frame.plates))
    return stop;
  if (auto stop =
          read_polygons(frame_lines, "triangle line", triangle_layout, triangle_word, triangle_count, frame.triangles))
    return stop;

  frame.particles.reserve(safe_reserve(particle_count));
  for (std::size_t k = 0; k < particle_count; ++k) {
    if (auto stop = frame_lines.next({"particle line", particle_layout, 13, k + 1, particle_count})) return stop;
    LineValues values = frame_lines.values();
    AnimationParticle& particle = frame.particles.emplace_back();
    particle.id = values.integer(0);
    particle.position = values.vec3(1);
    particle.diameter = values.real(4);
    particle.velocity = values.vec3(5);
    particle.contacts = values.integer(8);
    particle.angular_velocity = values.vec3(9);
    particle.part = values.integer(12);
    if (!values.ok()) return malformed(values.problem());
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// ANIMATION_2D.dat: ANIMATION_3D.dat's layout with (x, z) points, a spin about y, segments for plates

constexpr std::string_view plate_2d_layout = "id rplate x1 z1 x2 z2";
constexpr std::string_view triangle_2d_layout = "id tri x1 z1 x2 z2";
constexpr std::string_view disc_layout = "id x z D vx vz nc w part";

std::optional<Stop> read_segments(FrameLines& frame_lines, std::string_view what, std::string_view layout,
                                  std::string_view word, std::size_t count, std::vector<AnimationSegment>& out) {
  out.reserve(safe_reserve(count));
  for (std::size_t k = 0; k < count; ++k) {
    if (auto stop = frame_lines.next({what, layout, 6, k + 1, count})) return stop;
    if (auto stop = frame_lines.check_word(1, word)) return stop;
    LineValues values = frame_lines.values();
    AnimationSegment& segment = out.emplace_back();
    segment.id = values.integer(0);
    segment.ends[0] = {values.real(2), values.real(3)};
    segment.ends[1] = {values.real(4), values.real(5)};
    if (!values.ok()) return malformed(values.problem());
  }
  return std::nullopt;
}

std::optional<Stop> read_animation_2d_frame(TokenLines& lines, Animation2DFrame& frame) {
  if (auto stop = check_frame_header(lines, animation_2d_header, 1, animation_2d_header)) return stop;
  FrameLines frame_lines(lines, animation_2d_header);
  FrameCounts counts;
  if (auto stop = read_frame_opening(frame_lines, "xmin xmax zmin zmax", "segment count line", frame.domain,
                                     frame.scalars, frame.step, counts))
    return stop;
  const std::size_t disc_count = counts.particles, plate_count = counts.plates, triangle_count = counts.triangles;

  if (auto stop = read_segments(frame_lines, "plate line", plate_2d_layout, plate_word, plate_count, frame.plates))
    return stop;
  if (auto stop = read_segments(frame_lines, "mesh segment line", triangle_2d_layout, triangle_word, triangle_count,
                                frame.triangles))
    return stop;

  frame.discs.reserve(safe_reserve(disc_count));
  for (std::size_t k = 0; k < disc_count; ++k) {
    if (auto stop = frame_lines.next({"disc line", disc_layout, 9, k + 1, disc_count})) return stop;
    LineValues values = frame_lines.values();
    AnimationDisc& disc = frame.discs.emplace_back();
    disc.id = values.integer(0);
    disc.position = {values.real(1), values.real(2)};
    disc.diameter = values.real(3);
    disc.velocity = {values.real(4), values.real(5)};
    disc.contacts = values.integer(6);
    disc.spin = values.real(7);
    disc.part = values.integer(8);
    if (!values.ok()) return malformed(values.problem());
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// ForceChain_3D.dat

constexpr std::string_view chain_layout = "i i-1 j Fn Ft";

std::optional<Stop> read_force_chain_frame(TokenLines& lines, ForceChainFrame& frame) {
  if (auto stop = check_frame_header(lines, force_chain_header, 3, "3DF: step NC")) return stop;
  LineValues header = LineValues(lines);
  frame.step = header.integer64(1);
  const std::size_t chain_count = header.count(2);
  if (!header.ok()) return malformed(header.problem());

  FrameLines frame_lines(lines, force_chain_header);
  frame.chains.reserve(safe_reserve(chain_count));
  for (std::size_t k = 0; k < chain_count; ++k) {
    if (auto stop = frame_lines.next({"chain line", chain_layout, 5, k + 1, chain_count})) return stop;
    LineValues values = frame_lines.values();
    ForceChain& chain = frame.chains.emplace_back();
    chain.i = values.integer(0);
    // Column 2 repeats i - 1 (a 0-based copy of i in the legacy writer); it carries nothing new.
    chain.j = values.integer(2);
    chain.normal_force = values.real(3);
    chain.tangential_force = values.real(4);
    if (!values.ok()) return malformed(values.problem());
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// Wall_Animation_3D.dat, Wall_ForceChain_3D.dat, Force_Displacement.dat

constexpr std::string_view wall_line_layout = "id rplate x1 y1 z1 ... x4 y4 z4, or id tri x1 y1 z1 ... x3 y3 z3";

std::optional<Stop> read_wall_frame(TokenLines& lines, WallFrame& frame) {
  if (auto stop = check_frame_header(lines, wall_header, 3, "3DW: step NW")) return stop;
  LineValues header = LineValues(lines);
  frame.step = header.integer64(1);
  const std::size_t count = header.count(2);
  if (!header.ok()) return malformed(header.problem());
  FrameLines frame_lines(lines, wall_header);
  for (std::size_t k = 0; k < count; ++k) {
    const Expected expected{"wall line", wall_line_layout, 0, k + 1, count};
    if (auto stop = frame_lines.next_any(expected)) return stop;
    const bool plate = frame_lines.token_count() >= 2 && frame_lines.token(1) == plate_word;
    const bool triangle = frame_lines.token_count() >= 2 && frame_lines.token(1) == triangle_word;
    const std::size_t corners = plate ? 4 : 3;
    if ((!plate && !triangle) || frame_lines.token_count() != 2 + 3 * corners)
      return malformed(line_prefix(frame_lines.line_number()) + "expected a wall line (" +
                       std::string(wall_line_layout) + "), found " + std::to_string(frame_lines.token_count()) +
                       " values");
    LineValues values = frame_lines.values();
    if (plate) {
      AnimationPlate& p = frame.plates.emplace_back();
      p.id = values.integer(0);
      for (std::size_t c = 0; c < 4; ++c) p.corners[c] = values.vec3(2 + 3 * c);
    } else {
      AnimationTriangle& t = frame.triangles.emplace_back();
      t.id = values.integer(0);
      for (std::size_t c = 0; c < 3; ++c) t.corners[c] = values.vec3(2 + 3 * c);
    }
    if (!values.ok()) return malformed(values.problem());
  }
  return std::nullopt;
}

std::optional<Stop> read_wall_force_chain_frame(TokenLines& lines, WallForceChainFrame& frame) {
  if (auto stop = check_frame_header(lines, wall_force_chain_header, 3, "3DWF: step NC")) return stop;
  LineValues header = LineValues(lines);
  frame.step = header.integer64(1);
  const std::size_t count = header.count(2);
  if (!header.ok()) return malformed(header.problem());
  FrameLines frame_lines(lines, wall_force_chain_header);
  frame.chains.reserve(safe_reserve(count));
  for (std::size_t k = 0; k < count; ++k) {
    if (auto stop = frame_lines.next({"wall chain line", "i wall Fn Ft", 4, k + 1, count})) return stop;
    LineValues values = frame_lines.values();
    WallForceChain& chain = frame.chains.emplace_back();
    chain.i = values.integer(0);
    chain.wall = values.integer(1);
    chain.normal_force = values.real(2);
    chain.tangential_force = values.real(3);
    if (!values.ok()) return malformed(values.problem());
  }
  return std::nullopt;
}

std::optional<Stop> read_force_displacement_row(TokenLines& lines, ForceDisplacementRow& row) {
  if (lines.token_count() != 3)
    return malformed(line_prefix(lines.line_number()) + "expected 3 values (time displacement force), found " +
                     std::to_string(lines.token_count()));
  LineValues values(lines);
  row.time = values.real(0);
  row.displacement = values.real(1);
  row.force = values.real(2);
  if (!values.ok()) return malformed(values.problem());
  return std::nullopt;
}

struct RowReader {
  std::size_t columns;
  std::optional<Stop> operator()(TokenLines& lines, std::vector<double>& row) const {
    if (lines.token_count() != columns)
      return malformed(line_prefix(lines.line_number()) + "expected " + std::to_string(columns) + " values, found " +
                       std::to_string(lines.token_count()));
    LineValues values(lines);
    row.resize(columns);
    for (std::size_t k = 0; k < columns; ++k) row[k] = values.real(k);
    if (!values.ok()) return malformed(values.problem());
    return std::nullopt;
  }
};

// An animation frame's header and the four lines after it (read_frame_opening).
template <std::size_t DomainValues>
void write_frame_opening(FrameText& text, std::string_view header, const std::array<double, DomainValues>& domain,
                         const std::array<double, 4>& scalars, const AnimationStyles& styles, std::int64_t step,
                         const FrameCounts& counts) {
  text.word(header);
  text.end_line();
  for (double value : domain) text.real(value, styles.domain);
  text.end_line();
  for (double value : scalars) text.real(value, styles.scalar);
  text.end_line();
  text.integer(static_cast<long long>(counts.triangles));
  text.end_line();
  text.integer(step);
  text.integer(static_cast<long long>(counts.particles));
  text.integer(static_cast<long long>(counts.plates));
  text.end_line();
}

// Plate lines ("id rplate" + 4 corners), then triangle lines ("id tri" + 3 corners).
void write_polygons(FrameText& text, const std::vector<AnimationPlate>& plates,
                    const std::vector<AnimationTriangle>& triangles, RealStyle style) {
  for (const AnimationPlate& plate : plates) {
    text.integer(plate.id);
    text.word(plate_word);
    for (const Vec3& corner : plate.corners) text.reals(corner, style);
    text.end_line();
  }
  for (const AnimationTriangle& triangle : triangles) {
    text.integer(triangle.id);
    text.word(triangle_word);
    for (const Vec3& corner : triangle.corners) text.reals(corner, style);
    text.end_line();
  }
}

}  // namespace

void write_row(std::FILE* out, const std::vector<double>& values, NumberFormat format) {
  const RealStyle style = style_of(format, fixed(4));
  FrameText text(1);
  for (double v : values) text.real(v, style);
  text.end_line();
  text.write_to(out);
}

ReadResult<std::vector<double>> read_rows(std::istream& in, std::size_t columns) {
  return read_frames<std::vector<double>>(in, RowReader{columns});
}

void write_wall_frame(std::FILE* out, const WallFrame& frame, NumberFormat format) {
  const RealStyle style = animation_styles(format).corner;
  FrameText text(1 + frame.plates.size() + frame.triangles.size());
  text.word(wall_header);
  text.integer(frame.step);
  text.integer(static_cast<long long>(frame.plates.size()) + static_cast<long long>(frame.triangles.size()));
  text.end_line();
  write_polygons(text, frame.plates, frame.triangles, style);
  text.write_to(out);
}

void write_wall_force_chain_frame(std::FILE* out, const WallForceChainFrame& frame, NumberFormat format) {
  const RealStyle style = force_style(format);
  FrameText text(1 + frame.chains.size());
  text.word(wall_force_chain_header);
  text.integer(frame.step);
  text.integer(static_cast<long long>(frame.chains.size()));
  text.end_line();
  for (const WallForceChain& chain : frame.chains) {
    text.integer(chain.i);
    text.integer(chain.wall);
    text.real(chain.normal_force, style);
    text.real(chain.tangential_force, style);
    text.end_line();
  }
  text.write_to(out);
}

void write_force_displacement_row(std::FILE* out, const ForceDisplacementRow& row, NumberFormat format) {
  const RealStyle style = style_of(format, fixed(4));
  FrameText text(1);
  text.real(row.time, style);
  text.real(row.displacement, style);
  text.real(row.force, force_style(format));
  text.end_line();
  text.write_to(out);
}

ReadResult<WallFrame> read_wall_frames(std::istream& in) { return read_frames<WallFrame>(in, read_wall_frame); }

ReadResult<WallForceChainFrame> read_wall_force_chains(std::istream& in) {
  return read_frames<WallForceChainFrame>(in, read_wall_force_chain_frame);
}

ReadResult<ForceDisplacementRow> read_force_displacement(std::istream& in) {
  return read_frames<ForceDisplacementRow>(in, read_force_displacement_row);
}

void write_animation_frame(std::FILE* out, const AnimationFrame& frame, NumberFormat format) {
  const AnimationStyles styles = animation_styles(format);
  FrameText text(5 + frame.plates.size() + frame.triangles.size() + frame.particles.size());
  write_frame_opening(text, animation_header, frame.domain, frame.scalars, styles, frame.step,
                      {frame.triangles.size(), frame.particles.size(), frame.plates.size()});

  write_polygons(text, frame.plates, frame.triangles, styles.corner);
  for (const AnimationParticle& particle : frame.particles) {
    text.integer(particle.id);
    text.reals(particle.position, styles.position);
    text.real(particle.diameter, styles.diameter);
    text.reals(particle.velocity, styles.velocity);
    text.integer(particle.contacts);
    text.reals(particle.angular_velocity, styles.angular_velocity);
    text.integer(particle.part);
    text.end_line();
  }
  text.write_to(out);
}

void write_force_chain_frame(std::FILE* out, const ForceChainFrame& frame, NumberFormat format) {
  const RealStyle style = force_style(format);
  FrameText text(1 + frame.chains.size());

  text.word(force_chain_header);
  text.integer(frame.step);
  text.integer(static_cast<long long>(frame.chains.size()));
  text.end_line();
  for (const ForceChain& chain : frame.chains) {
    text.integer(chain.i);
    text.integer(static_cast<long long>(chain.i) - 1);
    text.integer(chain.j);
    text.real(chain.normal_force, style);
    text.real(chain.tangential_force, style);
    text.end_line();
  }
  text.write_to(out);
}

void write_animation_2d_frame(std::FILE* out, const Animation2DFrame& frame, NumberFormat format) {
  const AnimationStyles styles = animation_styles(format);
  FrameText text(5 + frame.plates.size() + frame.triangles.size() + frame.discs.size());
  write_frame_opening(text, animation_2d_header, frame.domain, frame.scalars, styles, frame.step,
                      {frame.triangles.size(), frame.discs.size(), frame.plates.size()});
  for (const auto* segments : {&frame.plates, &frame.triangles})
    for (const AnimationSegment& segment : *segments) {
      text.integer(segment.id);
      text.word(segments == &frame.plates ? plate_word : triangle_word);
      for (const Vec2& end : segment.ends) {
        text.real(end.x(), styles.corner);
        text.real(end.y(), styles.corner);
      }
      text.end_line();
    }
  for (const AnimationDisc& disc : frame.discs) {
    text.integer(disc.id);
    text.real(disc.position.x(), styles.position);
    text.real(disc.position.y(), styles.position);
    text.real(disc.diameter, styles.diameter);
    text.real(disc.velocity.x(), styles.velocity);
    text.real(disc.velocity.y(), styles.velocity);
    text.integer(disc.contacts);
    text.real(disc.spin, styles.angular_velocity);
    text.integer(disc.part);
    text.end_line();
  }
  text.write_to(out);
}

ReadResult<Animation2DFrame> read_animation_2d(std::istream& in) {
  return read_frames<Animation2DFrame>(in, read_animation_2d_frame);
}

ReadResult<AnimationFrame> read_animation(std::istream& in) {
  return read_frames<AnimationFrame>(in, read_animation_frame);
}

ReadResult<ForceChainFrame> read_force_chains(std::istream& in) {
  return read_frames<ForceChainFrame>(in, read_force_chain_frame);
}

}  // namespace dem::legacy
