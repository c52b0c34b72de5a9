// A legacy triangle-mesh boundary `.dat` (docs/formats.md section 1):
//
//   NV NT        vertex count, triangle count
//   NV lines     x y z
//   NT lines     i j k      1-based vertex indices
//
// Unlike the frame files, a mesh is all or nothing (as engine/mesh/mesh_io.cpp): a truncated file,
// extra lines, a non-number, an index out of range or a degenerate triangle is an error naming the
// line. Commas count as separators. Returns { vertices: Float32Array, triangles: Uint32Array (0-based) }.

import { allocate, ensure } from './growable.js';
import { Stop, Values } from './frame_lines.js';

export class MeshParser {
  constructor() {
    this.vertexCount = -1; // -1 until the header is read
    this.vertexIndex = 0;
    this.triangleIndex = 0;
    this.vertexLines = [];
  }

  line(tokens, lineNumber) {
    const stop = this.read(tokens, lineNumber);
    if (stop) this.stop = stop;
    return !stop;
  }

  read(tokens, n) {
    const values = new Values(tokens, n);
    if (this.vertexCount < 0) {
      if (tokens.length !== 2) return new Stop(`line ${n}: expected the header 'NV NT' (2 values), found ${tokens.length}`);
      this.vertexCount = values.count(0);
      this.triangleCount = values.count(1);
      if (values.problem) return new Stop(values.problem);
      this.vertices = allocate(Float32Array, this.vertexCount, 3);
      this.triangles = allocate(Uint32Array, this.triangleCount, 3);
      return null;
    }
    if (this.vertexIndex < this.vertexCount) {
      if (tokens.length !== 3) return new Stop(`line ${n}: expected 3 values on vertex line ${this.vertexIndex + 1} of ${this.vertexCount} (x y z), found ${tokens.length}`);
      const k = this.vertexIndex;
      this.vertices = ensure(this.vertices, k * 3 + 3);
      for (let c = 0; c < 3; c++) this.vertices[k * 3 + c] = values.real(c);
      this.vertexIndex += 1;
      return values.problem ? new Stop(values.problem) : null;
    }
    if (this.triangleIndex < this.triangleCount) {
      if (tokens.length !== 3) return new Stop(`line ${n}: expected 3 values on triangle line ${this.triangleIndex + 1} of ${this.triangleCount} (i j k), found ${tokens.length}`);
      const t = this.triangleIndex;
      this.triangles = ensure(this.triangles, t * 3 + 3);
      for (let c = 0; c < 3; c++) {
        const index = values.id(c);
        if (!values.problem && index > this.vertexCount) values.fail(c, `is not a vertex: the file has ${this.vertexCount}`);
        this.triangles[t * 3 + c] = index - 1;
      }
      if (values.problem) return new Stop(values.problem);
      const why = this.degenerate(t);
      if (why) return new Stop(`line ${n}: triangle ${t + 1} is degenerate (${why})`);
      this.triangleIndex += 1;
      return null;
    }
    return new Stop(`line ${n}: extra line after the ${this.vertexCount} vertices and ${this.triangleCount} triangles the header announces`);
  }

  // Why triangle t has no area, or '' when it has one.
  degenerate(t) {
    const [a, b, c] = this.triangles.subarray(t * 3, t * 3 + 3);
    if (a === b || b === c || a === c) return 'a vertex repeats';
    const v = this.vertices;
    const u = [v[b * 3] - v[a * 3], v[b * 3 + 1] - v[a * 3 + 1], v[b * 3 + 2] - v[a * 3 + 2]];
    const w = [v[c * 3] - v[a * 3], v[c * 3 + 1] - v[a * 3 + 1], v[c * 3 + 2] - v[a * 3 + 2]];
    const cross = u[1] * w[2] - u[2] * w[1] || u[2] * w[0] - u[0] * w[2] || u[0] * w[1] - u[1] * w[0];
    return cross === 0 ? 'its corners are on one line' : '';
  }

  finish(end) {
    let problem = this.stop ? this.stop.problem : '';
    if (!problem && this.vertexCount < 0) {
      problem = 'the file is empty';
    } else if (!problem && (this.vertexIndex < this.vertexCount || this.triangleIndex < this.triangleCount)) {
      const what = this.vertexIndex < this.vertexCount
        ? `vertex line ${this.vertexIndex + 1} of ${this.vertexCount}`
        : `triangle line ${this.triangleIndex + 1} of ${this.triangleCount}`;
      problem = `the file ends at line ${end.lastLine}: its ${what} is missing (truncated)`;
    }
    if (problem) return { kind: 'mesh', mesh: null, truncated: false, problem };
    return {
      kind: 'mesh',
      mesh: {
        vertices: this.vertices.length === this.vertexCount * 3 ? this.vertices : this.vertices.slice(0, this.vertexCount * 3),
        triangles: this.triangles.length === this.triangleCount * 3 ? this.triangles : this.triangles.slice(0, this.triangleCount * 3),
      },
      truncated: false,
      problem: '',
    };
  }
}
