// The live side of the viewer, in #live-panel (docs/viewer.md): the server's jobs (#jobs), following
// a running job's frames (#live-step), replaying a finished job (#replay), and a bundled case to
// submit (#case-select, #case-duration, #case-friction, #case-spec, #submit-case). Charts go to
// #charts (charts.js).
//
// main.js: `import('./live/panel.js').then((m) => m.initLivePanel(viewer))`. The Viewer methods used
// are those of the contract: setRun, addFrame, setForceChains, setMesh, message; `viewer.live` is set
// to true while a job is followed (or viewer.setLive(bool) when the core has it).

import * as server from './server.js';
import { FrameDecoder } from './frame_decode.js';
import { counted } from '../words.js';
import { Charts } from './charts.js';
import { formatSpec } from './spec_format.js';
import { parseFile } from '../formats/load_files.js';
import { addStats } from '../formats/stats.js';

const ACTIVE = new Set(['queued', 'running']);
const POLL_MS = 1000;
const STATS_EVERY_POLLS = 5; // statistics files of a followed job re-read every 5 s (when their size changed)
const STATS_FILES = ['Force_Displacement.dat', 'Fragments.dat', 'Bond_Breaks.dat'];
const RECONNECTS = 5;
const METRES_PER = { m: 1, cm: 0.01, mm: 0.001 };

// The element with this id, made (tag, attributes, parent) when the page has none.
function ensure(id, tag, parent, attributes = {}) {
  let el = document.getElementById(id);
  if (!el) {
    el = document.createElement(tag);
    el.id = id;
    for (const [k, v] of Object.entries(attributes)) {
      if (k === 'text') el.textContent = v;
      else el.setAttribute(k, v);
    }
    if (parent) parent.appendChild(el);
  }
  return el;
}

function make(tag, parent, attributes = {}) {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === 'text') el.textContent = v;
    else if (k === 'className') el.className = v;
    else el.setAttribute(k, v);
  }
  if (parent) parent.appendChild(el);
  return el;
}

function errorText(e) {
  if (!e) return 'unknown error';
  return e.message || String(e);
}

function percent(progress) {
  const p = Number(progress);
  return Number.isFinite(p) ? `${(100 * p).toFixed(p < 0.1 ? 1 : 0)}%` : '';
}

// The panel's own look (the page's style.css is the core's): added once to <head>.
const STYLE = `
.live-panel .live-jobs, .live-panel .live-follow, .live-panel .live-case { margin-bottom: 10px; }
#jobs { list-style: none; padding: 0; margin: 4px 0; max-height: 220px; overflow-y: auto; }
#jobs li { display: grid; grid-template-columns: auto 1fr auto; gap: 0 6px; align-items: center; padding: 3px 4px;
  border: 1px solid transparent; border-radius: 4px; cursor: pointer; font-size: 12px; }
#jobs li:hover { border-color: var(--border, #ccd); }
#jobs li.selected { background: rgba(31, 111, 235, .12); border-color: var(--accent, #1f6feb); }
#jobs li .job-id { font-variant-numeric: tabular-nums; color: var(--muted, #667); }
#jobs li .job-name { overflow: hidden; text-overflow: ellipsis; white-space: nowrap; }
#jobs li .job-state { font-weight: 600; }
#jobs li[data-state=running] .job-state { color: var(--accent, #1f6feb); }
#jobs li[data-state=failed] .job-state, #jobs li[data-state=interrupted] .job-state { color: var(--error, #b3261e); }
#jobs li .job-bar { grid-column: 1 / 3; width: 100%; height: 6px; }
#jobs li .job-progress { font-variant-numeric: tabular-nums; color: var(--muted, #667); }
.live-panel #live-step { font-variant-numeric: tabular-nums; font-weight: 600; }
.live-panel #live-status { word-break: break-word; }
.live-panel #live-server-status.error { color: var(--error, #b3261e); }
.live-panel #case-select { width: 100%; }
.live-panel #case-spec { width: 100%; min-height: 160px; font: 11px/1.35 ui-monospace, Menlo, Consolas, monospace;
  white-space: pre; overflow: auto; resize: vertical; }
.live-panel #case-spec.error { outline: 2px solid var(--error, #b3261e); }
.live-panel .live-quick label { display: flex; align-items: center; gap: 6px; margin: 4px 0; }
`;

function addStyle() {
  if (document.getElementById('live-panel-style')) return;
  const style = document.createElement('style');
  style.id = 'live-panel-style';
  style.textContent = STYLE;
  document.head.appendChild(style);
}

class LivePanel {
  constructor(viewer) {
    this.viewer = viewer || {};
    this.session = 0; // bumped by every follow / replay / stop: late answers of older ones are dropped
    this.openToken = 0; // bumped by every job click: an older click's late answer opens nothing
    this.downloads = null; // AbortController of the current follow / replay's downloads
    this.generation = undefined; // the viewer's run generation (setRun's answer) of the current follow / replay
    this.statsInFlight = 0; // loadStatsCharts calls running
    this.statsSizes = new Map(); // statistics file -> its size when last read (current follow / replay)
    this.socket = null;
    this.selected = null; // the job followed or replayed: {id, state, name, ...}
    this.jobs = new Map(); // id -> job object (last poll)
    this.cases = [];
    this.caseSpecs = new Map();
    this.polls = 0;
    this.polling = false;
    this.spec = null; // the case form's spec (object), mirrors #case-spec
    this.build();
  }

  // ---- page ------------------------------------------------------------------------------------

  build() {
    addStyle();
    const root = document.getElementById('live-panel') || make('section', document.body, { id: 'live-panel' });
    this.root = root;
    root.classList.add('live-panel');

    const jobsBox = document.getElementById('jobs') ? null : make('div', root, { className: 'live-jobs' });
    if (jobsBox) make('h2', jobsBox, { text: 'Server jobs' });
    this.serverStatus = ensure('live-server-status', 'div', jobsBox || root, { class: 'hint live-note' });
    this.jobList = ensure('jobs', 'ul', jobsBox || root, { class: 'job-list', 'aria-label': 'jobs of the server' });
    this.jobList.addEventListener('click', (e) => {
      const li = e.target.closest && e.target.closest('li[data-id]');
      if (li && this.jobList.contains(li)) this.open(Number(li.dataset.id));
    });
    this.jobList.addEventListener('keydown', (e) => {
      const li = e.target.closest && e.target.closest('li[data-id]');
      if (li && (e.key === 'Enter' || e.key === ' ')) {
        e.preventDefault();
        this.open(Number(li.dataset.id));
      }
    });

    const follow = document.getElementById('live-step') ? null : make('div', root, { className: 'live-follow' });
    if (follow) {
      const line = make('div', follow);
      make('span', line, { text: 'Job ' });
      this.jobLabel = make('span', line, { id: 'live-job', text: 'none' });
      make('span', line, { text: ' · step ' });
    }
    this.stepLabel = ensure('live-step', 'span', follow ? follow.firstChild : root);
    this.jobLabel = this.jobLabel || ensure('live-job', 'span', follow || root);
    this.statusLabel = ensure('live-status', 'div', follow || root, { class: 'hint live-note' });
    const buttons = follow ? make('div', follow, { className: 'buttons live-buttons' }) : root;
    this.replayButton = ensure('replay', 'button', buttons, { type: 'button', text: 'Replay', title: "load the finished job's ANIMATION_3D.dat or ANIMATION_2D.dat (and ForceChain_3D.dat) and play it" });
    this.stopButton = ensure('live-stop', 'button', buttons, { type: 'button', text: 'Stop following' });
    this.cancelButton = ensure('live-cancel', 'button', buttons, { type: 'button', text: 'Cancel job' });
    this.replayButton.disabled = true;
    this.stopButton.disabled = true;
    this.cancelButton.disabled = true;
    this.replayButton.addEventListener('click', () => {
      if (this.selected) this.replay(this.selected.id);
    });
    this.stopButton.addEventListener('click', () => this.stopFollowing('stopped following'));
    this.cancelButton.addEventListener('click', () => this.cancelSelected());

    const form = document.getElementById('case-select') ? null : make('div', root, { className: 'live-case' });
    if (form) make('h2', form, { text: 'Run a bundled case' });
    this.caseSelect = ensure('case-select', 'select', form || root, { 'aria-label': 'bundled case' });
    this.caseDescription = ensure('case-description', 'p', form || root, { class: 'hint live-note' });
    const quick = form ? make('div', form, { className: 'live-quick' }) : root;
    let label = form ? make('label', quick, { text: 'Duration (s) ' }) : quick;
    this.durationInput = ensure('case-duration', 'input', label, { type: 'number', min: '0', step: 'any', title: 'time.duration of the spec, s' });
    label = form ? make('label', quick, { text: 'Friction ' }) : quick;
    this.frictionInput = ensure('case-friction', 'input', label, { type: 'number', min: '0', step: 'any', title: 'the friction of every interaction' });
    this.specText = ensure('case-spec', 'textarea', form || root, { rows: '12', spellcheck: 'false', 'aria-label': 'job spec (JSON)' });
    const submitRow = form ? make('div', form, { className: 'buttons' }) : root;
    this.submitButton = ensure('submit-case', 'button', submitRow, { type: 'button', text: 'Submit' });
    this.submitButton.disabled = true;

    this.caseSelect.addEventListener('change', () => this.loadCase(this.caseSelect.value));
    this.durationInput.addEventListener('input', () => this.quickEdit('duration'));
    this.frictionInput.addEventListener('input', () => this.quickEdit('friction'));
    this.specText.addEventListener('input', () => this.specEdited());
    this.submitButton.addEventListener('click', () => this.submit());

    this.charts = new Charts(document.getElementById('charts'));
    // The charts mark the time of the frame in view (viewer.onChange, when the core has it).
    if (typeof this.viewer.onChange === 'function' && typeof this.viewer.state === 'function') {
      this.viewer.onChange(() => {
        const state = this.viewer.state();
        this.charts.setCursor(state && state.time !== null ? Number(state.time) : NaN);
      });
    }

    // Chains: asked of the server only while the viewer shows them.
    const chains = document.getElementById('show-force-chains');
    if (chains) {
      chains.addEventListener('change', () => {
        if (this.socket) server.setForceChains(this.socket, chains.checked);
      });
    }
    // Opening files replaces the run: stop adding live frames to it.
    const files = document.getElementById('file-input');
    if (files) files.addEventListener('change', () => this.stopFollowing());
    document.addEventListener('drop', (e) => {
      if (e.dataTransfer && e.dataTransfer.files && e.dataTransfer.files.length) this.stopFollowing();
    });
  }

  start() {
    if (!server.hasServer()) {
      this.serverStatus.textContent = 'No server: this page was opened from a file. Jobs need dem-server.';
      this.root.dataset.server = 'none';
      this.caseSelect.disabled = true;
      return this;
    }
    this.root.dataset.server = 'yes';
    this.refreshJobs();
    this.timer = setInterval(() => this.refreshJobs(), POLL_MS);
    this.loadCases();
    // a link to a job (?job=N, as scripts/start prints it) opens it at once: live or replayed
    const wanted = Number(new URLSearchParams(window.location.search).get('job'));
    if (Number.isInteger(wanted) && wanted > 0) this.open(wanted);
    return this;
  }

  say(text, isError = false) {
    if (typeof this.viewer.message === 'function') {
      try {
        this.viewer.message(text, isError);
        return;
      } catch (e) {
        console.error(e);
      }
    }
    (isError ? console.error : console.log)(text);
    this.statusLabel.textContent = text;
  }

  setLive(on) {
    try {
      if (typeof this.viewer.setLive === 'function') this.viewer.setLive(on);
      else this.viewer.live = on;
    } catch (e) {
      console.warn('viewer.live could not be set', e);
    }
    this.root.dataset.live = on ? 'true' : 'false';
  }

  call(method, ...args) {
    const f = this.viewer[method];
    if (typeof f !== 'function') {
      console.warn(`the viewer has no ${method}()`);
      return undefined;
    }
    return f.apply(this.viewer, args);
  }

  // ---- job list --------------------------------------------------------------------------------

  async refreshJobs() {
    if (this.polling) return;
    this.polling = true;
    try {
      const jobs = await server.listJobs();
      this.serverStatus.textContent = jobs.length ? '' : 'No jobs yet: submit a bundled case below.';
      this.serverStatus.classList.remove('error');
      this.renderJobs(jobs);
      this.polls += 1;
      if (this.selected) {
        const job = this.jobs.get(this.selected.id);
        if (job) this.selectedChanged(job);
        else if (this.selected.state !== 'deleted') this.selectedChanged({ ...this.selected, state: 'deleted' });
      }
      // one round at a time: a round still downloading skips this one
      if (this.socket && this.selected && this.polls % STATS_EVERY_POLLS === 0 && this.statsInFlight === 0) this.loadStatsCharts(this.selected.id, this.session);
    } catch (e) {
      this.serverStatus.textContent = `Job list: ${errorText(e)}`;
      this.serverStatus.classList.add('error');
    } finally {
      this.polling = false;
    }
  }

  renderJobs(jobs) {
    const seen = new Set();
    this.jobs = new Map();
    // Newest first.
    const ordered = jobs.slice().sort((a, b) => b.id - a.id);
    let before = this.jobList.firstChild;
    for (const job of ordered) {
      this.jobs.set(job.id, job);
      seen.add(String(job.id));
      let li = this.jobList.querySelector(`li[data-id="${job.id}"]`);
      if (!li) {
        li = document.createElement('li');
        li.dataset.id = String(job.id);
        li.tabIndex = 0;
        li.className = 'job';
        make('span', li, { className: 'job-id' });
        make('span', li, { className: 'job-name' });
        make('span', li, { className: 'job-state' });
        make('progress', li, { className: 'job-bar', max: '1' });
        make('span', li, { className: 'job-progress' });
      }
      if (li !== before) this.jobList.insertBefore(li, before);
      before = li.nextSibling;
      this.renderJob(li, job);
    }
    for (const li of Array.from(this.jobList.querySelectorAll('li[data-id]'))) {
      if (!seen.has(li.dataset.id)) li.remove();
    }
  }

  renderJob(li, job) {
    const progress = Number(job.progress) || 0;
    li.dataset.state = job.state;
    li.dataset.progress = String(progress);
    li.classList.toggle('selected', !!this.selected && this.selected.id === job.id);
    li.querySelector('.job-id').textContent = `#${job.id}`;
    li.querySelector('.job-name').textContent = ` ${job.name || '(no name)'} `;
    li.querySelector('.job-state').textContent = job.state;
    li.querySelector('.job-bar').value = progress;
    let text = ` ${percent(progress)}`;
    if (job.state === 'running' && Number.isFinite(job.secondsLeft)) text += `, ${Math.round(job.secondsLeft)} s left`;
    li.querySelector('.job-progress').textContent = text;
    const details = [`job ${job.id}: ${job.state}`, `step ${job.step ?? 0} of ${job.totalSteps ?? '?'}`, job.particles === undefined || job.particles === null ? '? particles' : counted(job.particles, 'particle')];
    if (job.error) details.push(job.error);
    li.title = `${details.join(', ')}. Click: ${ACTIVE.has(job.state) ? 'follow it live' : 'replay it'}.`;
  }

  // A click on a job: follow it if it runs or waits, else replay it.
  async open(id) {
    if (this.socket && this.selected && this.selected.id === id) return; // already followed
    // A later click (or another follow / replay) while this one waits for the server wins.
    const token = ++this.openToken;
    const session = this.session;
    let job = this.jobs.get(id);
    try {
      job = await server.getJob(id);
    } catch (e) {
      if (token !== this.openToken || session !== this.session) return;
      if (!job) {
        this.say(errorText(e), true);
        return;
      }
    }
    if (token !== this.openToken || session !== this.session) return;
    if (ACTIVE.has(job.state)) this.follow(job);
    else this.replay(job.id, job);
  }

  select(job) {
    this.selected = { ...job };
    for (const li of this.jobList.querySelectorAll('li[data-id]')) li.classList.toggle('selected', Number(li.dataset.id) === job.id);
    this.root.dataset.job = String(job.id);
    this.jobLabel.textContent = `#${job.id} ${job.name || ''}`.trim();
    this.updateButtons();
  }

  selectedChanged(job) {
    const was = this.selected.state;
    this.selected = { ...this.selected, ...job };
    if (was === job.state) return;
    this.updateButtons();
    if (!this.socket || !this.lastFrame) this.showStatus();
  }

  updateButtons() {
    const job = this.selected;
    this.replayButton.disabled = !job || ACTIVE.has(job.state) || job.state === 'deleted';
    this.cancelButton.disabled = !job || !(ACTIVE.has(job.state) || job.state === 'interrupted');
    this.stopButton.disabled = !this.socket;
  }

  showStatus(frame) {
    const job = this.selected;
    if (!job) {
      this.statusLabel.textContent = '';
      return;
    }
    if (frame) {
      const total = frame.totalSteps || job.totalSteps;
      this.statusLabel.textContent = `live: step ${frame.step}${total ? ` of ${total}` : ''}, t = ${frame.time.toPrecision(6)} s, ` +
        (frame.stage ? `stage ${frame.stage}, ` : '') + `${counted(frame.count, 'particle')}, ${counted(this.framesReceived, 'frame')}`;
    } else if (this.socket) {
      this.statusLabel.textContent = job.state === 'queued' ? 'queued: waiting for the job to start' : 'waiting for the first frame';
    } else {
      this.statusLabel.textContent = `${job.state}${job.error ? `: ${job.error}` : ''}`;
    }
  }

  async cancelSelected() {
    if (!this.selected) return;
    try {
      const job = await server.cancelJob(this.selected.id);
      if (job) this.selectedChanged(job);
      this.say(`job ${this.selected.id} cancelled`);
    } catch (e) {
      this.say(errorText(e), true);
    }
    this.refreshJobs();
  }

  // ---- following a job live --------------------------------------------------------------------

  follow(job) {
    this.closeSocket();
    const session = ++this.session;
    this.downloads = new AbortController();
    this.statsSizes = new Map();
    this.select(job);
    this.decoder = new FrameDecoder();
    this.framesReceived = 0;
    this.lastFrame = null;
    this.meshAsked = false;
    this.reconnects = 0;
    this.stepLabel.textContent = '';
    this.charts.clear();
    // An empty live run (lengths in metres); the frames are appended as they come.
    this.generation = this.call('setRun', { frames: [], mesh: null, unit: 'm', source: `job ${job.id}` });
    this.setLive(true);
    this.unitOfJob(job).then((unit) => {
      if (session === this.session) this.charts.setLengthUnit(unit);
    });
    this.connect(job.id, session);
    this.updateButtons();
    this.showStatus();
    this.say(`following job ${job.id} live (${job.state})`);
  }

  connect(id, session) {
    const chains = document.getElementById('show-force-chains');
    let socket;
    try {
      socket = server.openFrames(id, {
        forceChains: !!(chains && chains.checked),
        onMessage: (data) => this.onFrame(data, session),
        onClose: (code, reason) => this.onClose(id, session, socket, code, reason),
      });
    } catch (e) {
      this.say(errorText(e), true);
      this.setLive(false);
      return;
    }
    this.socket = socket;
    this.updateButtons();
  }

  onFrame(data, session) {
    if (session !== this.session) return;
    let frame;
    try {
      frame = this.decoder.decode(data);
    } catch (e) {
      if (!this.decodeErrorShown) this.say(`a live frame could not be read: ${errorText(e)}`, true);
      this.decodeErrorShown = true;
      return;
    }
    this.reconnects = 0;
    try {
      addStats(frame);
    } catch (e) {
      console.warn(e);
    }
    if (frame.forceChains) {
      frame.forceChains.step = frame.step;
      frame.forceChains.count = frame.forceChains.i.length;
      try {
        addStats(frame.forceChains);
      } catch (e) {
        console.warn(e);
      }
    }
    if (this.generation !== undefined && this.viewer.runGeneration !== undefined && this.viewer.runGeneration !== this.generation) {
      // files were opened over the live run: it is not this job's any more
      this.stopFollowing();
      this.statusLabel.textContent = 'stopped following: another run was opened';
      return;
    }
    this.framesReceived += 1;
    this.lastFrame = frame;
    try {
      this.call('addFrame', frame, this.generation);
    } catch (e) {
      console.error(e);
      if (!this.viewerErrorShown) this.say(`the viewer could not show a live frame: ${errorText(e)}`, true);
      this.viewerErrorShown = true;
    }
    this.stepLabel.textContent = String(frame.step);
    this.root.dataset.step = String(frame.step);
    this.charts.addFrame(frame);
    if (this.selected && this.selected.state === 'queued') this.selected.state = 'running';
    this.showStatus(frame);
    if (!this.meshAsked) {
      this.meshAsked = true;
      this.loadLiveMesh(this.selected, session);
      this.loadStatsCharts(this.selected.id, session);
    }
  }

  async onClose(id, session, socket, code, reason) {
    if (this.socket === socket) this.socket = null;
    if (session !== this.session) return;
    this.updateButtons();
    let job = null;
    try {
      job = await server.getJob(id);
    } catch {
      /* deleted or the server is gone */
    }
    if (session !== this.session) return;
    if (job) this.selectedChanged(job);
    if (job && ACTIVE.has(job.state) && code !== 1000 && this.reconnects < RECONNECTS) {
      // The connection broke (not closed by the server): join again.
      this.reconnects += 1;
      this.statusLabel.textContent = `connection lost (${code}${reason ? ` ${reason}` : ''}); reconnecting`;
      setTimeout(() => {
        if (session === this.session && !this.socket) this.connect(id, session);
      }, 1000 * this.reconnects);
      return;
    }
    this.setLive(false);
    const why = reason || (job ? `job ${job.state}` : `connection closed (${code})`);
    this.showStatus();
    this.statusLabel.textContent = `${why}; ${counted(this.framesReceived, 'live frame')}` + (job && !ACTIVE.has(job.state) ? ': Replay loads every frame' : '');
    const failed = job && (job.state === 'failed' || job.state === 'interrupted');
    this.say(`job ${id}: ${why}${failed && job.error ? ` (${job.error})` : ''}`, !!failed);
    if (job && !ACTIVE.has(job.state)) this.loadStatsCharts(id, session, job);
  }

  // Ends the current follow / replay's connection and downloads.
  closeSocket() {
    if (this.downloads) {
      this.downloads.abort();
      this.downloads = null;
    }
    const socket = this.socket;
    this.socket = null;
    if (socket) {
      try {
        socket.close(1000, 'viewer left');
      } catch {
        /* already closed */
      }
    }
  }

  stopFollowing(text) {
    const wasFollowing = !!this.socket;
    this.session += 1;
    this.closeSocket();
    this.setLive(false);
    this.updateButtons();
    if (wasFollowing && text) {
      this.statusLabel.textContent = text;
      this.say(text);
    }
  }

  // The fixed mesh of a followed job (Wall.dat, in the files' length unit) in metres, as the frames.
  async loadLiveMesh(job, session) {
    const generation = this.generation;
    try {
      const artifacts = await server.listArtifacts(job.id);
      if (session !== this.session || !artifacts.some((a) => a.name === 'Wall.dat')) return;
      const [result, unit] = await Promise.all([this.fetchMesh(job.id, session), this.unitOfJob(job)]);
      if (session !== this.session || !result) return;
      if (result.kind !== 'mesh' || !result.mesh) return;
      const scale = METRES_PER[unit] || 1;
      if (scale !== 1) {
        const v = result.mesh.vertices;
        for (let k = 0; k < v.length; k++) v[k] *= scale;
      }
      this.call('setMesh', result.mesh, generation);
    } catch (e) {
      if (session === this.session) console.warn('Wall.dat of the followed job', e);
    }
  }

  // A job's Wall.dat, downloaded as a Blob and parsed off the main thread (parseFile); null when
  // another follow / replay took over meanwhile.
  async fetchMesh(id, session) {
    const signal = this.downloads ? this.downloads.signal : undefined;
    const blob = await server.downloadArtifactBlob(id, 'Wall.dat', { signal });
    if (session !== this.session) return null;
    const result = await parseFile(blob);
    return session === this.session ? result : null;
  }

  // ---- replaying a finished job ----------------------------------------------------------------

  async replay(id, job = null) {
    this.closeSocket();
    const session = ++this.session;
    this.downloads = new AbortController();
    this.statsSizes = new Map();
    this.setLive(false);
    if (!job) {
      try {
        job = await server.getJob(id);
      } catch (e) {
        this.say(errorText(e), true);
        return;
      }
    }
    if (session !== this.session) return;
    this.select(job);
    this.stepLabel.textContent = '';
    this.lastFrame = null;
    this.charts.clear();
    this.replayButton.disabled = true;
    const unit = await this.unitOfJob(job);
    if (session !== this.session) return;
    this.charts.setLengthUnit(unit);
    try {
      const artifacts = await server.listArtifacts(id);
      const names = new Set(artifacts.map((a) => a.name));
      if (session !== this.session) return;
      this.loadStatsCharts(id, session, job, artifacts);
      // a 2D run's frames are in ANIMATION_2D.dat
      const file = names.has('ANIMATION_3D.dat') ? 'ANIMATION_3D.dat' : names.has('ANIMATION_2D.dat') ? 'ANIMATION_2D.dat' : null;
      if (!file) {
        this.say(`job ${id} has no ANIMATION_3D.dat (or ANIMATION_2D.dat) to replay (${job.state})`, true);
        return;
      }
      this.say(`loading job ${id}'s ${file}`);
      const result = await this.fetchAndParse(id, file, artifacts, session);
      if (!result) return;
      if (result.kind !== 'animation' || !result.frames || !result.frames.length) {
        this.say(`job ${id}'s ${file}: ${result.problem || 'no frames'}`, true);
        this.statusLabel.textContent = 'nothing to replay';
        return;
      }
      let mesh = null;
      if (names.has('Wall.dat')) {
        try {
          const meshResult = await this.fetchMesh(id, session);
          if (meshResult && meshResult.kind === 'mesh') mesh = meshResult.mesh;
        } catch (e) {
          if (session === this.session) console.warn('Wall.dat', e);
        }
      }
      if (session !== this.session) return;
      const run = { frames: result.frames, mesh, unit: 'file', source: `job ${id}` };
      if (unit) run.lengthUnit = unit;
      this.generation = this.call('setRun', run);
      this.charts.setAnimationFrames(result.frames);
      const last = result.frames[result.frames.length - 1];
      this.stepLabel.textContent = '';
      let note = `job ${id}: ${counted(result.frames.length, 'frame')} replayed`;
      if (result.problem) note += ` (${result.problem})`;
      if (names.has('ForceChain_3D.dat')) {
        const chains = await this.fetchAndParse(id, 'ForceChain_3D.dat', artifacts, session);
        if (!chains) return;
        if (chains.kind === 'forceChains') {
          this.call('setForceChains', chains.frames, this.generation);
          note += `, ${counted(chains.frames.length, 'frame')} of force chains`;
          if (chains.problem) note += ` (ForceChain_3D.dat: ${chains.problem})`;
        }
      }
      this.statusLabel.textContent = `${job.state}: ${counted(result.frames.length, 'frame')}, last step ${last.step}, t = ${Number(last.time).toPrecision(6)} s`;
      this.say(note);
      this.play();
    } catch (e) {
      if (session === this.session) {
        this.say(errorText(e), true);
        this.statusLabel.textContent = `replay failed: ${errorText(e)}`;
      }
    } finally {
      if (session === this.session) this.updateButtons();
    }
  }

  // Starts playback of the run just loaded (the page's Play control).
  play() {
    if (typeof this.viewer.play === 'function') {
      this.viewer.play();
      return;
    }
    const button = document.getElementById('play');
    if (button && !button.disabled) button.click();
  }

  // Downloads an output file and parses it with the core's parsers (in its worker when it can), the
  // page's #load-progress showing both. null when another follow / replay took over meanwhile.
  async fetchAndParse(id, name, artifacts, session) {
    const size = (artifacts.find((a) => a.name === name) || {}).size || 0;
    const progress = document.getElementById('load-progress');
    const show = (fraction, text) => {
      if (session !== this.session) return;
      this.statusLabel.textContent = text;
      if (progress) {
        progress.hidden = false;
        progress.value = Math.max(0, Math.min(1, fraction));
      }
    };
    try {
      show(0, `downloading ${name} (${(size / 1e6).toFixed(1)} MB)`);
      const blob = await server.downloadArtifactBlob(id, name, {
        signal: this.downloads ? this.downloads.signal : undefined,
        onProgress: (got, total) => show(0.5 * (got / (total || size || got)), `downloading ${name}: ${percent(got / (total || size || got))}`),
      });
      if (session !== this.session) return null;
      show(0.5, `reading ${name}`);
      const result = await parseFile(blob, (fraction) => show(0.5 + 0.5 * fraction, `reading ${name}: ${percent(fraction)}`));
      return session === this.session ? result : null;
    } finally {
      // hidden whatever happened (an aborted or superseded download too); a newer download shows it again
      if (progress) {
        progress.value = 1;
        progress.hidden = true;
      }
    }
  }

  // Force_Displacement.dat, Fragments.dat and Bond_Breaks.dat into the charts, when the job has them.
  // A file is downloaded again only when its size in the artifact list changed since it was read.
  async loadStatsCharts(id, session, job = null, artifacts = null) {
    this.statsInFlight += 1;
    try {
      if (!artifacts) artifacts = await server.listArtifacts(id);
      if (session !== this.session) return;
      const sizes = new Map(artifacts.map((a) => [a.name, a.size]));
      const signal = this.downloads ? this.downloads.signal : undefined;
      const final = !!job && !ACTIVE.has(job.state); // the job's last read: every file, whatever its size
      const changed = (name) => sizes.has(name) && (final || sizes.get(name) === undefined || this.statsSizes.get(name) !== sizes.get(name));
      const get = (name) => (changed(name) ? server.downloadArtifact(id, name, { signal }) : Promise.resolve(null));
      const [fd, fragments, breaks] = await Promise.all(STATS_FILES.map(get));
      if (session !== this.session) return;
      STATS_FILES.forEach((name, k) => {
        if ([fd, fragments, breaks][k] !== null) this.statsSizes.set(name, sizes.get(name));
      });
      if (fd !== null) this.charts.setForceDisplacement(fd);
      if (fragments !== null) this.charts.setFragments(fragments, { brokenBonds: !sizes.has('Bond_Breaks.dat') });
      if (breaks !== null) {
        let end = NaN;
        if (job && !ACTIVE.has(job.state) && Number.isFinite(job.timeStep) && Number.isFinite(job.step)) end = job.step * job.timeStep;
        else if (this.lastFrame) end = this.lastFrame.time;
        this.charts.setBondBreaks(breaks, end);
      }
    } catch (e) {
      if (session === this.session) console.warn('statistics files', e);
    } finally {
      this.statsInFlight -= 1;
    }
  }

  // ---- units -----------------------------------------------------------------------------------

  // The length unit of a job's files ("m", "cm", "mm"), from its record (the server says it), asked
  // again when the record at hand is an old one without it; '' when the server cannot be asked.
  async unitOfJob(job) {
    if (job.lengthUnit) return job.lengthUnit;
    try {
      return (await server.getJob(job.id)).lengthUnit || 'm';
    } catch {
      return '';
    }
  }

  async caseSpec(name) {
    if (!this.caseSpecs.has(name)) this.caseSpecs.set(name, server.getCase(name));
    try {
      return await this.caseSpecs.get(name);
    } catch (e) {
      this.caseSpecs.delete(name);
      throw e;
    }
  }

  // ---- bundled cases ---------------------------------------------------------------------------

  async loadCases() {
    try {
      this.cases = await server.listCases();
    } catch (e) {
      this.caseDescription.textContent = `Bundled cases: ${errorText(e)}`;
      return;
    }
    this.caseSelect.textContent = '';
    for (const c of this.cases) {
      const option = make('option', this.caseSelect, { value: c.name, text: c.title || c.name });
      if (c.description) option.title = c.description;
    }
    if (!this.cases.length) {
      this.caseDescription.textContent = 'The server has no bundled cases.';
      return;
    }
    await this.loadCase(this.caseSelect.value || this.cases[0].name);
  }

  async loadCase(name) {
    const c = this.cases.find((k) => k.name === name);
    this.caseDescription.textContent = c ? (c.description || '').replace(/\[`?([^\]`]+)`?\]\([^)]*\)/g, '$1') : '';
    this.submitButton.disabled = true;
    try {
      const spec = await this.caseSpec(name);
      if (this.caseSelect.value !== name) return; // another case was chosen meanwhile
      this.setSpec(JSON.parse(JSON.stringify(spec)));
    } catch (e) {
      this.say(`bundled case ${name}: ${errorText(e)}`, true);
    }
  }

  setSpec(spec) {
    this.spec = spec;
    this.specText.value = formatSpec(spec);
    this.specText.classList.remove('error');
    this.fillQuickFields(spec);
    this.submitButton.disabled = false;
  }

  fillQuickFields(spec) {
    const duration = spec && spec.time ? Number(spec.time.duration) : NaN;
    this.durationInput.value = Number.isFinite(duration) && duration > 0 ? String(duration) : '';
    this.durationInput.placeholder = spec && spec.time && spec.time.steps ? `${spec.time.steps} steps` : '';
    const frictions = ((spec && spec.interactions) || []).map((i) => Number(i.friction || 0));
    const distinct = [...new Set(frictions)];
    this.frictionInput.value = frictions.length ? String(frictions[0]) : '';
    this.frictionInput.title = distinct.length > 1
      ? `the friction of every interaction (now ${frictions.join(', ')}): a value here sets them all`
      : 'the friction of every interaction';
  }

  // The spec in the textarea, or null (and a message) when it is not valid JSON.
  readSpec(report = true) {
    try {
      const spec = JSON.parse(this.specText.value);
      if (!spec || typeof spec !== 'object' || Array.isArray(spec)) throw new Error('the spec must be a JSON object');
      this.specText.classList.remove('error');
      return spec;
    } catch (e) {
      this.specText.classList.add('error');
      if (report) this.say(`the spec is not valid JSON: ${errorText(e)}`, true);
      return null;
    }
  }

  specEdited() {
    const spec = this.readSpec(false);
    if (!spec) return;
    this.spec = spec;
    this.fillQuickFields(spec);
  }

  quickEdit(which) {
    const input = which === 'duration' ? this.durationInput : this.frictionInput;
    const value = Number(input.value);
    if (input.value.trim() === '' || !Number.isFinite(value) || value < 0) return;
    const spec = this.readSpec();
    if (!spec) return;
    if (which === 'duration') {
      spec.time = { ...(spec.time || {}) };
      spec.time.duration = value;
      delete spec.time.steps; // give duration or steps, not both
    } else {
      for (const interaction of spec.interactions || []) interaction.friction = value;
    }
    this.spec = spec;
    this.specText.value = formatSpec(spec);
    if (which === 'friction') this.frictionInput.title = 'the friction of every interaction';
  }

  async submit() {
    const spec = this.readSpec();
    if (!spec) return;
    this.submitButton.disabled = true;
    try {
      const job = await server.submitJob(spec);
      this.say(`job ${job.id} submitted: ${job.particles ?? '?'} particle${job.particles === 1 ? '' : 's'}, ${job.totalSteps ?? '?'} step${job.totalSteps === 1 ? '' : 's'}`);
      await this.refreshJobs();
      this.follow(job);
    } catch (e) {
      this.say(errorText(e), true);
    } finally {
      this.submitButton.disabled = false;
    }
  }
}

// Builds the live panel in #live-panel and starts polling the server. Returns the panel (also as
// window.demLive, for the console and tests): follow(job), replay(id), stopFollowing(), refreshJobs().
export function initLivePanel(viewer) {
  const panel = new LivePanel(viewer).start();
  if (typeof window !== 'undefined') window.demLive = panel;
  return panel;
}

export default initLivePanel;
