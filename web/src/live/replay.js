// Replaying a finished job: its ANIMATION_3D.dat (or a 2D run's ANIMATION_2D.dat), Wall.dat and
// ForceChain_3D.dat downloaded and parsed into the viewer, its statistics into the charts, then
// played. #load-progress shows the downloads and parses, and #load-cancel (or opening files, or
// another job, or a study) ends the session: the downloads are aborted and the parses stopped, and
// the run shown before stays with its charts (nothing is replaced until every file is read).

import * as server from './server.js';
import { counted } from '../words.js';
import { errorText } from './session.js';
import { downloadAndParse, readMesh, readStatistics, unitOfJob } from './job_files.js';

// Shows a download or parse of the session on the page's load bar; hidden when `fraction` is null.
// Hidden whatever happened (a cancelled or superseded replay too): a newer load shows it again.
function showProgress(panel, session, fraction, text) {
  const progress = document.getElementById('load-progress');
  const cancel = document.getElementById('load-cancel');
  if (fraction === null) {
    progress.hidden = true;
    cancel.hidden = true;
    return;
  }
  if (session.ended) return;
  progress.hidden = false;
  cancel.hidden = false;
  progress.value = Math.max(0, Math.min(1, fraction));
  panel.statusLabel.textContent = text;
}

export async function replay(panel, session) {
  const { job } = session;
  const id = job.id;
  const progress = (fraction, text) => showProgress(panel, session, fraction, text);
  const parse = (name, artifacts) => downloadAndParse(session, name, (artifacts.find((a) => a.name === name) || {}).size || 0, progress);
  try {
    const unit = await unitOfJob(job);
    if (session.ended) return;
    const artifacts = await server.listArtifacts(id);
    if (session.ended) return;
    const names = new Set(artifacts.map((a) => a.name));
    const file = names.has('ANIMATION_3D.dat') ? 'ANIMATION_3D.dat' : names.has('ANIMATION_2D.dat') ? 'ANIMATION_2D.dat' : null;
    if (!file) {
      panel.say(`job ${id} has no ANIMATION_3D.dat (or ANIMATION_2D.dat) to replay (${job.state})`, true);
      return;
    }
    panel.say(`loading job ${id}'s ${file}`);
    const result = await parse(file, artifacts);
    if (session.ended) return;
    if (result.kind !== 'animation' || !result.frames.length) {
      panel.say(`job ${id}'s ${file}: ${result.problem || 'no frames'}`, true);
      panel.statusLabel.textContent = 'nothing to replay';
      return;
    }
    let mesh = null;
    if (names.has('Wall.dat')) {
      try {
        mesh = await readMesh(session, 'file'); // the replay keeps the files' length unit
      } catch (e) {
        if (session.ended) return;
        console.warn('Wall.dat', e);
      }
    }
    let chains = null;
    if (names.has('ForceChain_3D.dat')) chains = await parse('ForceChain_3D.dat', artifacts);
    if (session.ended) return;
    const run = { frames: result.frames, mesh, unit: 'file', source: `job ${id}` };
    if (unit) run.lengthUnit = unit;
    session.generation = panel.viewer.setRun(run);
    panel.showing(session);
    panel.charts.setLengthUnit(unit);
    panel.charts.setAnimationFrames(result.frames);
    readStatistics(session, panel.charts, { job, artifacts });
    let note = `job ${id}: ${counted(result.frames.length, 'frame')} replayed`;
    if (result.problem) note += ` (${result.problem})`;
    if (chains && chains.kind === 'forceChains') {
      panel.viewer.setForceChains(chains.frames, session.generation);
      note += `, ${counted(chains.frames.length, 'frame')} of force chains`;
      if (chains.problem) note += ` (ForceChain_3D.dat: ${chains.problem})`;
    }
    const last = result.frames[result.frames.length - 1];
    panel.statusLabel.textContent = `${job.state}: ${counted(result.frames.length, 'frame')}, last step ${last.step}, t = ${Number(last.time).toPrecision(6)} s`;
    panel.say(note);
    panel.viewer.playback.play();
  } catch (e) {
    if (!session.ended) {
      panel.say(errorText(e), true);
      panel.statusLabel.textContent = `replay failed: ${errorText(e)}`;
    }
  } finally {
    showProgress(panel, session, null);
  }
}
