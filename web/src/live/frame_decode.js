// Decodes the server's live frames: protobuf `Frame` messages (proto/dem.proto, messages Frame and
// WallShape) read straight from the wire format, with no protobuf library.
//
// The server writes one frame as up to three pieces of the same message (the base, the radii, the
// force chains), concatenated: protobuf merge semantics apply. A field present twice: the last one
// wins (scalars and bytes alike); a repeated field (`walls`) collects every occurrence.
//
// decodeFrameMessage(bytes) -> the raw fields (typed arrays, numbers); toFrame(raw, previous) -> the
// contract's frame (docs/viewer.md, "The run model"); FrameDecoder keeps the last radii across
// frames, since the server sends them only in a viewer's first frame and when they change.

// Field numbers of Frame and WallShape, by their proto names: the browser test reads
// proto/dem.proto and checks every field of both messages is here with its number (this table once
// drifted: clump positions and orientations were sent and silently skipped).
export const FRAME_FIELDS = Object.freeze({
  job: 1, step: 2, total_steps: 3, time: 4, particle_count: 5, positions: 6, velocities: 7, radii: 8,
  fragments: 9, force_chains: 10, walls: 11, kinetic_energy: 12, clump_positions: 13,
  clump_orientations: 14, stage: 15, absent_walls: 16, planar: 17,
});
export const WALL_SHAPE_FIELDS = Object.freeze({ wall: 1, triangles: 2 });
const F_JOB = FRAME_FIELDS.job;
const F_STEP = FRAME_FIELDS.step;
const F_TOTAL_STEPS = FRAME_FIELDS.total_steps;
const F_TIME = FRAME_FIELDS.time;
const F_PARTICLE_COUNT = FRAME_FIELDS.particle_count;
const F_POSITIONS = FRAME_FIELDS.positions;
const F_VELOCITIES = FRAME_FIELDS.velocities;
const F_RADII = FRAME_FIELDS.radii;
const F_FRAGMENTS = FRAME_FIELDS.fragments;
const F_FORCE_CHAINS = FRAME_FIELDS.force_chains;
const F_WALLS = FRAME_FIELDS.walls;
const F_KINETIC_ENERGY = FRAME_FIELDS.kinetic_energy;
const F_CLUMP_POSITIONS = FRAME_FIELDS.clump_positions;
const F_CLUMP_ORIENTATIONS = FRAME_FIELDS.clump_orientations;
const F_STAGE = FRAME_FIELDS.stage;
const F_ABSENT_WALLS = FRAME_FIELDS.absent_walls;
const F_PLANAR = FRAME_FIELDS.planar; // a 2D run: discs in the x-z plane
const W_WALL = WALL_SHAPE_FIELDS.wall;
const W_TRIANGLES = WALL_SHAPE_FIELDS.triangles;

// Wire types.
const VARINT = 0;
const FIXED64 = 1;
const LEN = 2;
const START_GROUP = 3;
const END_GROUP = 4;
const FIXED32 = 5;

const LITTLE_ENDIAN = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;

export class FrameDecodeError extends Error {}

// A cursor over the bytes of one message.
class Reader {
  constructor(bytes, start = 0, end = bytes.length) {
    this.bytes = bytes;
    this.pos = start;
    this.end = end;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  }

  done() {
    return this.pos >= this.end;
  }

  // An unsigned varint as a Number (exact up to 2^53); 64-bit values past that go through BigInt
  // and are read as int64 (two's complement), which is what every int64/uint32 field here holds.
  varint() {
    const b = this.bytes;
    let result = 0;
    let scale = 1;
    const start = this.pos;
    for (let k = 0; k < 10; k++) {
      if (this.pos >= this.end) throw new FrameDecodeError(`truncated varint at byte ${start}`);
      const byte = b[this.pos++];
      result += (byte & 0x7f) * scale;
      if ((byte & 0x80) === 0) {
        if (k < 7) return result;
        return this.bigVarint(start);
      }
      scale *= 128;
    }
    throw new FrameDecodeError(`varint longer than 10 bytes at byte ${start}`);
  }

  bigVarint(start) {
    let value = 0n;
    let shift = 0n;
    for (let p = start; p < this.pos; p++) {
      value |= BigInt(this.bytes[p] & 0x7f) << shift;
      shift += 7n;
    }
    return Number(BigInt.asIntN(64, value));
  }

  double() {
    if (this.pos + 8 > this.end) throw new FrameDecodeError(`truncated double at byte ${this.pos}`);
    const v = this.view.getFloat64(this.pos, true);
    this.pos += 8;
    return v;
  }

  // The [start, end) range of a length-delimited field's content.
  span() {
    const len = this.varint();
    const start = this.pos;
    if (len < 0 || start + len > this.end) throw new FrameDecodeError(`length ${len} at byte ${start} runs past the message`);
    this.pos = start + len;
    return [start, start + len];
  }

  skip(wireType, field) {
    switch (wireType) {
      case VARINT: this.varint(); return;
      case FIXED64: this.advance(8); return;
      case LEN: this.span(); return;
      case FIXED32: this.advance(4); return;
      case START_GROUP: {
        // A group (deprecated): skip fields up to the matching end-group tag.
        for (;;) {
          if (this.done()) throw new FrameDecodeError(`unterminated group ${field}`);
          const tag = this.varint();
          const wt = tag & 7;
          if (wt === END_GROUP) return;
          this.skip(wt, Math.floor(tag / 8));
        }
      }
      default:
        throw new FrameDecodeError(`wire type ${wireType} of field ${field} at byte ${this.pos}`);
    }
  }

  advance(n) {
    if (this.pos + n > this.end) throw new FrameDecodeError(`truncated field at byte ${this.pos}`);
    this.pos += n;
  }
}

// Copies bytes [start, end) into a new, aligned typed array of the given kind (Float32Array or
// Int32Array); the wire is little-endian.
function typedCopy(bytes, start, end, Kind) {
  const n = Math.floor((end - start) / 4);
  const out = new Kind(n);
  if (LITTLE_ENDIAN) {
    new Uint8Array(out.buffer).set(bytes.subarray(start, start + 4 * n));
  } else {
    const view = new DataView(bytes.buffer, bytes.byteOffset + start, 4 * n);
    const get = Kind === Float32Array ? (i) => view.getFloat32(4 * i, true) : (i) => view.getInt32(4 * i, true);
    for (let i = 0; i < n; i++) out[i] = get(i);
  }
  return out;
}

function asBytes(data) {
  if (data instanceof Uint8Array) return data;
  if (data instanceof ArrayBuffer) return new Uint8Array(data);
  if (ArrayBuffer.isView(data)) return new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  throw new FrameDecodeError('a frame must be an ArrayBuffer or a typed array');
}

function decodeWallShape(bytes, start, end) {
  const r = new Reader(bytes, start, end);
  let wall = 0;
  let triangles = new Float32Array(0);
  while (!r.done()) {
    const tag = r.varint();
    const field = Math.floor(tag / 8);
    const wt = tag & 7;
    if (field === W_WALL && wt === VARINT) wall = r.varint() >>> 0;
    else if (field === W_TRIANGLES && wt === LEN) {
      const [s, e] = r.span();
      triangles = typedCopy(bytes, s, e, Float32Array);
    } else r.skip(wt, field);
  }
  return { wall, triangles };
}

// The raw fields of one Frame message (pieces concatenated). Absent fields are 0 or null (arrays);
// `present` lists the field numbers seen.
export function decodeFrameMessage(data) {
  const bytes = asBytes(data);
  const r = new Reader(bytes);
  const raw = {
    job: 0, step: 0, totalSteps: 0, time: 0, particleCount: 0,
    positions: null, velocities: null, radii: null, fragments: null, forceChains: null,
    walls: [], kineticEnergy: 0, stage: '', planar: false,
    clumpPositions: null, clumpOrientations: null, absentWalls: [],
    present: new Set(),
  };
  while (!r.done()) {
    const tag = r.varint();
    const field = Math.floor(tag / 8);
    const wt = tag & 7;
    if (field === 0) throw new FrameDecodeError(`field number 0 at byte ${r.pos}`);
    let known = true;
    switch (field) {
      case F_JOB: if (wt === VARINT) raw.job = r.varint(); else known = false; break;
      case F_STEP: if (wt === VARINT) raw.step = r.varint(); else known = false; break;
      case F_TOTAL_STEPS: if (wt === VARINT) raw.totalSteps = r.varint(); else known = false; break;
      case F_PARTICLE_COUNT: if (wt === VARINT) raw.particleCount = r.varint() >>> 0; else known = false; break;
      case F_TIME: if (wt === FIXED64) raw.time = r.double(); else known = false; break;
      case F_KINETIC_ENERGY: if (wt === FIXED64) raw.kineticEnergy = r.double(); else known = false; break;
      case F_PLANAR: if (wt === VARINT) raw.planar = r.varint() !== 0; else known = false; break;
      case F_ABSENT_WALLS: {  // repeated uint32: packed (proto3's way) or one varint each
        if (wt === VARINT) raw.absentWalls.push(r.varint() >>> 0);
        else if (wt === LEN) {
          const [s, e] = r.span();
          const packed = new Reader(bytes, s, e);
          while (!packed.done()) raw.absentWalls.push(packed.varint() >>> 0);
        } else known = false;
        break;
      }
      case F_POSITIONS:
      case F_VELOCITIES:
      case F_RADII:
      case F_FRAGMENTS:
      case F_FORCE_CHAINS:
      case F_CLUMP_POSITIONS:
      case F_CLUMP_ORIENTATIONS: {
        if (wt !== LEN) { known = false; break; }
        const [s, e] = r.span();
        if (field === F_CLUMP_POSITIONS) raw.clumpPositions = typedCopy(bytes, s, e, Float32Array);
        else if (field === F_CLUMP_ORIENTATIONS) raw.clumpOrientations = typedCopy(bytes, s, e, Float32Array);
        else if (field === F_POSITIONS) raw.positions = typedCopy(bytes, s, e, Float32Array);
        else if (field === F_VELOCITIES) raw.velocities = typedCopy(bytes, s, e, Float32Array);
        else if (field === F_RADII) raw.radii = typedCopy(bytes, s, e, Float32Array);
        else if (field === F_FRAGMENTS) raw.fragments = typedCopy(bytes, s, e, Int32Array);
        else raw.forceChains = decodeForceChains(bytes, s, e);
        break;
      }
      case F_STAGE: {
        if (wt !== LEN) { known = false; break; }
        const [s, e] = r.span();
        raw.stage = new TextDecoder().decode(bytes.subarray(s, e));
        break;
      }
      case F_WALLS: {
        if (wt !== LEN) { known = false; break; }
        const [s, e] = r.span();
        raw.walls.push(decodeWallShape(bytes, s, e));
        break;
      }
      default: known = false;
    }
    if (known) raw.present.add(field);
    else r.skip(wt, field);
  }
  return raw;
}

// 16-byte records: int32 i, int32 j (0-based), float32 Fn, float32 Ft.
function decodeForceChains(bytes, start, end) {
  const n = Math.floor((end - start) / 16);
  const view = new DataView(bytes.buffer, bytes.byteOffset + start, 16 * n);
  const i = new Int32Array(n);
  const j = new Int32Array(n);
  const fn = new Float32Array(n);
  const ft = new Float32Array(n);
  for (let k = 0, o = 0; k < n; k++, o += 16) {
    i[k] = view.getInt32(o, true);
    j[k] = view.getInt32(o + 4, true);
    fn[k] = view.getFloat32(o + 8, true);
    ft[k] = view.getFloat32(o + 12, true);
  }
  return { i, j, fn, ft };
}

const zerosCache = { Int32: new Int32Array(0), Float32: new Float32Array(0) };
function zerosInt32(n) {
  if (zerosCache.Int32.length !== n) zerosCache.Int32 = new Int32Array(n);
  return zerosCache.Int32;   // shared, read-only by convention
}
function zerosFloat32(n) {
  if (zerosCache.Float32.length !== n) zerosCache.Float32 = new Float32Array(n);
  return zerosCache.Float32;
}

function concatFloat32(arrays) {
  if (arrays.length === 1) return arrays[0];
  let n = 0;
  for (const a of arrays) n += a.length;
  const out = new Float32Array(n);
  let o = 0;
  for (const a of arrays) { out.set(a, o); o += a.length; }
  return out;
}

// The contract's frame from the raw fields. `previousRadii`: the last radii received (a Float32Array),
// used when this frame carries none. Lengths are metres (the run's unit "m").
export function toFrame(raw, previousRadii = null) {
  let count = raw.particleCount;
  if (!count && raw.positions) count = Math.floor(raw.positions.length / 3);
  const positions = raw.positions && raw.positions.length >= 3 * count ? raw.positions : padFloat32(raw.positions, 3 * count);
  const velocities = raw.velocities && raw.velocities.length >= 3 * count ? raw.velocities : padFloat32(raw.velocities, 3 * count);
  let radii = raw.radii || previousRadii;
  let radiiMissing = false;
  if (!radii || radii.length < count) {
    radiiMissing = !radii;
    radii = padFloat32(radii, count);
  }
  const parts = raw.fragments && raw.fragments.length >= count ? raw.fragments : zerosInt32(count);
  const triangles = raw.walls.length ? concatFloat32(raw.walls.map((w) => w.triangles)) : new Float32Array(0);
  return {
    job: raw.job,
    step: raw.step,
    totalSteps: raw.totalSteps,
    time: raw.time,
    count,
    positions,
    velocities,
    radii,
    radiiMissing,
    radiiChanged: raw.radii !== null,
    parts,
    plates: new Float32Array(0),
    triangles,
    walls: raw.walls,
    stage: raw.stage,
    planar: raw.planar,
    forceChains: raw.forceChains,
    scalars: { time: raw.time, plateDisplacement: 0, plateForce: 0, kineticEnergy: raw.kineticEnergy },
  };
}

function padFloat32(a, n) {
  if (!a) return n ? new Float32Array(n) : zerosFloat32(0);
  const out = new Float32Array(n);
  out.set(a.subarray(0, Math.min(a.length, n)));
  return out;
}

// Decodes one binary message into the contract's frame (no radii carried over).
export function decodeFrame(data, previousRadii = null) {
  return toFrame(decodeFrameMessage(data), previousRadii);
}

// Decodes the frames of one WebSocket in order, keeping the last radii.
export class FrameDecoder {
  constructor() {
    this.radii = null;
    this.frames = 0;
  }

  decode(data) {
    const raw = decodeFrameMessage(data);
    const frame = toFrame(raw, this.radii);
    if (raw.radii) this.radii = raw.radii;
    this.frames++;
    return frame;
  }

  reset() {
    this.radii = null;
    this.frames = 0;
  }
}
