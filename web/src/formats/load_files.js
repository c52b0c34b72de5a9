// The main thread's side of file parsing: hands each File to the parse worker and gets the frames
// back as transferred typed arrays, so the page keeps drawing and answering while a large file is
// read. When no module worker can be started (an old browser, or the page opened from file://),
// the same parser runs on the main thread, in chunks.

import { parseBlob } from './parse.js';

let worker = null;
let workerBroken = false;
let nextId = 1;
const pending = new Map(); // id -> { resolve, reject, onProgress }

function startWorker() {
  if (worker || workerBroken) return worker;
  try {
    // dist/parse_worker.js sits next to dist/viewer.js: relative to this bundle, any serving path
    worker = new Worker(new URL('./parse_worker.js', import.meta.url), { type: 'module' });
  } catch {
    workerBroken = true;
    return null;
  }
  worker.onmessage = (event) => {
    const { id, type } = event.data;
    const job = pending.get(id);
    if (!job) return;
    if (type === 'progress') job.onProgress(event.data.fraction);
    else {
      pending.delete(id);
      if (type === 'done') job.resolve(event.data.result);
      else job.reject(new Error(event.data.error));
    }
  };
  // The worker script failed to load or crashed: finish its jobs on the main thread instead.
  worker.onerror = (event) => {
    event.preventDefault();
    workerBroken = true;
    worker.terminate();
    worker = null;
    const jobs = [...pending.values()];
    pending.clear();
    for (const job of jobs) parseBlob(job.file, job.onProgress).then(job.resolve, job.reject);
  };
  return worker;
}

// The error a parse cancelled through its AbortSignal rejects with.
export function cancelled() {
  return new DOMException('the load was cancelled', 'AbortError');
}

// Parses one File; resolves with parse.js's result { kind, frames | mesh, truncated, problem }.
// `signal` (an AbortSignal, optional) cancels it: the promise rejects with an AbortError at once and
// the worker parsing the file is stopped (a new one starts with the next file).
export function parseFile(file, onProgress = () => {}, signal = null) {
  if (signal && signal.aborted) return Promise.reject(cancelled());
  const w = startWorker();
  if (!w) return parseBlob(file, onProgress, undefined, signal);
  return new Promise((resolve, reject) => {
    const id = nextId++;
    const done = (settle) => (value) => {
      if (signal) signal.removeEventListener('abort', abort);
      settle(value);
    };
    const abort = () => {
      if (!pending.delete(id)) return;
      // a worker cannot be interrupted in the middle of a parse: stopped, with the parses it holds
      stopWorker();
      reject(cancelled());
    };
    pending.set(id, { resolve: done(resolve), reject: done(reject), onProgress, file });
    if (signal) signal.addEventListener('abort', abort, { once: true });
    w.postMessage({ id, file });
  });
}

// Stops the worker; the parses still pending in it are cancelled.
function stopWorker() {
  if (!worker) return;
  worker.terminate();
  worker = null;
  const jobs = [...pending.values()];
  pending.clear();
  for (const job of jobs) job.reject(cancelled());
}
