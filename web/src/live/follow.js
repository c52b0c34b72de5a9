// Following a running (or queued) job live: its frames over a WebSocket into the viewer as they
// come (the viewer shows the newest), its mesh once the first frame is in, its statistics files
// re-read every few seconds; when the connection breaks while the job goes on (a network hiccup, the
// server restarting and resuming it), joining again for up to two minutes.

import * as server from './server.js';
import { FrameDecoder } from './frame_decode.js';
import { addStats } from '../formats/stats.js';
import { counted } from '../words.js';
import { ACTIVE, errorText } from './session.js';
import { readMesh, readStatistics, unitOfJob } from './job_files.js';

const RETRY_SECONDS = 120; // how long a broken follow keeps trying to join again

export class Follow {
  // panel: the LivePanel (its viewer, charts, labels and messages); session: this follow's Session.
  constructor(panel, session) {
    this.panel = panel;
    this.session = session;
    this.viewer = panel.viewer;
    this.socket = null;
    this.decoder = new FrameDecoder();
    this.framesReceived = 0;
    this.reconnects = 0;
    this.meshAsked = false;
  }

  start() {
    const { session, panel } = this;
    // An empty live run (lengths in metres); the frames are appended as they come.
    session.generation = this.viewer.setRun({ frames: [], mesh: null, unit: 'm', source: `job ${session.job.id}` });
    panel.showing(session);
    panel.setLive(true);
    unitOfJob(session.job).then((unit) => {
      if (!session.ended) panel.charts.setLengthUnit(unit);
    });
    this.connect();
  }

  connect() {
    const chains = document.getElementById('show-force-chains');
    let socket;
    try {
      socket = server.openFrames(this.session.job.id, {
        forceChains: chains.checked,
        onMessage: (data) => this.onFrame(data),
        onClose: (code, reason) => this.onClose(socket, code, reason),
      });
    } catch (e) {
      this.panel.say(errorText(e), true);
      this.panel.setLive(false);
      return;
    }
    this.socket = socket;
    this.panel.updateButtons();
  }

  // The force chains asked of the server only while the viewer shows them.
  setForceChains(on) {
    if (this.socket) server.setForceChains(this.socket, on);
  }

  close() {
    const socket = this.socket;
    this.socket = null;
    if (!socket) return;
    try {
      socket.close(1000, 'viewer left');
    } catch {
      /* already closed */
    }
  }

  onFrame(data) {
    const { session, panel } = this;
    if (session.ended) return;
    let frame;
    try {
      frame = this.decoder.decode(data);
    } catch (e) {
      if (!this.decodeErrorShown) panel.say(`a live frame could not be read: ${errorText(e)}`, true);
      this.decodeErrorShown = true;
      return;
    }
    this.reconnects = 0;
    this.brokenSince = null;
    addStats(frame);
    if (frame.forceChains) {
      frame.forceChains.step = frame.step;
      frame.forceChains.count = frame.forceChains.i.length;
      addStats(frame.forceChains);
    }
    if (this.viewer.runGeneration !== session.generation) {
      // files were opened over the live run: it is not this job's any more
      panel.stopFollowing();
      panel.statusLabel.textContent = 'stopped following: another run was opened';
      return;
    }
    this.framesReceived += 1;
    session.lastFrame = frame;
    try {
      this.viewer.addFrame(frame, session.generation);
    } catch (e) {
      console.error(e);
      if (!this.viewerErrorShown) panel.say(`the viewer could not show a live frame: ${errorText(e)}`, true);
      this.viewerErrorShown = true;
    }
    panel.stepLabel.textContent = String(frame.step);
    panel.root.dataset.step = String(frame.step);
    panel.charts.addFrame(frame);
    if (panel.selected.state === 'queued') panel.selectedChanged({ state: 'running' });
    panel.showStatus(frame, this.framesReceived);
    if (!this.meshAsked) {
      this.meshAsked = true;
      this.loadMesh();
      readStatistics(session, panel.charts);
    }
  }

  // The fixed mesh (Wall.dat, in the files' length unit) in metres, as the frames.
  async loadMesh() {
    const { session } = this;
    try {
      const artifacts = await server.listArtifacts(session.job.id);
      if (session.ended || !artifacts.some((a) => a.name === 'Wall.dat')) return;
      const mesh = await readMesh(session, await unitOfJob(session.job));
      if (!session.ended && mesh) this.viewer.setMesh(mesh, session.generation);
    } catch (e) {
      if (!session.ended) console.warn('Wall.dat of the followed job', e);
    }
  }

  async onClose(socket, code, reason) {
    const { session, panel } = this;
    if (this.socket === socket) this.socket = null;
    if (session.ended) return;
    panel.updateButtons();
    const id = session.job.id;
    let job = null;
    let reachable = true;
    try {
      job = await server.getJob(id);
    } catch (e) {
      reachable = e.status !== 0; // 0: no answer at all (the server is down or restarting)
    }
    if (session.ended) return;
    if (job) panel.selectedChanged(job);
    // The job goes on (the connection broke, or the server restarts and resumes it): join again,
    // for as long as RETRY_SECONDS from the break.
    this.brokenSince = this.brokenSince || Date.now();
    const waited = (Date.now() - this.brokenSince) / 1000;
    if ((!reachable || (job && ACTIVE.has(job.state))) && waited < RETRY_SECONDS) {
      this.reconnects += 1;
      const delay = Math.min(5, this.reconnects);
      panel.statusLabel.textContent = `${reachable ? 'connection lost' : 'the server does not answer'}` +
        `${reason ? ` (${reason})` : ''}; joining again in ${delay} s (${counted(this.framesReceived, 'live frame')} so far)`;
      setTimeout(() => {
        if (!session.ended && !this.socket) this.connect();
      }, 1000 * delay);
      return;
    }
    if (!reachable) reason = `the server did not answer for ${Math.round(waited)} s; stopped following`;
    panel.setLive(false);
    const why = reason || (job ? `job ${job.state}` : `connection closed (${code})`);
    panel.statusLabel.textContent = `${why}; ${counted(this.framesReceived, 'live frame')}` + (job && !ACTIVE.has(job.state) ? ': Replay loads every frame' : '');
    const failed = job && (job.state === 'failed' || job.state === 'interrupted');
    panel.say(`job ${id}: ${why}${failed && job.error ? ` (${job.error})` : ''}`, !!failed || !reachable);
    if (job && !ACTIVE.has(job.state)) readStatistics(session, panel.charts, { job });
  }
}
