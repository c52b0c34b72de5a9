// The viewer page: owns the Viewer (the run being shown and the display settings), wires the side
// panel's controls to it, loads files dropped or chosen offline, and lets the live panel (written
// separately, src/live/panel.js) feed it frames from dem-server. docs/viewer.md is the contract for
// the run model, the element ids and window.demViewer.

import { Stage } from './view/scene.js';
import { Particles } from './view/particles.js';
import { ForceChainView } from './view/force_chains.js';
import { BoundaryView } from './view/boundary.js';
import { particleColours, hexToRgb } from './view/colours.js';
import { QUANTITIES, frameRange, partSizes, widen } from './view/quantities.js';
import { addStats } from './formats/stats.js';
import { wireControls } from './view/controls.js';
import { Playback } from './view/playback.js';
import { loadFiles, forgetWaitingChains, cancelLoading } from './view/file_drop.js';
import { Probe } from './view/probe.js';
import { parseFile } from './formats/load_files.js';
import { wireCamera } from './view/camera_tools.js';

// Live frames kept in memory: about this many bytes (positions, velocities, radii, parts, force
// chains and a fixed overhead per frame), and at most this many frames.
const LIVE_BYTES = 512 * 1024 * 1024;
const LIVE_FRAMES = 5000;
const FRAME_OVERHEAD = 2048;
const BYTES_PER_CONTACT = 16;
// The particles' opacity while force chains are drawn, unless the user chose one.
const CHAIN_PARTICLE_OPACITY = 0.3;

// The bytes a live frame holds (an estimate, for the live memory cap).
function frameBytes(frame) {
  const n = frame.count || 0;
  let bytes = FRAME_OVERHEAD + 28 * n;
  if (frame.parts) bytes += 4 * n;
  if (frame.forceChains) bytes += BYTES_PER_CONTACT * (frame.forceChains.count ?? (frame.forceChains.i ? frame.forceChains.i.length : 0));
  return bytes;
}

const $ = (id) => document.getElementById(id);

export class Viewer {
  constructor(stage) {
    this.stage = stage;
    this.particles = new Particles(stage);
    this.chains = new ForceChainView(stage);
    this.boundary = new BoundaryView(stage);
    this.playback = new Playback(this);
    this.run = null;
    this.runGeneration = 0; // bumped by setRun: late results meant for an older run are dropped
    this.liveBytes = 0; // bytes of the live frames kept (frameBytes)
    this.frameIndex = -1;
    this.live = false;
    this.follow = true; // live: show the newest frame as frames arrive (until the user moves away)
    this.chainsByStep = new Map();
    this.fnMax = 0;
    this.bounds = null; // { min, max, speed, diameter, partMax } over the frames of the run
    this.runRanges = new Map();
    this.settings = {
      colourMode: 'speed', constantColour: '#2e8b57',
      colourMap: 'legacy', // colours.js COLOUR_MAPS
      colourRangeMode: 'run', // the colour scale over the whole run, this frame, or `colourRangeManual`
      colourRangeManual: [0, 1],
      sectionFront: 0, sectionRear: 1000, sectionAxis: [0, 1, 0], // the section's direction (unit vector)
      showChains: false, chainThickness: 30, chainShowParticles: true, particleOpacity: 1,
      opacityChosen: false, // the user set the particles' opacity: chains no longer change it
      showBoundary: true,
    };
    this.visible = new Uint32Array(0); // indices of the particles left by the section
    this.shown = new Uint8Array(0); // 1 per particle left by the section
    this.colours = new Float32Array(0);
    this.drawnCount = 0;
    this.listeners = [];
  }

  // ---- the methods other modules call (docs/viewer.md) ----

  // Replaces the run: frames (maybe none yet), mesh, unit. Resets chains and the live flag. Returns
  // the run's generation (runGeneration): addFrame / setForceChains / setMesh given an older one
  // are ignored. options.fromFiles: set by the file loader (file_drop.js); any other caller (a
  // follow or replay) also drops force chains the file loader keeps for an animation to come.
  setRun(run, options = {}) {
    this.runGeneration += 1;
    if (!options.fromFiles) forgetWaitingChains();
    this.playback.pause();
    this.run = { frames: [], mesh: null, unit: 'file', ...run };
    this.run.frames = this.run.frames || [];
    this.live = false;
    this.liveSet = false;
    this.follow = true;
    this.chainsByStep = new Map();
    this.latestChains = null; // live: the newest frame's chains that had any, and its step
    this.fnMax = 0;
    this.bounds = null;
    this.runRanges = new Map(); // a quantity's [min, max] over the run's frames, by colour mode
    for (const frame of this.run.frames) {
      this.extendBounds(addStats(frame));
      this.extendChainScale(frame.forceChains);
    }
    this.boundary.setMesh(this.run.mesh);
    if (this.probe) this.probe.forget();
    this.frameCamera();
    this.frameIndex = -1;
    this.liveBytes = 0;
    if (this.run.frames.length) this.showFrame(0);
    else this.clearView();
    this.changed();
    return this.runGeneration;
  }

  // Whether a call made for run generation `generation` (undefined: no generation given) is stale.
  stale(generation) {
    return generation !== undefined && generation !== null && generation !== this.runGeneration;
  }

  // Appends a frame (live). Shown at once while following the newest frame. `generation` (optional,
  // setRun's answer): the frame is dropped (false returned) when another run has replaced that one.
  addFrame(frame, generation) {
    if (this.stale(generation)) return false;
    if (!this.run) this.setRun({ frames: [], mesh: null, unit: 'm' });
    if (!this.liveSet) this.live = true; // unless the live panel says otherwise with setLive
    addStats(frame);
    if (!frame.forceChains && this.chainsByStep.has(frame.step)) frame.forceChains = this.chainsByStep.get(frame.step);
    this.extendChainScale(frame.forceChains);
    if (frame.forceChains) this.latestChains = { chains: frame.forceChains, step: frame.step };
    const first = this.run.frames.length === 0;
    frame.liveBytes = frameBytes(frame);
    this.run.frames.push(frame);
    this.liveBytes += frame.liveBytes;
    // A live run keeps its newest frames only, about LIVE_BYTES and at most LIVE_FRAMES of them: a
    // long job of many particles would otherwise fill the page's memory (Replay loads the whole run
    // from its files).
    const frames = this.run.frames;
    let drop = 0;
    let bytes = this.liveBytes;
    while (frames.length - drop > 2 && (bytes > LIVE_BYTES || frames.length - drop > LIVE_FRAMES)) {
      bytes -= frames[drop].liveBytes ?? frameBytes(frames[drop]);
      drop += 1;
    }
    let viewGone = false; // the frame in view was among those dropped
    if (drop > 0) {
      frames.splice(0, drop);
      this.liveBytes = bytes;
      viewGone = this.frameIndex >= 0 && this.frameIndex < drop;
      this.frameIndex = Math.max(0, this.frameIndex - drop);
    }
    this.extendBounds(frame);
    if (this.runRanges.size) {
      const context = this.colourContext();
      for (const [mode, range] of this.runRanges) {
        if (range) this.runRanges.set(mode, widen(range, frameRange(QUANTITIES[mode], frame, context)));
      }
    }
    if (first) {
      this.frameCamera();
      this.showFrame(frames.length - 1);
    } else if (this.follow) {
      this.showNewestSoon();
      this.changed();
    } else if (viewGone) {
      this.redraw(); // the frame in view may have gone: picture and read-outs agree
    } else {
      this.changed();
    }
    return true;
  }

  // Following a live run: shows the newest frame at the next picture, once however many frames
  // arrived since. Drawing each frame as it arrives let a view slower than the stream fall further
  // and further behind it (frames wait in the page's queue, each drawn in turn).
  showNewestSoon() {
    if (this.newestPending) return;
    this.newestPending = true;
    const show = () => {
      this.newestPending = false;
      if (this.follow && this.run && this.run.frames.length) this.showFrame(this.run.frames.length - 1);
    };
    // a hidden page gets no animation frames: it catches up when shown again, or every half second
    if (typeof document !== 'undefined' && document.hidden) setTimeout(show, 500);
    else requestAnimationFrame(show);
  }

  // Attaches force-chain frames ({ step, count, i, j, fn, ft }) to the run's frames of equal step.
  // `generation` (optional, setRun's answer): ignored (0 returned) when another run replaced that one.
  setForceChains(framesOfChains, generation) {
    if (this.stale(generation)) return 0;
    this.chainsByStep = new Map();
    this.fnMax = 0;
    for (const chains of framesOfChains || []) {
      this.chainsByStep.set(chains.step, chains);
      this.extendChainScale(chains);
    }
    let matched = 0;
    for (const frame of this.run ? this.run.frames : []) {
      frame.forceChains = this.chainsByStep.get(frame.step) || null;
      if (frame.forceChains) matched += 1;
    }
    this.redraw();
    return matched;
  }

  // A fixed boundary mesh { vertices, triangles } (or null).
  setMesh(mesh, generation) {
    if (this.stale(generation)) return;
    if (!this.run) this.setRun({ frames: [], mesh: null, unit: 'file' }, { fromFiles: true }); // keeps chains waiting
    this.run.mesh = mesh;
    this.boundary.setMesh(mesh);
    this.frameCamera(); // a terrain is usually larger than the particles on it
  }

  // Shows frame `index` (0-based; clamped to the run).
  showFrame(index) {
    if (!this.run || !this.run.frames.length) return;
    const last = this.run.frames.length - 1;
    this.frameIndex = Math.max(0, Math.min(last, Math.round(Number(index) || 0)));
    this.follow = this.frameIndex === last;
    this.redraw();
  }

  message(text, isError = false) {
    const element = $('message');
    element.textContent = text;
    element.classList.toggle('error', Boolean(isError));
  }

  // Marks the run as live (frames still arriving) or finished; addFrame sets it, setRun clears it.
  setLive(on) {
    this.live = Boolean(on);
    this.liveSet = true;
    this.changed();
  }

  state() {
    const frame = this.currentFrame();
    return {
      particles: frame ? frame.count : 0,
      frames: this.run ? this.run.frames.length : 0,
      frameIndex: this.frameIndex,
      time: frame ? frame.time : null,
      step: frame ? frame.step : null,
      visible: frame ? this.drawnCount : 0,
      planar: Boolean(frame && frame.planar), // a 2D run's discs (ANIMATION_2D.dat)
      colourMode: this.settings.colourMode,
      playing: this.playback.playing,
      live: this.live,
    };
  }

  // ---- display ----

  currentFrame() {
    return this.run && this.frameIndex >= 0 ? this.run.frames[this.frameIndex] || null : null;
  }

  // Changes display settings ({ colourMode: 'part', ... }) and redraws.
  set(changes) {
    Object.assign(this.settings, changes);
    this.redraw();
  }

  // Called after any change of what is shown: the controls refresh their read-outs.
  onChange(listener) {
    this.listeners.push(listener);
  }

  changed() {
    for (const listener of this.listeners) listener(this);
  }

  extendBounds(frame) {
    const s = frame.stats;
    if (!frame.count) return;
    if (!this.bounds) {
      this.bounds = { min: [...s.min], max: [...s.max], speed: [...s.speed], diameter: [...s.diameter], partMax: s.partMax };
      return;
    }
    const b = this.bounds;
    for (let c = 0; c < 3; c++) {
      b.min[c] = Math.min(b.min[c], s.min[c]);
      b.max[c] = Math.max(b.max[c], s.max[c]);
    }
    b.speed = [Math.min(b.speed[0], s.speed[0]), Math.max(b.speed[1], s.speed[1])];
    b.diameter = [Math.min(b.diameter[0], s.diameter[0]), Math.max(b.diameter[1], s.diameter[1])];
    b.partMax = Math.max(b.partMax, s.partMax);
  }

  // The largest |Fn| of the run (shown in the legend next to the frame's own).
  extendChainScale(chains) {
    if (chains) this.fnMax = Math.max(this.fnMax, addStats(chains).stats.fnMax);
  }

  // The name of the run's length unit: metres for live frames, the files' unit when known (a job's
  // replay: its lengthUnit), else null (files opened from disk do not say).
  lengthUnitName() {
    if (!this.run) return null;
    return this.run.unit === 'm' ? 'm' : this.run.lengthUnit || null;
  }

  // What a quantity needs beside the frame: the run's first frame (displacement) and part sizes.
  colourContext() {
    const reference = this.run && this.run.frames.length ? this.run.frames[0] : null;
    return { reference, referenceIndex: reference ? this.indexOfId(reference) : () => -1, partSizes };
  }

  // The colour map the current mode draws with: its own (Part's green to red), or the one chosen.
  colourMapName() {
    const quantity = QUANTITIES[this.settings.colourMode];
    return (quantity && quantity.map) || this.settings.colourMap;
  }

  // The colour scale's [min, max] for the current mode: over the run (as the legacy bar), over the
  // frame shown, or as set by hand (`rangeMode`: 'run', 'frame', 'manual'; the one chosen by
  // default); null for Parts and Constant colour.
  colourRange(rangeMode = this.settings.colourRangeMode) {
    const mode = this.settings.colourMode;
    const quantity = QUANTITIES[mode];
    if (!quantity || !this.bounds) return null;
    const s = this.settings;
    if (rangeMode === 'manual') return s.colourRangeManual;
    if (rangeMode === 'frame') {
      const frame = this.currentFrame();
      return frame ? frameRange(quantity, frame, this.colourContext()) : null;
    }
    if (mode === 'speed') return this.bounds.speed;
    if (mode === 'diameter') return this.bounds.diameter;
    if (!this.runRanges.has(mode)) {
      let range = null;
      const context = this.colourContext();
      for (const frame of this.run.frames) range = widen(range, frameRange(quantity, frame, context));
      this.runRanges.set(mode, range);
    }
    return this.runRanges.get(mode);
  }

  // Puts the camera on the particles of the frame shown, those left by the section (a landslide
  // block on a 4 km terrain, not the terrain); the whole run when there is no frame.
  fitParticles() {
    const frame = this.currentFrame();
    if (!frame || !this.drawnCount) return this.frameCamera();
    const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
    const p = frame.positions, r = frame.radii;
    for (let v = 0; v < this.drawnCount; v++) {
      const k = this.visible[v];
      for (let c = 0; c < 3; c++) {
        min[c] = Math.min(min[c], p[k * 3 + c] - r[k]);
        max[c] = Math.max(max[c], p[k * 3 + c] + r[k]);
      }
    }
    this.stage.frame(min, max, { planar: Boolean(frame.planar), direction: this.stage.viewDirection() });
  }

  // The mean position of the particles left by the section (the camera's target when following).
  particlesCentre() {
    const frame = this.currentFrame();
    if (!frame || !this.drawnCount) return null;
    const sum = [0, 0, 0];
    for (let v = 0; v < this.drawnCount; v++) for (let c = 0; c < 3; c++) sum[c] += frame.positions[this.visible[v] * 3 + c];
    return sum.map((s) => s / this.drawnCount);
  }

  // Puts the camera on the run: the particles' extent and the frame's plates, or the mesh alone.
  frameCamera() {
    let min = null, max = null;
    const grow = (lo, hi) => {
      if (!min) { min = [...lo]; max = [...hi]; return; }
      for (let c = 0; c < 3; c++) { min[c] = Math.min(min[c], lo[c]); max[c] = Math.max(max[c], hi[c]); }
    };
    if (this.bounds) {
      const r = this.bounds.diameter[1] / 2;
      grow(this.bounds.min.map((v) => v - r), this.bounds.max.map((v) => v + r));
    }
    const first = this.run && this.run.frames[0];
    if (first && first.plates) {
      for (let k = 0; k < first.plates.length; k += 3) grow(first.plates.subarray(k, k + 3), first.plates.subarray(k, k + 3));
    }
    const meshBox = this.boundary.meshBounds();
    if (meshBox) grow(meshBox[0], meshBox[1]);
    if (min) this.stage.frame(min, max, { planar: Boolean(first && first.planar) });
  }

  clearView() {
    this.drawnCount = 0;
    this.particles.clear();
    this.chains.hide();
    this.boundary.drawFrame(null);
  }

  // Draws the current frame with the current settings.
  redraw() {
    const frame = this.currentFrame();
    if (!frame) {
      this.clearView();
      this.changed();
      return;
    }
    const n = frame.count;
    if (this.visible.length < n) {
      this.visible = new Uint32Array(n);
      this.shown = new Uint8Array(n);
      this.colours = new Float32Array(n * 3);
    }
    // Section along an axis (legacy Scaling Front / Rear: along y): Front hides from the front
    // (small coordinates), Rear from the back, in thousandths of the run's extent along the axis. The
    // two together leave a slice.
    const s = this.settings;
    const [ax, ay, az] = s.sectionAxis;
    const [c0, c1] = this.sectionExtent();
    const front = s.sectionFront <= 0 ? -Infinity : c0 + (s.sectionFront / 1000) * (c1 - c0);
    const rear = s.sectionRear >= 1000 ? Infinity : c0 + (s.sectionRear / 1000) * (c1 - c0);
    const p = frame.positions;
    let drawn = 0;
    for (let k = 0; k < n; k++) {
      const c = p[k * 3] * ax + p[k * 3 + 1] * ay + p[k * 3 + 2] * az;
      const inside = c >= front && c <= rear ? 1 : 0;
      this.shown[k] = inside;
      if (inside) this.visible[drawn++] = k;
    }
    this.drawnCount = drawn;

    particleColours(frame, s.colourMode, this.colourRange() || [0, 1], hexToRgb(s.constantColour), this.colours,
                    { quantity: QUANTITIES[s.colourMode] || null, context: this.colourContext(), map: this.colourMapName() });
    this.particles.draw(frame, this.visible, drawn, this.colours);
    this.particles.setVisible(!s.showChains || s.chainShowParticles);

    // A live job sends chains with its output frames only: between them, the latest chains
    // received are drawn between the particles' new places (the legend names their step).
    const chains = this.chainsShown(frame);
    if (s.showChains && chains) {
      const baseRadius = (this.bounds ? this.bounds.diameter[1] / 2 : 1) * 0.5 * (s.chainThickness / 30);
      // Scaled to this frame's strongest chain: a run's largest force is often an impact early on,
      // which would leave the resting packing's network uniformly thin and blue.
      this.chains.draw(frame, chains.chains, this.indexOfId(frame), this.shown, baseRadius);
    } else {
      this.chains.hide();
    }
    // Opaque particles hide the chains between their centres: while chains are drawn they are made
    // translucent (the legacy T/C), unless the user chose an opacity.
    if (!s.opacityChosen) {
      const opacity = s.showChains && this.chains.drawn > 0 ? CHAIN_PARTICLE_OPACITY : 1;
      if (this.particles.opacity !== opacity) this.particles.setOpacity(opacity);
    }
    this.boundary.drawFrame(frame);
    this.changed();
  }

  // The run's extent [min, max] along the section's axis: the bounds' corners projected on it.
  sectionExtent() {
    if (!this.bounds) return [0, 0];
    const { min, max } = this.bounds;
    const [ax, ay, az] = this.settings.sectionAxis;
    let lo = Infinity, hi = -Infinity;
    for (const x of [min[0], max[0]]) for (const y of [min[1], max[1]]) for (const z of [min[2], max[2]]) {
      const c = x * ax + y * ay + z * az;
      lo = Math.min(lo, c);
      hi = Math.max(hi, c);
    }
    return [lo, hi];
  }

  // The force chains to draw with `frame`: its own ({ chains, step }), or on a live run the latest
  // received; null when none.
  chainsShown(frame) {
    if (frame.forceChains) return { chains: frame.forceChains, step: frame.step };
    return this.live && this.latestChains && this.latestChains.step <= frame.step ? this.latestChains : null;
  }

  // Maps a 0-based particle id (force chains) to the particle's index in the frame: the identity
  // when the frame lists ids 1..N in order, as the engine writes them; a table otherwise (particles
  // removed from the run leave gaps).
  indexOfId(frame) {
    if (!frame.ids) return (id) => (id < frame.count ? id : -1);
    if (!frame.indexOfId) {
      let identity = true;
      let maxId = 0;
      for (let k = 0; k < frame.count; k++) {
        if (frame.ids[k] !== k + 1) identity = false;
        if (frame.ids[k] > maxId) maxId = frame.ids[k];
      }
      if (identity) {
        frame.indexOfId = (id) => (id < frame.count ? id : -1);
      } else if (maxId <= 4 * frame.count + 1024) {
        const table = new Int32Array(maxId).fill(-1);
        for (let k = 0; k < frame.count; k++) if (frame.ids[k] > 0) table[frame.ids[k] - 1] = k;
        frame.indexOfId = (id) => (id >= 0 && id < table.length ? table[id] : -1);
      } else {
        // sparse ids (one particle numbered 2,147,483,647): a table that long would take gigabytes
        const map = new Map();
        for (let k = 0; k < frame.count; k++) if (frame.ids[k] > 0) map.set(frame.ids[k] - 1, k);
        frame.indexOfId = (id) => map.get(id) ?? -1;
      }
    }
    return frame.indexOfId;
  }
}

// ---- the page ----

function start() {
  const stage = new Stage($('view'));
  const viewer = new Viewer(stage);
  wireControls(viewer);
  viewer.probe = new Probe(viewer);
  wireCamera(viewer);
  window.demViewer = { state: () => viewer.state(), viewer, loadFiles: (files) => loadFiles(viewer, files), parseFile };

  // Offline files: the file input and drag-and-drop anywhere on the page.
  $('load-cancel').addEventListener('click', () => cancelLoading());
  $('message-close').addEventListener('click', () => viewer.message(''));
  $('file-input').addEventListener('change', (event) => {
    loadFiles(viewer, [...event.target.files]);
    event.target.value = ''; // choosing the same file again reloads it
  });
  document.addEventListener('dragover', (event) => {
    event.preventDefault();
    document.body.classList.add('dragging');
  });
  document.addEventListener('dragleave', (event) => {
    if (!event.relatedTarget) document.body.classList.remove('dragging');
  });
  document.addEventListener('drop', (event) => {
    event.preventDefault();
    document.body.classList.remove('dragging');
    if (event.dataTransfer && event.dataTransfer.files.length) loadFiles(viewer, [...event.dataTransfer.files]);
  });

  // The server's side (src/live/): a failure in it must not take the offline viewer down.
  import('./live/panel.js')
    .then((module) => module.initLivePanel(viewer))
    .catch((error) => viewer.message(`live panel: ${error.message}`, true));
}

start();
