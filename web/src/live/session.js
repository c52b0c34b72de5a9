// One follow or replay of a job. The panel has one current session; starting another ends it, and
// every late answer of an ended one (a download, a parse, a frame, a reconnect) is dropped on
// `ended`. Ending aborts its downloads and stops its parses (their worker is terminated).

export class Session {
  constructor(job) {
    this.job = job;
    this.controller = new AbortController();
    this.ended = false;
    this.generation = undefined; // the viewer's run generation: setRun's answer
    this.lastFrame = null; // the newest live frame
    this.statsSizes = new Map(); // statistics file -> its size when last read
    this.statsInFlight = 0; // statistics reads running
  }

  get signal() {
    return this.controller.signal;
  }

  end() {
    if (this.ended) return;
    this.ended = true;
    this.controller.abort();
  }
}

export function errorText(e) {
  if (!e) return 'unknown error';
  return e.message || String(e);
}

export function percent(progress) {
  const p = Number(progress);
  return Number.isFinite(p) ? `${(100 * p).toFixed(p < 0.1 ? 1 : 0)}%` : '';
}

export const ACTIVE = new Set(['queued', 'running']);
