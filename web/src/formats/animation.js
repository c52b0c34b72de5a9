// ANIMATION_3D.dat (docs/formats.md section 3): a sequence of frames
//
//   3DA:
//   xmin xmax ymin ymax zmin zmax
//   s1 s2 s3 s4                      time, plate displacement, plate force, kinetic energy
//   NT                               moving mesh triangles
//   step NP NW                       step, particles, plates
//   NW plate lines     id rplate x1 y1 z1 ... x4 y4 z4
//   NT triangle lines  id tri x1 y1 z1 ... x3 y3 z3
//   NP particle lines  id x y z D vx vy vz nc wx wy wz part
//
// ANIMATION_2D.dat (section 3a, a 2D run's discs in the x-z plane) has the same frames with (x, z) points:
//
//   2DA:
//   xmin xmax zmin zmax
//   s1 s2 s3 s4
//   NT                               moving mesh segments
//   step NP NW
//   NW plate lines     id rplate x1 z1 x2 z2      where a plate crosses the plane
//   NT segment lines   id tri x1 z1 x2 z2         where a moving mesh's triangle crosses it
//   NP disc lines      id x z D vx vz nc w part
//
// Its frames come out as 3D frames at y = 0 (frame.planar), so every control works on them; a segment
// becomes a thin band in the plane (a plate of four corners, or two triangles), which a camera looking
// along y shows as a line.
//
// Fed line by line (see lines.js) so a 150 MB file is never one string. Returns every complete
// frame and stops at the first problem, as the engine's reader does: `truncated` when the input
// ends inside a frame (the writer was killed), otherwise `problem` names the malformed line.

import { allocate, ensure } from './growable.js';
import { checkLine, ended, Stop, Values } from './frame_lines.js';

export const ANIMATION_HEADER = '3DA:';
export const ANIMATION_2D_HEADER = '2DA:';

const DOMAIN = { name: 'domain line', layout: 'xmin xmax ymin ymax zmin zmax', columns: 6 };
const SCALARS = { name: 'scalar line', layout: 's1 s2 s3 s4', columns: 4 };
const TRIANGLE_COUNT = { name: 'triangle count line', layout: 'NT', columns: 1 };
const COUNTS = { name: 'count line', layout: 'step NP NW', columns: 3 };
const PLATE = { name: 'plate line', layout: 'id rplate x1 y1 z1 x2 y2 z2 x3 y3 z3 x4 y4 z4', columns: 14 };
const TRIANGLE = { name: 'triangle line', layout: 'id tri x1 y1 z1 x2 y2 z2 x3 y3 z3', columns: 11 };
const PARTICLE = { name: 'particle line', layout: 'id x y z D vx vy vz nc wx wy wz part', columns: 13 };
const DOMAIN_2D = { name: 'domain line', layout: 'xmin xmax zmin zmax', columns: 4 };
const SEGMENT_COUNT = { name: 'segment count line', layout: 'NT', columns: 1 };
const PLATE_2D = { name: 'plate line', layout: 'id rplate x1 z1 x2 z2', columns: 6 };
const SEGMENT = { name: 'mesh segment line', layout: 'id tri x1 z1 x2 z2', columns: 6 };
const DISC = { name: 'disc line', layout: 'id x z D vx vz nc w part', columns: 9 };

// The lines of a frame of each file, in order.
const LAYOUTS = {
  [ANIMATION_HEADER]: { domain: DOMAIN, triangleCount: TRIANGLE_COUNT, plate: PLATE, triangle: TRIANGLE, particle: PARTICLE },
  [ANIMATION_2D_HEADER]: { domain: DOMAIN_2D, triangleCount: SEGMENT_COUNT, plate: PLATE_2D, triangle: SEGMENT, particle: DISC },
};

// The corners (x, 0, z) of a band of width w along the segment (x1, z1)-(x2, z2), centred on it.
function band(x1, z1, x2, z2, w) {
  const length = Math.hypot(x2 - x1, z2 - z1) || 1;
  const nx = (-(z2 - z1) / length) * w / 2, nz = ((x2 - x1) / length) * w / 2;
  return [[x1 - nx, z1 - nz], [x2 - nx, z2 - nz], [x2 + nx, z2 + nz], [x1 + nx, z1 + nz]];
}

export class AnimationParser {
  constructor() {
    this.frames = [];
    this.frame = null; // the frame being read
    this.expected = null; // what the next line must be; null between frames
    this.index = 0; // lines read of the current repeated kind
  }

  // One non-blank line; returns false when reading stops (this.stop says why).
  line(tokens, lineNumber) {
    const stop = this.expected ? this.body(tokens, lineNumber) : this.header(tokens, lineNumber);
    if (stop) this.stop = stop;
    return !stop;
  }

  header(tokens, lineNumber) {
    // the first frame's header says which file this is; every frame after it has the same
    if (!this.headerWord && LAYOUTS[tokens[0]]) this.headerWord = tokens[0];
    const header = this.headerWord || ANIMATION_HEADER;
    if (tokens[0] !== header || tokens.length !== 1) {
      return new Stop(`line ${lineNumber}: expected the frame header '${header}', found ` +
        `'${tokens[0].slice(0, 40)}'${tokens.length > 1 ? ' and more' : ''}`);
    }
    this.layout = LAYOUTS[header];
    this.planar = header === ANIMATION_2D_HEADER;
    this.frameLine = lineNumber;
    this.frame = { domain: new Float64Array(6), step: 0, count: 0, planar: this.planar };
    this.expected = this.layout.domain;
    return null;
  }

  body(tokens, lineNumber) {
    const expected = this.repeated();
    const bad = checkLine(tokens, lineNumber, expected, this.headerWord, this.frameLine);
    if (bad) return bad;
    const values = new Values(tokens, lineNumber);
    const frame = this.frame;
    const layout = this.layout;
    switch (this.expected) {
      case DOMAIN:
        for (let k = 0; k < 6; k++) frame.domain[k] = values.real(k);
        this.expected = SCALARS;
        break;
      case DOMAIN_2D: {
        const [x0, x1, z0, z1] = [values.real(0), values.real(1), values.real(2), values.real(3)];
        frame.domain.set([x0, x1, 0, 0, z0, z1]);
        // a wall's band: thin beside the scene, but wide enough to be seen
        this.bandWidth = 0.004 * Math.max(Math.abs(x1 - x0), Math.abs(z1 - z0)) || 1e-3;
        this.expected = SCALARS;
        break;
      }
      case SCALARS: {
        const s = [values.real(0), values.real(1), values.real(2), values.real(3)];
        frame.scalars = { time: s[0], plateDisplacement: s[1], plateForce: s[2], kineticEnergy: s[3] };
        frame.time = s[0];
        this.expected = layout.triangleCount;
        break;
      }
      case TRIANGLE_COUNT:
      case SEGMENT_COUNT:
        this.triangleCount = values.count(0);
        this.expected = COUNTS;
        break;
      case COUNTS:
        frame.step = values.step(0);
        frame.count = values.count(1);
        this.plateCount = values.count(2);
        if (values.problem) break;
        frame.plates = allocate(Float32Array, this.plateCount, 12);
        frame.triangles = allocate(Float32Array, this.triangleCount * this.trianglesPerLine(), 9);
        frame.ids = allocate(Int32Array, frame.count, 1);
        frame.positions = allocate(Float32Array, frame.count, 3);
        frame.velocities = allocate(Float32Array, frame.count, 3);
        frame.radii = allocate(Float32Array, frame.count, 1);
        frame.parts = allocate(Int32Array, frame.count, 1);
        frame.contacts = allocate(Int32Array, frame.count, 1);
        frame.spins = allocate(Float32Array, frame.count, 3);
        this.index = 0;
        this.expected = layout.plate;
        break;
      case PLATE: {
        values.integer(0);
        values.word(1, 'rplate');
        frame.plates = ensure(frame.plates, (this.index + 1) * 12);
        for (let k = 0; k < 12; k++) frame.plates[this.index * 12 + k] = values.real(2 + k);
        this.index += 1;
        break;
      }
      case TRIANGLE: {
        values.integer(0);
        values.word(1, 'tri');
        frame.triangles = ensure(frame.triangles, (this.index + 1) * 9);
        for (let k = 0; k < 9; k++) frame.triangles[this.index * 9 + k] = values.real(2 + k);
        this.index += 1;
        break;
      }
      case PLATE_2D: {
        values.integer(0);
        values.word(1, 'rplate');
        frame.plates = ensure(frame.plates, (this.index + 1) * 12);
        const corners = band(values.real(2), values.real(3), values.real(4), values.real(5), this.bandWidth);
        corners.forEach(([x, z], c) => frame.plates.set([x, 0, z], this.index * 12 + c * 3));
        this.index += 1;
        break;
      }
      case SEGMENT: {
        values.integer(0);
        values.word(1, 'tri');
        frame.triangles = ensure(frame.triangles, (this.index + 1) * 18);
        const [a, b, c, d] = band(values.real(2), values.real(3), values.real(4), values.real(5), this.bandWidth);
        [a, b, c, a, c, d].forEach(([x, z], k) => frame.triangles.set([x, 0, z], this.index * 18 + k * 3));
        this.index += 1;
        break;
      }
      case DISC: {
        const n = this.index;
        if (n * 3 + 3 > frame.positions.length) this.grow(n + 1);
        frame.ids[n] = values.integer(0);
        frame.positions[n * 3] = values.real(1);
        frame.positions[n * 3 + 1] = 0;
        frame.positions[n * 3 + 2] = values.real(2);
        frame.radii[n] = values.real(3) / 2;
        frame.velocities[n * 3] = values.real(4);
        frame.velocities[n * 3 + 1] = 0;
        frame.velocities[n * 3 + 2] = values.real(5);
        frame.contacts[n] = values.integer(6);
        frame.spins[n * 3] = 0;
        frame.spins[n * 3 + 1] = values.real(7); // a disc in the x-z plane turns about y
        frame.spins[n * 3 + 2] = 0;
        frame.parts[n] = values.integer(8);
        this.index += 1;
        break;
      }
      case PARTICLE: {
        const n = this.index;
        if (n * 3 + 3 > frame.positions.length) this.grow(n + 1);
        frame.ids[n] = values.integer(0);
        frame.positions[n * 3] = values.real(1);
        frame.positions[n * 3 + 1] = values.real(2);
        frame.positions[n * 3 + 2] = values.real(3);
        frame.radii[n] = values.real(4) / 2;
        frame.velocities[n * 3] = values.real(5);
        frame.velocities[n * 3 + 1] = values.real(6);
        frame.velocities[n * 3 + 2] = values.real(7);
        frame.contacts[n] = values.integer(8);
        frame.spins[n * 3] = values.real(9);
        frame.spins[n * 3 + 1] = values.real(10);
        frame.spins[n * 3 + 2] = values.real(11);
        frame.parts[n] = values.integer(12);
        this.index += 1;
        break;
      }
    }
    if (values.problem) return new Stop(values.problem);
    this.advance();
    return null;
  }

  // The Expected of the next line, numbered among its kind ("particle line 12 of 400").
  repeated() {
    const e = this.expected;
    const layout = this.layout;
    if (!layout) return e;
    if (e === layout.plate) return { ...e, index: this.index + 1, total: this.plateCount };
    if (e === layout.triangle) return { ...e, index: this.index + 1, total: this.triangleCount };
    if (e === layout.particle) return { ...e, index: this.index + 1, total: this.frame.count };
    return e;
  }

  // Moves past the finished kinds of lines; completes the frame after its last particle.
  advance() {
    const layout = this.layout;
    if (this.expected === layout.plate && this.index === this.plateCount) {
      this.expected = layout.triangle;
      this.index = 0;
    }
    if (this.expected === layout.triangle && this.index === this.triangleCount) {
      this.expected = layout.particle;
      this.index = 0;
    }
    if (this.expected === layout.particle && this.index === this.frame.count) this.complete();
  }

  // Triangles drawn per triangle line: a 2D file's segment is a band of two.
  trianglesPerLine() {
    return this.planar ? 2 : 1;
  }

  grow(particles) {
    const f = this.frame;
    f.ids = ensure(f.ids, particles);
    f.positions = ensure(f.positions, particles * 3);
    f.velocities = ensure(f.velocities, particles * 3);
    f.radii = ensure(f.radii, particles);
    f.parts = ensure(f.parts, particles);
    f.contacts = ensure(f.contacts, particles);
    f.spins = ensure(f.spins, particles * 3);
  }

  complete() {
    const f = this.frame;
    // Arrays grown by doubling may be longer than the counts: cut them to size.
    f.ids = f.ids.length === f.count ? f.ids : f.ids.slice(0, f.count);
    f.positions = f.positions.length === f.count * 3 ? f.positions : f.positions.slice(0, f.count * 3);
    f.velocities = f.velocities.length === f.count * 3 ? f.velocities : f.velocities.slice(0, f.count * 3);
    f.radii = f.radii.length === f.count ? f.radii : f.radii.slice(0, f.count);
    f.parts = f.parts.length === f.count ? f.parts : f.parts.slice(0, f.count);
    f.contacts = f.contacts.length === f.count ? f.contacts : f.contacts.slice(0, f.count);
    f.spins = f.spins.length === f.count * 3 ? f.spins : f.spins.slice(0, f.count * 3);
    f.plates = f.plates.length === this.plateCount * 12 ? f.plates : f.plates.slice(0, this.plateCount * 12);
    const triangleFloats = this.triangleCount * this.trianglesPerLine() * 9;
    f.triangles = f.triangles.length === triangleFloats ? f.triangles : f.triangles.slice(0, triangleFloats);
    f.forceChains = null;
    f.line = this.frameLine; // where the frame starts in the file, for messages
    this.frames.push(f);
    this.frame = null;
    this.expected = null;
  }

  // The input ended. `end` is LineSplitter.end()'s answer.
  finish(end) {
    if (!this.stop && this.expected) this.stop = ended(this.repeated(), this.frameLine, end);
    if (!this.stop && end.unfinishedLastLine) {
      this.stop = new Stop(`the file ends inside a frame header: the last line (line ${end.lastLine}) has no line end, ` +
        'the writer was stopped while writing it', true);
    }
    return {
      kind: 'animation',
      frames: this.frames,
      truncated: this.stop ? this.stop.truncated : false,
      problem: this.stop ? this.stop.problem : '',
    };
  }
}
