// Tells the three legacy files apart by content and drives their parsers over text that arrives in
// chunks. Used by the Web Worker (parse_worker.js), by the main thread when no worker can be
// started, and by Node checks (parseText).
//
//   first token '3DA:'          ANIMATION_3D.dat    (animation.js)
//   first token '2DA:'          ANIMATION_2D.dat    (animation.js: a 2D run's discs)
//   first token '3DF:'          ForceChain_3D.dat   (force_chains.js)
//   first line  'NV NT'         mesh .dat           (mesh.js)

import { AnimationParser, ANIMATION_HEADER, ANIMATION_2D_HEADER } from './animation.js';
import { ForceChainParser, CHAIN_HEADER } from './force_chains.js';
import { MeshParser } from './mesh.js';
import { LineSplitter } from './lines.js';
import { parseInteger } from './numbers.js';
import { addStats } from './stats.js';

// The kind of file whose first non-blank line holds `tokens`, or null.
export function detectKind(tokens) {
  if (tokens[0] === ANIMATION_HEADER || tokens[0] === ANIMATION_2D_HEADER) return 'animation';
  if (tokens[0] === CHAIN_HEADER) return 'forceChains';
  const header = tokens.length === 1 ? tokens[0].split(',') : tokens; // "NV,NT" also counts
  if (header.length === 2 && header.every((t) => parseInteger(t) >= 0)) return 'mesh';
  return null;
}

// Parses one file fed with push(text) and closed with finish(). The result is
//   { kind: 'animation' | 'forceChains' | 'mesh' | null, frames | mesh, truncated, problem }.
export class ChunkedParse {
  constructor() {
    this.parser = null;
    this.kind = null;
    this.splitter = null;
    this.head = ''; // text before the first non-blank line is complete
  }

  push(text) {
    if (this.splitter) return this.splitter.push(text);
    this.head += text;
    const kind = this.detect();
    if (kind === undefined) return true; // first line not complete yet
    if (kind === null) return false;
    const head = this.head;
    this.head = '';
    return this.splitter.push(head);
  }

  // Chooses the parser from the first non-blank line; undefined while that line is incomplete.
  detect(atEnd = false) {
    const lines = this.head.split('\n');
    const complete = atEnd ? lines.length : lines.length - 1;
    for (let k = 0; k < complete; k++) {
      const tokens = lines[k].split(/[ \t\r\f\v]+/).filter((t) => t !== '');
      if (!tokens.length) continue;
      this.kind = detectKind(tokens);
      if (!this.kind) {
        this.unknown = `line ${k + 1}: not a DEM file: it starts with '${lines[k].trim().slice(0, 40)}', ` +
          "expected '3DA:' (ANIMATION_3D.dat), '2DA:' (ANIMATION_2D.dat), '3DF: step NC' (ForceChain_3D.dat) " +
          "or 'NV NT' (mesh .dat)";
        return null;
      }
      this.parser = this.kind === 'animation' ? new AnimationParser()
        : this.kind === 'forceChains' ? new ForceChainParser() : new MeshParser();
      const mesh = this.kind === 'mesh';
      this.splitter = new LineSplitter((t, n) => this.parser.line(t, n), { commas: mesh, useUnfinished: mesh });
      return this.kind;
    }
    if (this.head.length > (1 << 20)) { // a megabyte without a line end: not a text file of ours
      this.unknown = 'not a DEM file: no line end in its first megabyte';
      return null;
    }
    return undefined;
  }

  finish() {
    if (!this.splitter && !this.unknown) {
      if (this.detect(true) === null) return { kind: null, truncated: false, problem: this.unknown };
      if (!this.splitter) return { kind: null, truncated: false, problem: 'the file is empty' };
      const head = this.head;
      this.head = '';
      this.splitter.push(head);
    }
    if (this.unknown) return { kind: null, truncated: false, problem: this.unknown };
    const result = this.parser.finish(this.splitter.end());
    if (result.kind === 'animation') result.frames.forEach(addStats);
    if (result.kind === 'forceChains') result.frames.forEach(addStats);
    return result;
  }
}

// Parses a whole text at once (Node checks, small files).
export function parseText(text) {
  const parse = new ChunkedParse();
  parse.push(text);
  return parse.finish();
}

// The error a cancelled parse rejects with (an AbortSignal's abort).
export function cancelled() {
  return new DOMException('the load was cancelled', 'AbortError');
}

// Reads a Blob/File in pieces so that neither the text nor the parse blocks for long, and reports
// progress as a fraction. Works in a worker and on the main thread.
export async function parseBlob(blob, onProgress = () => {}, chunkBytes = 4 << 20, signal = null) {
  const parse = new ChunkedParse();
  const decoder = new TextDecoder('utf-8');
  for (let at = 0; at < blob.size; at += chunkBytes) {
    if (signal && signal.aborted) throw cancelled();
    const bytes = await blob.slice(at, Math.min(at + chunkBytes, blob.size)).arrayBuffer();
    const more = parse.push(decoder.decode(bytes, { stream: at + chunkBytes < blob.size }));
    onProgress(Math.min(at + chunkBytes, blob.size) / blob.size);
    if (!more) break;
  }
  return parse.finish();
}

// The typed arrays of a result, for postMessage's transfer list (no copy to the main thread).
export function transferables(result) {
  const buffers = new Set();
  const add = (a) => { if (a && a.buffer) buffers.add(a.buffer); };
  if (result.mesh) { add(result.mesh.vertices); add(result.mesh.triangles); }
  for (const f of result.frames || []) {
    for (const key of ['ids', 'positions', 'velocities', 'radii', 'parts', 'contacts', 'spins', 'plates', 'triangles', 'domain', 'i', 'j', 'fn', 'ft']) add(f[key]);
  }
  return [...buffers];
}
