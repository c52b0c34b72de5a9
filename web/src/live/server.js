// The dem-server's REST API and frames WebSocket (docs/api.md), relative to the page's origin.
// An access token in the page's URL (`?access_token=TOKEN`) is forwarded: as
// `Authorization: Bearer TOKEN` on fetch, as `?access_token=TOKEN` on the WebSocket (browsers cannot
// set its headers).

// A failed request: `status` (HTTP, 0 when the server could not be reached), `error` and
// `problems` from the server's {"error", "problems"} answer. `message` is the text to show.
export class ServerError extends Error {
  constructor(status, error, problems = []) {
    const text = problems && problems.length ? `${error}: ${problems.join('; ')}` : error;
    super(text);
    this.name = 'ServerError';
    this.status = status;
    this.error = error;
    this.problems = problems || [];
  }
}

const config = { base: null, token: undefined };

function pageLocation() {
  return typeof window !== 'undefined' && window.location ? window.location : null;
}

// The server's origin: the page's, or one set with setServer (tests, Node).
export function serverBase() {
  if (config.base) return config.base;
  const loc = pageLocation();
  if (loc && /^https?:$/.test(loc.protocol)) return loc.origin;
  return null;
}

// Is there a server behind this page (http(s), not a file opened offline)?
export function hasServer() {
  return serverBase() !== null;
}

// For tests and Node: use this server ("http://127.0.0.1:18600") and token (undefined: the page's).
export function setServer(base, token) {
  config.base = base ? String(base).replace(/\/+$/, '') : null;
  config.token = token;
}

// The access token of the page's URL, or null.
export function accessToken() {
  if (config.token !== undefined) return config.token || null;
  const loc = pageLocation();
  if (!loc) return null;
  try {
    return new URLSearchParams(loc.search).get('access_token') || null;
  } catch {
    return null;
  }
}

function url(path) {
  const base = serverBase();
  if (!base) throw new ServerError(0, 'no server: this page was not opened from dem-server');
  return base + path;
}

function headers(extra = {}) {
  const h = { ...extra };
  const token = accessToken();
  if (token) h.Authorization = `Bearer ${token}`;
  return h;
}

// The server's error answer as a ServerError (JSON {"error", "problems"} or plain text).
async function errorOf(response) {
  let text = '';
  try {
    text = await response.text();
  } catch {
    /* no body */
  }
  let error = `${response.status} ${response.statusText || ''}`.trim();
  let problems = [];
  if (text) {
    try {
      const body = JSON.parse(text);
      if (body && typeof body.error === 'string') error = body.error;
      if (body && Array.isArray(body.problems)) problems = body.problems.map(String);
    } catch {
      error = `${error}: ${text.slice(0, 200)}`;
    }
  }
  return new ServerError(response.status, error, problems);
}

async function request(path, options = {}) {
  let response;
  try {
    response = await fetch(url(path), { ...options, headers: headers(options.headers) });
  } catch (e) {
    if (e instanceof ServerError) throw e;
    throw new ServerError(0, `the server could not be reached (${e && e.message ? e.message : e})`);
  }
  if (!response.ok) throw await errorOf(response);
  return response;
}

async function json(path, options) {
  const response = await request(path, options);
  if (response.status === 204) return null;
  return response.json();
}

const id = (jobId) => encodeURIComponent(String(jobId));

// GET /api/jobs (optionally ?state=): the jobs, oldest first.
export async function listJobs(state) {
  const body = await json(state ? `/api/jobs?state=${encodeURIComponent(state)}` : '/api/jobs');
  return (body && body.jobs) || [];
}

// GET /api/jobs/{id}: the job object.
export function getJob(jobId) {
  return json(`/api/jobs/${id(jobId)}`);
}

// POST /api/jobs: submits a spec (an object or JSON text); returns the job object.
export function submitJob(spec, { idempotencyKey } = {}) {
  const body = typeof spec === 'string' ? spec : JSON.stringify(spec);
  const extra = { 'Content-Type': 'application/json' };
  if (idempotencyKey) extra['Idempotency-Key'] = idempotencyKey;
  return json('/api/jobs', { method: 'POST', body, headers: extra });
}

// POST /api/jobs/{id}/cancel.
export function cancelJob(jobId) {
  return json(`/api/jobs/${id(jobId)}/cancel`, { method: 'POST' });
}

// GET /api/cases: [{name, title, description}].
export async function listCases() {
  const body = await json('/api/cases');
  return (body && body.cases) || [];
}

// GET /api/cases/{name}: the case's job spec (meshes inlined), ready to submit.
export function getCase(name) {
  return json(`/api/cases/${encodeURIComponent(name)}`);
}

// GET /api/jobs/{id}/artifacts: [{name, size, url}].
export async function listArtifacts(jobId) {
  const body = await json(`/api/jobs/${id(jobId)}/artifacts`);
  return (body && body.artifacts) || [];
}

// GET /api/jobs/{id}/artifacts/{name} as text. onProgress(received, total) while it downloads
// (total: Content-Length, or 0 when unknown).
export async function downloadArtifact(jobId, name, options = {}) {
  return (await downloadArtifactBlob(jobId, name, options)).text();
}

// GET /api/jobs/{id}/artifacts/{name} as a Blob (for the parse worker), with onProgress as above.
export async function downloadArtifactBlob(jobId, name, { onProgress, signal } = {}) {
  const response = await request(`/api/jobs/${id(jobId)}/artifacts/${encodeURIComponent(name)}`, { signal });
  if (!onProgress || !response.body || typeof response.body.getReader !== 'function') return response.blob();
  const total = Number(response.headers.get('Content-Length')) || 0;
  const reader = response.body.getReader();
  const pieces = [];
  let received = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    received += value.length;
    pieces.push(value);
    onProgress(received, total);
  }
  return new Blob(pieces, { type: 'text/plain' });
}

// The frames WebSocket's URL: ws(s)://host/api/jobs/{id}/frames[?forceChains=1][&access_token=].
export function framesUrl(jobId, { forceChains = false } = {}) {
  const base = url(`/api/jobs/${id(jobId)}/frames`).replace(/^http/, 'ws');
  const query = new URLSearchParams();
  if (forceChains) query.set('forceChains', '1');
  const token = accessToken();
  if (token) query.set('access_token', token);
  const q = query.toString();
  return q ? `${base}?${q}` : base;
}

// Opens the frames WebSocket of a job (binaryType arraybuffer). Handlers: onMessage(ArrayBuffer),
// onClose(code, reason), onError(event). Returns the socket; setForceChains(socket, on) asks for
// force chains (or stops them) while it is open.
export function openFrames(jobId, { forceChains = false, onMessage, onClose, onError, WebSocketImpl } = {}) {
  const Impl = WebSocketImpl || globalThis.WebSocket;
  if (!Impl) throw new ServerError(0, 'this browser has no WebSocket');
  const socket = new Impl(framesUrl(jobId, { forceChains }));
  socket.binaryType = 'arraybuffer';
  if (onMessage) {
    socket.onmessage = (e) => {
      if (typeof e.data !== 'string') onMessage(e.data);
    };
  }
  if (onClose) socket.onclose = (e) => onClose(e.code, e.reason);
  if (onError) socket.onerror = (e) => onError(e);
  return socket;
}

export function setForceChains(socket, on) {
  if (socket && socket.readyState === 1) socket.send(JSON.stringify({ forceChains: !!on }));
}

// GET /api/studies: the parameter studies, as GET /api/studies/{id} gives each.
export async function listStudies() {
  const body = await json('/api/studies');
  return (body && body.studies) || [];
}

// GET /api/studies/{id}: the study, with its runs' jobs and parameter values.
export function getStudy(studyId) {
  return json(`/api/studies/${id(studyId)}`);
}
