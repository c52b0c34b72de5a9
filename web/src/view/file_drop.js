// Loads files chosen with #file-input or dropped on the page into the Viewer: parses them in the
// worker (one after another, one progress bar for all), then applies them in the order that makes
// sense whatever the order they came in: the animation first (it makes the run), then its force
// chains, then a boundary mesh. A bad file is reported by name and line and leaves the run that
// was shown before untouched. A load can be cancelled (#load-cancel), and a new choice of files
// cancels the one still loading: a small file is not kept waiting behind a large one.

import { parseFile } from '../formats/load_files.js';
import { counted } from '../words.js';

const ORDER = { animation: 0, forceChains: 1, mesh: 2 };
let queue = Promise.resolve(); // loads run one at a time, in the order the user asked
let loading = null; // the AbortController of the load in progress
let waitingChains = null; // force chains opened before any animation: attached to the next one

// Drops the force chains kept for an animation to come: the Viewer calls it when a run is set by
// anything but this loader (a live follow or a replay).
export function forgetWaitingChains() {
  waitingChains = null;
}

// Cancels the load in progress, if any (the run shown before stays).
export function cancelLoading() {
  if (loading) loading.abort();
}

export function loadFiles(viewer, files) {
  cancelLoading();
  const controller = new AbortController();
  loading = controller;
  queue = queue.then(() => load(viewer, [...files], controller.signal))
    .catch((error) => viewer.message(String(error), true))
    .finally(() => { if (loading === controller) loading = null; });
  return queue;
}

async function load(viewer, files, signal) {
  if (!files.length) return;
  const names = files.map((f) => f.name).join(', ');
  if (signal.aborted) {
    viewer.message(`${names}: not loaded, other files were chosen`);
    return;
  }
  const progress = document.getElementById('load-progress');
  const cancel = document.getElementById('load-cancel');
  progress.hidden = false;
  progress.value = 0;
  if (cancel) cancel.hidden = false;
  viewer.message(`Loading ${names}, please wait`);
  // A follow or replay started while the files are parsed replaces the run: their result is then
  // dropped rather than put over it.
  const generation = viewer.runGeneration;
  const parsed = [];
  try {
    for (let k = 0; k < files.length; k++) {
      const file = files[k];
      try {
        const result = await parseFile(file, (fraction) => { progress.value = (k + fraction) / files.length; }, signal);
        parsed.push({ file, result });
      } catch (error) {
        if (signal.aborted) break;
        parsed.push({ file, result: { kind: null, problem: `could not be read: ${error.message}` } });
      }
    }
  } finally {
    progress.value = 1;
    progress.hidden = true;
    if (cancel) cancel.hidden = true;
  }
  if (signal.aborted) {
    // the newer choice's own message follows at once; a cancel by the button stays
    viewer.message(`Loading ${names} cancelled; the run shown before stays`);
    return;
  }
  if (viewer.runGeneration !== generation) {
    viewer.message(`${files.map((f) => f.name).join(', ')}: not shown, another run was opened while they were read`);
    return;
  }
  // sort is stable: files of one kind keep the order they were given in
  parsed.sort((a, b) => (ORDER[a.result.kind] ?? 3) - (ORDER[b.result.kind] ?? 3));

  const notes = [];
  let failed = false;
  for (const { file, result } of parsed) {
    const name = file.name;
    // A malformed file (not merely cut short) is refused whole: frames after a bad line cannot be
    // trusted, and the run shown before stays.
    if (!result.kind || (result.problem && !result.truncated)) {
      notes.push(`${name}: ${result.problem}`);
      failed = true;
      continue;
    }
    if (result.kind === 'mesh') {
      viewer.setMesh(result.mesh);
      notes.push(`${name}: mesh of ${counted(result.mesh.vertices.length / 3, 'vertex', 'vertices')} and ${counted(result.mesh.triangles.length / 3, 'triangle')}`);
      continue;
    }
    if (!result.frames.length) {
      notes.push(`${name}: no complete frame (${result.problem || 'the file is empty'})`);
      failed = true;
      continue;
    }
    const cut = result.truncated ? `; the file is cut short, the last frame is incomplete and not shown: ${result.problem}` : '';
    if (result.kind === 'animation') {
      // A mesh loaded on its own before any animation (a terrain first) stays with the new run.
      const previous = viewer.run;
      const keepMesh = previous && !previous.frames.length ? previous.mesh : null;
      viewer.setRun({ frames: result.frames, mesh: keepMesh, unit: 'file', source: name }, { fromFiles: true });
      // the particles of the frames: one count, or the least and most when they vary
      let fewest = Infinity, most = 0;
      for (const f of result.frames) { fewest = Math.min(fewest, f.count); most = Math.max(most, f.count); }
      const noun = result.frames[0].planar ? 'disc' : 'particle';
      const count = fewest === most ? counted(most, noun) : `${fewest} to ${most} ${noun}s`;
      const what = result.frames[0].planar ? `${count} (2D, the x-z plane seen from -y)` : count;
      notes.push(`${name}: ${counted(result.frames.length, 'frame')} of ${what}${cut}`);
      const repeated = result.frames.filter((f) => f.stats.repeatedId);
      if (repeated.length) {
        const more = repeated.length > 1 ? ` (and in ${counted(repeated.length - 1, 'more frame')})` : '';
        notes.push(`${name}: particle id ${repeated[0].stats.repeatedId} is given twice at step ${repeated[0].step}${more}; ` +
          'force chains and the probe take the last particle of an id');
      }
      if (waitingChains) {
        const matched = viewer.setForceChains(waitingChains.frames);
        notes.push(`${waitingChains.name} (opened before): ${counted(matched, 'frame')} matched by step`);
        waitingChains = null;
      }
    } else if (!viewer.run || !viewer.run.frames.length) {
      waitingChains = { name, frames: result.frames };
      notes.push(`${name}: ${counted(result.frames.length, 'frame')} of force chains, kept for the animation file to come${cut}`);
    } else {
      const matched = viewer.setForceChains(result.frames);
      const frames = viewer.run ? viewer.run.frames.length : 0;
      notes.push(`${name}: ${counted(result.frames.length, 'frame')} of force chains, ${matched} of the ${counted(frames, 'animation frame')} matched by step${cut}`);
    }
  }
  viewer.message(notes.join('\n'), failed);
}
