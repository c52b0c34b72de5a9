// The main thread's side of file parsing: hands each File to a parse worker of its own and gets the
// frames back as transferred typed arrays, so the page keeps drawing and answering while a large
// file is read. One worker a parse: cancelling a parse stops its worker and nothing else (a replay
// parsing beside a file load goes on). When no module worker can be started (an old browser, or the
// page opened from file://), the same parser runs on the main thread, in chunks.

import { parseBlob, cancelled } from './parse.js';

let workersBroken = false;

function startWorker() {
  if (workersBroken) return null;
  try {
    // dist/parse_worker.js sits next to dist/viewer.js: relative to this bundle, any serving path
    return new Worker(new URL('./parse_worker.js', import.meta.url), { type: 'module' });
  } catch {
    workersBroken = true;
    return null;
  }
}

// Parses one File; resolves with parse.js's result { kind, frames | mesh, truncated, problem }.
// `signal` (an AbortSignal, optional) cancels it: the promise rejects with an AbortError at once and
// the parse's worker is stopped.
export function parseFile(file, onProgress = () => {}, signal = null) {
  if (signal && signal.aborted) return Promise.reject(cancelled());
  const worker = startWorker();
  if (!worker) return parseBlob(file, onProgress, undefined, signal);
  return new Promise((resolve, reject) => {
    let settled = false;
    const finish = (settle, value) => {
      if (settled) return;
      settled = true;
      worker.terminate();
      if (signal) signal.removeEventListener('abort', abort);
      settle(value);
    };
    const abort = () => finish(reject, cancelled());
    if (signal) signal.addEventListener('abort', abort, { once: true });
    worker.onmessage = (event) => {
      const { type } = event.data;
      if (type === 'progress') onProgress(event.data.fraction);
      else if (type === 'done') finish(resolve, event.data.result);
      else finish(reject, new Error(event.data.error));
    };
    // The worker script failed to load or crashed: this parse, and the next ones, on the main thread.
    worker.onerror = (event) => {
      event.preventDefault();
      if (settled) return;
      workersBroken = true;
      settled = true;
      worker.terminate();
      parseBlob(file, onProgress, undefined, signal).then(resolve, reject).finally(() => {
        if (signal) signal.removeEventListener('abort', abort);
      });
    };
    worker.postMessage({ id: 1, file });
  });
}
