// The server's side of the viewer, in #live-panel (markup in index.html, docs/viewer.md): it ties
// the job list (job_list.js), following a running job (follow.js), replaying a finished one
// (replay.js), the studies' overlaid charts (studies.js) and the bundled case form (case_form.js)
// to the viewer and the charts. One job is shown at a time, by one Session (session.js): choosing
// another job, a study or files ends it.

import * as server from './server.js';
import { counted } from '../words.js';
import { Charts } from './charts.js';
import { JobList } from './job_list.js';
import { Follow } from './follow.js';
import { replay } from './replay.js';
import { Studies } from './studies.js';
import { CaseForm } from './case_form.js';
import { readStatistics, unitOfJob } from './job_files.js';
import { ACTIVE, Session, errorText } from './session.js';

const POLL_MS = 1000;
const STATS_EVERY_POLLS = 5; // a followed job's statistics files re-read every 5 s (when their size changed)

const $ = (id) => document.getElementById(id);

class LivePanel {
  constructor(viewer) {
    this.viewer = viewer;
    this.root = $('live-panel');
    this.session = null; // the job being followed or replayed (loading, or shown)
    this.following = null; // its Follow, while it is followed
    this.shown = null; // { job, generation }: the job whose run the viewer shows (setRun's generation)
    this.selected = null; // the session's job record (or the shown one's), kept up to date by the polls
    this.openToken = 0; // bumped by every job click: an older click's late answer opens nothing
    this.polls = 0;
    this.polling = false;
    this.jobLabel = $('live-job');
    this.stepLabel = $('live-step');
    this.statusLabel = $('live-status');
    this.replayButton = $('replay');
    this.stopButton = $('live-stop');
    this.cancelButton = $('live-cancel');
    this.charts = new Charts($('charts'));
    this.jobList = new JobList($('jobs'), $('live-server-status'), (id) => this.open(id));
    // a study chosen: the charts are its runs', not the job's
    this.studies = new Studies($('charts'), () => {
      this.stopFollowing(this.interruption('a study was chosen'));
      this.charts.clear();
    }, () => this.restoreCharts());
    this.caseForm = new CaseForm((text, isError) => this.say(text, isError), async (job) => {
      await this.refreshJobs();
      this.follow(job);
    });
    this.wire();
  }

  wire() {
    this.replayButton.addEventListener('click', () => {
      if (this.selected) this.replay(this.selected);
    });
    this.stopButton.addEventListener('click', () => this.stopFollowing('stopped following'));
    this.cancelButton.addEventListener('click', () => this.cancelSelected());
    // #load-cancel stops a replay's downloads and parses as it stops a file load
    $('load-cancel').addEventListener('click', () => {
      if (this.session && !this.following) this.stopFollowing('replay cancelled; the run shown before stays');
    });
    this.viewer.onChange(() => {
      // files opened over the job's run: the panel and the charts no longer name that job
      if (this.shown && this.viewer.runGeneration !== this.shown.generation) this.runReplaced();
      // the charts mark the time of the frame in view
      const state = this.viewer.state();
      this.charts.setCursor(state.time !== null ? Number(state.time) : NaN);
    });
    $('show-force-chains').addEventListener('change', (e) => {
      if (this.following) this.following.setForceChains(e.target.checked);
    });
    // Opening files replaces the run: the job's follow or replay ends (its downloads and parses too).
    $('file-input').addEventListener('change', () => this.stopFollowing(this.interruption('files were opened')));
    document.addEventListener('drop', (e) => {
      if (e.dataTransfer && e.dataTransfer.files.length) this.stopFollowing(this.interruption('files were opened'));
    });
  }

  start() {
    if (!server.hasServer()) {
      $('live-server-status').textContent = 'No server: this page was opened from a file. Jobs need dem-server.';
      this.root.dataset.server = 'none';
      this.caseForm.disable();
      $('study-select').disabled = true;
      return this;
    }
    this.root.dataset.server = 'yes';
    this.refreshJobs();
    this.studies.refresh();
    this.timer = setInterval(() => this.refreshJobs(), POLL_MS);
    this.caseForm.loadCases();
    // a link to a job (?job=N, as scripts/start prints it) opens it at once: live or replayed
    const asked = new URLSearchParams(window.location.search).get('job');
    if (asked !== null) {
      const wanted = Number(asked);
      // decimal digits, as the REST paths take them (not 0x2, 2.0 or 1e0)
      if (/^[0-9]+$/.test(asked) && Number.isSafeInteger(wanted) && wanted > 0) this.open(wanted);
      else this.say(`?job=${asked} in the address is not a job number (1, 2, ...)`, true);
    }
    return this;
  }

  say(text, isError = false) {
    this.viewer.message(text, isError);
  }

  setLive(on) {
    this.viewer.setLive(on);
    this.root.dataset.live = on ? 'true' : 'false';
  }

  async refreshJobs() {
    if (this.polling) return;
    this.polling = true;
    try {
      const jobs = await this.jobList.refresh();
      if (!jobs) return;
      this.polls += 1;
      if (this.polls % STATS_EVERY_POLLS === 0) this.studies.refresh();
      if (this.selected) {
        const job = this.jobList.jobs.get(this.selected.id);
        this.selectedChanged(job || { state: 'deleted' });
      }
      // one round at a time: a round still downloading skips this one
      const session = this.session;
      if (this.following && this.following.socket && this.polls % STATS_EVERY_POLLS === 0 && session.statsInFlight === 0) readStatistics(session, this.charts);
    } finally {
      this.polling = false;
    }
  }

  // A click on a job: follow it if it runs or waits, else replay it.
  async open(id) {
    if (this.following && this.following.socket && this.selected.id === id) return; // already followed
    // A later click (or another follow / replay) while this one waits for the server wins.
    const token = ++this.openToken;
    const session = this.session;
    let job = this.jobList.jobs.get(id);
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
    else this.replay(job);
  }

  // Ends the current session (its connection, downloads and parses) and starts one for `job`. The
  // charts stay those of the run shown until the new run replaces it (showing).
  begin(job) {
    this.leaveJob();
    this.studies.clear();
    this.session = new Session(job);
    this.label(job);
    this.stepLabel.textContent = '';
    return this.session;
  }

  // The session's run is now the viewer's (setRun answered `generation`): its charts start empty.
  showing(session) {
    this.shown = { job: session.job, generation: session.generation };
    this.charts.clear();
  }

  isShown(session) {
    return !!this.shown && this.shown.job === session.job && this.shown.generation === session.generation;
  }

  // The panel names `job` (null: none) as the selected one.
  label(job) {
    this.selected = job ? { ...job } : null;
    this.jobList.select(job ? job.id : null);
    this.root.dataset.job = job ? String(job.id) : '';
    this.jobLabel.textContent = job ? `#${job.id} ${job.name || ''}`.trim() : 'none';
    this.updateButtons();
  }

  // Ends the current session, if any. The run shown stays in the viewer; a session ended before its
  // run was shown (a replay cancelled or overtaken) hands the panel back to the job shown.
  leaveJob() {
    const session = this.session;
    if (this.following) this.following.close();
    this.following = null;
    this.session = null;
    if (!session) return;
    session.end();
    if (!this.isShown(session)) {
      this.label(this.shown ? this.shown.job : null);
      this.restoreCharts();
    }
  }

  // What ending the current session for `why` means, for the status line and the message ('' when
  // nothing is followed or loading).
  interruption(why) {
    const session = this.session;
    if (!session) return '';
    if (this.following && this.isShown(session)) return `stopped following job ${session.job.id}: ${why}`;
    if (!this.isShown(session)) return `the replay of job ${session.job.id} stopped: ${why}; the run shown before stays`;
    return '';
  }

  // The charts of the job shown, drawn again when they are empty (a study or a replay that did not
  // finish had them): its frames' energy from the viewer, its statistics files from the server.
  restoreCharts() {
    if (!this.shown || this.charts.hasData()) return;
    const job = this.jobList.jobs.get(this.shown.job.id) || this.shown.job;
    const session = new Session(job);
    session.generation = this.shown.generation;
    this.charts.setAnimationFrames(this.viewer.run ? this.viewer.run.frames : []);
    unitOfJob(job).then((unit) => this.charts.setLengthUnit(unit));
    readStatistics(session, this.charts, { job });
  }

  // Files replaced the job's run in the viewer.
  runReplaced() {
    this.shown = null;
    if (this.session) return; // a newer follow or replay has the panel
    this.charts.clear();
    this.label(null);
    this.statusLabel.textContent = '';
  }

  follow(job) {
    const session = this.begin(job);
    this.following = new Follow(this, session);
    this.following.start();
    this.updateButtons();
    this.showStatus();
    this.say(`following job ${job.id} live`);
  }

  replay(job) {
    const session = this.begin(job);
    this.setLive(false);
    this.updateButtons();
    this.replayButton.disabled = true;
    replay(this, session).finally(() => {
      if (session !== this.session) return;
      // the replay ended without showing its run (no file, a bad file, an error): the panel and the
      // charts go back to the run shown; the status line keeps what went wrong
      if (!this.isShown(session)) {
        const why = this.statusLabel.textContent;
        this.leaveJob();
        this.statusLabel.textContent = why;
      }
      this.updateButtons();
    });
  }

  stopFollowing(text) {
    const hadSession = !!this.session;
    this.leaveJob();
    this.setLive(false);
    this.updateButtons();
    if (hadSession && text) {
      this.statusLabel.textContent = text;
      this.say(text);
    }
  }

  // The selected job's record changed (a poll, a frame, the end of the connection).
  selectedChanged(changes) {
    if (!this.selected) return;
    const was = this.selected.state;
    this.selected = { ...this.selected, ...changes };
    if (was === this.selected.state) return;
    this.updateButtons();
    if (!this.following || !this.session.lastFrame) this.showStatus();
  }

  updateButtons() {
    const job = this.selected;
    this.replayButton.disabled = !job || ACTIVE.has(job.state) || job.state === 'deleted';
    this.cancelButton.disabled = !job || !(ACTIVE.has(job.state) || job.state === 'interrupted');
    this.stopButton.disabled = !(this.following && this.following.socket);
  }

  showStatus(frame = null, frames = 0) {
    const job = this.selected;
    if (!job) {
      this.statusLabel.textContent = '';
      return;
    }
    if (frame) {
      const total = frame.totalSteps || job.totalSteps;
      this.statusLabel.textContent = `live: step ${frame.step}${total ? ` of ${total}` : ''}, t = ${frame.time.toPrecision(6)} s, ` +
        (frame.stage ? `stage ${frame.stage}, ` : '') + `${counted(frame.count, 'particle')}, ${counted(frames, 'frame')}`;
    } else if (this.following) {
      this.statusLabel.textContent = job.state === 'queued' ? 'queued: waiting for the job to start' : 'waiting for the first frame';
    } else {
      this.statusLabel.textContent = `${job.state}${job.error ? `: ${job.error}` : ''}`;
    }
  }

  async cancelSelected() {
    if (!this.selected) return;
    const { id } = this.selected;
    try {
      const job = await server.cancelJob(id);
      if (job && this.selected && this.selected.id === id) this.selectedChanged(job);
      this.say(`job ${id} cancelled`);
    } catch (e) {
      this.say(errorText(e), true);
    }
    this.refreshJobs();
  }
}

// Builds the live panel and starts polling the server. Returns the panel (also window.demLive, for
// the console and tests).
export function initLivePanel(viewer) {
  const panel = new LivePanel(viewer).start();
  window.demLive = panel;
  return panel;
}
