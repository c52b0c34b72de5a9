// ForceChain_3D.dat (docs/formats.md section 4): a sequence of frames
//
//   3DF: step NC
//   NC lines   i i-1 j Fn Ft      1-based particle ids (i < j), normal force, tangential force
//
// The second column is a 0-based copy of i: checked as an integer, then skipped. Returns frames of
// { step, count, i, j (0-based ids, Int32Array), fn, ft (Float32Array) }, every complete frame, and
// stops at the first problem as the animation reader does.

import { allocate, ensure } from './growable.js';
import { checkLine, ended, Stop, Values } from './frame_lines.js';

export const CHAIN_HEADER = '3DF:';

const CHAIN = { name: 'chain line', layout: 'i i-1 j Fn Ft', columns: 5 };

export class ForceChainParser {
  constructor() {
    this.frames = [];
    this.frame = null;
  }

  line(tokens, lineNumber) {
    const stop = this.frame ? this.chain(tokens, lineNumber) : this.header(tokens, lineNumber);
    if (stop) this.stop = stop;
    return !stop;
  }

  header(tokens, lineNumber) {
    if (tokens[0] !== CHAIN_HEADER || tokens.length !== 3) {
      return new Stop(`line ${lineNumber}: expected the frame header '${CHAIN_HEADER} step NC', found ` +
        `'${tokens[0].slice(0, 40)}'${tokens.length > 1 ? ' and more' : ''}`);
    }
    const values = new Values(tokens, lineNumber);
    const step = values.step(1);
    const count = values.count(2);
    if (values.problem) return new Stop(values.problem);
    this.frameLine = lineNumber;
    this.frame = {
      step, count,
      i: allocate(Int32Array, count, 1), j: allocate(Int32Array, count, 1),
      fn: allocate(Float32Array, count, 1), ft: allocate(Float32Array, count, 1),
    };
    this.index = 0;
    if (count === 0) this.complete();
    return null;
  }

  chain(tokens, lineNumber) {
    const bad = checkLine(tokens, lineNumber, this.expected(), CHAIN_HEADER, this.frameLine);
    if (bad) return bad;
    const values = new Values(tokens, lineNumber);
    const f = this.frame;
    const n = this.index;
    if (n >= f.i.length) {
      f.i = ensure(f.i, n + 1);
      f.j = ensure(f.j, n + 1);
      f.fn = ensure(f.fn, n + 1);
      f.ft = ensure(f.ft, n + 1);
    }
    f.i[n] = values.id(0) - 1;
    values.integer(1);
    f.j[n] = values.id(2) - 1;
    f.fn[n] = values.real(3);
    f.ft[n] = values.real(4);
    if (values.problem) return new Stop(values.problem);
    this.index += 1;
    if (this.index === f.count) this.complete();
    return null;
  }

  expected() {
    return { ...CHAIN, index: this.index + 1, total: this.frame.count };
  }

  complete() {
    const f = this.frame;
    if (f.i.length !== f.count) {
      f.i = f.i.slice(0, f.count);
      f.j = f.j.slice(0, f.count);
      f.fn = f.fn.slice(0, f.count);
      f.ft = f.ft.slice(0, f.count);
    }
    this.frames.push(f);
    this.frame = null;
  }

  finish(end) {
    if (!this.stop && this.frame) this.stop = ended(this.expected(), this.frameLine, end);
    if (!this.stop && end.unfinishedLastLine) {
      this.stop = new Stop(`the file ends inside a frame header: the last line (line ${end.lastLine}) has no line end, ` +
        'the writer was stopped while writing it', true);
    }
    return {
      kind: 'forceChains',
      frames: this.frames,
      truncated: this.stop ? this.stop.truncated : false,
      problem: this.stop ? this.stop.problem : '',
    };
  }
}
