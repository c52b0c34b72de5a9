// Probing the particles: a click on a particle shows all its values (#probe), a shift-click on a
// second measures the distance between the two, and the pointer's particle is named as it moves
// (#hover-readout). The picked particle is followed by id from frame to frame and ringed in the view.
//
// Picking is a ray cast on the CPU against the frame's spheres (the particles left by the section):
// the same for instanced spheres and impostors, about 10 ms for a million particles, and only on a
// click or once an animation frame while the pointer moves.

import * as THREE from 'three';
import { formatValue } from './colours.js';
import { counted } from '../words.js';

// A pointer that moves more than this (px) between press and release is dragging the view.
const CLICK_SLOP = 4;
// Chains of the probed particle listed in #probe, strongest first.
const CHAINS_LISTED = 8;

const $ = (id) => document.getElementById(id);

// The index (in the frame) of the nearest visible particle under the canvas point (x, y) (client
// pixels), or -1.
export function pickParticle(viewer, clientX, clientY) {
  const frame = viewer.currentFrame();
  if (!frame || !viewer.particles || viewer.particles.hidden) return -1;
  const stage = viewer.stage;
  const rect = stage.canvas.getBoundingClientRect();
  const ndc = new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
  const ray = new THREE.Raycaster();
  stage.camera.updateMatrixWorld();
  ray.setFromCamera(ndc, stage.camera);
  const o = ray.ray.origin, d = ray.ray.direction;
  const p = frame.positions, r = frame.radii;
  let best = -1, bestT = Infinity;
  for (let v = 0; v < viewer.drawnCount; v++) {
    const k = viewer.visible[v];
    // |o + t d - c|^2 = r^2 with |d| = 1: t = b -+ sqrt(b^2 - (|o - c|^2 - r^2)), b = d . (c - o)
    const cx = p[k * 3] - o.x, cy = p[k * 3 + 1] - o.y, cz = p[k * 3 + 2] - o.z;
    const b = cx * d.x + cy * d.y + cz * d.z;
    const disc = b * b - (cx * cx + cy * cy + cz * cz - r[k] * r[k]);
    if (disc < 0) continue;
    const t = b - Math.sqrt(disc);
    if (t > 0 && t < bestT) { bestT = t; best = k; }
  }
  return best;
}

// The values of particle k of a frame, as [label, text] rows, with the unit of the run's lengths.
function particleRows(frame, k, unit) {
  const v3 = (a) => `${formatValue(a[k * 3])}, ${formatValue(a[k * 3 + 1])}, ${formatValue(a[k * 3 + 2])}`;
  const speed = Math.hypot(frame.velocities[k * 3], frame.velocities[k * 3 + 1], frame.velocities[k * 3 + 2]);
  const rows = [
    ['position', `${v3(frame.positions)} ${unit}`],
    ['velocity', `${v3(frame.velocities)} ${unit}/s`],
    ['speed', `${formatValue(speed)} ${unit}/s`],
    ['diameter', `${formatValue(2 * frame.radii[k])} ${unit}`],
  ];
  if (frame.spins) rows.push(['spin', `${v3(frame.spins)} rad/s`]);
  if (frame.parts) rows.push(['part', String(frame.parts[k])]);
  if (frame.contacts) rows.push(['contacts', String(frame.contacts[k])]);
  return rows;
}

// The frame's force chains that have particle `id` (0-based) at one end: [{ other, fn, ft }],
// strongest first.
function chainsOf(frame, id) {
  const chains = frame.forceChains;
  if (!chains) return null;
  const count = chains.count ?? chains.i.length;
  const found = [];
  for (let c = 0; c < count; c++) {
    if (chains.i[c] === id) found.push({ other: chains.j[c], fn: chains.fn[c], ft: chains.ft ? chains.ft[c] : NaN });
    else if (chains.j[c] === id) found.push({ other: chains.i[c], fn: chains.fn[c], ft: chains.ft ? chains.ft[c] : NaN });
  }
  found.sort((a, b) => Math.abs(b.fn) - Math.abs(a.fn));
  return found;
}

export class Probe {
  constructor(viewer) {
    this.viewer = viewer;
    this.picked = []; // up to two particle ids (1-based, as in the files) being probed
    this.marker = new THREE.Group();
    this.marker.visible = false;
    viewer.stage.scene.add(this.marker);
    this.hoverPending = false;
    const canvas = viewer.stage.canvas;
    let down = null;
    canvas.addEventListener('pointerdown', (e) => { down = { x: e.clientX, y: e.clientY }; });
    canvas.addEventListener('pointerup', (e) => {
      if (!down || Math.hypot(e.clientX - down.x, e.clientY - down.y) > CLICK_SLOP) return;
      down = null;
      this.click(e.clientX, e.clientY, e.shiftKey);
    });
    canvas.addEventListener('pointermove', (e) => this.hover(e.clientX, e.clientY));
    canvas.addEventListener('pointerleave', () => { $('hover-readout').hidden = true; });
    $('probe-close').addEventListener('click', () => this.clear());
    viewer.onChange(() => this.update());
  }

  // The 1-based id of particle k of the current frame.
  idOf(k) {
    const frame = this.viewer.currentFrame();
    return frame.ids ? frame.ids[k] : k + 1;
  }

  // The index in the current frame of the particle with 1-based id `id`, or -1.
  indexOf(id) {
    const frame = this.viewer.currentFrame();
    return frame ? this.viewer.indexOfId(frame)(id - 1) : -1;
  }

  click(x, y, measure) {
    const k = pickParticle(this.viewer, x, y);
    if (k < 0) {
      if (!measure) this.clear();
      return;
    }
    const id = this.idOf(k);
    // a shift-click on the probed particle itself measures nothing
    if (measure && this.picked.length && id === this.picked[0]) this.picked = [id];
    else this.picked = measure && this.picked.length ? [this.picked[0], id] : [id];
    this.update();
  }

  clear() {
    this.picked = [];
    this.update();
  }

  // Another run replaced the one probed: its particles are not these.
  forget() {
    this.picked = [];
    $('hover-readout').hidden = true;
    this.update();
  }

  hover(x, y) {
    this.hoverAt = [x, y];
    if (this.hoverPending) return;
    this.hoverPending = true;
    requestAnimationFrame(() => {
      this.hoverPending = false;
      const [hx, hy] = this.hoverAt;
      const k = pickParticle(this.viewer, hx, hy);
      const readout = $('hover-readout');
      if (k < 0) {
        readout.hidden = true;
        return;
      }
      const frame = this.viewer.currentFrame();
      const speed = Math.hypot(frame.velocities[k * 3], frame.velocities[k * 3 + 1], frame.velocities[k * 3 + 2]);
      readout.textContent = `particle ${this.idOf(k)} · speed ${formatValue(speed)} · D ${formatValue(2 * frame.radii[k])}`;
      const rect = this.viewer.stage.container.getBoundingClientRect();
      readout.hidden = false;
      // beside the pointer, turned to its left or above it near the view's right or bottom edge
      const w = readout.offsetWidth, h = readout.offsetHeight;
      const left = hx - rect.left + 14 + w > rect.width ? hx - rect.left - 14 - w : hx - rect.left + 14;
      const top = hy - rect.top + 14 + h > rect.height ? hy - rect.top - 14 - h : hy - rect.top + 14;
      readout.style.left = `${Math.max(0, left)}px`;
      readout.style.top = `${Math.max(0, top)}px`;
    });
  }

  // Refreshes #probe and the rings for the current frame (the particles are found again by id), and
  // the hover readout (the particle under the pointer changes with the frame).
  update() {
    if (!$('hover-readout').hidden && this.hoverAt) this.hover(...this.hoverAt);
    const box = $('probe');
    const frame = this.viewer.currentFrame();
    const found = frame ? this.picked.map((id) => ({ id, k: this.indexOf(id) })) : [];
    this.placeMarkers(frame, found.filter((f) => f.k >= 0));
    if (!this.picked.length) {
      box.hidden = true;
      return;
    }
    box.hidden = false;
    const unit = this.viewer.lengthUnitName() || '(file length unit)';
    const lines = [];
    const first = found[0];
    if (!first || first.k < 0) {
      lines.push(`<h3>Particle ${first ? first.id : ''}</h3><p>not in this frame</p>`);
    } else {
      lines.push(`<h3>Particle ${first.id}</h3><dl>`);
      for (const [label, text] of particleRows(frame, first.k, unit)) lines.push(`<dt>${label}</dt><dd data-field="${label}">${text}</dd>`);
      lines.push('</dl>');
      const chains = chainsOf(frame, first.id - 1);
      if (chains) {
        lines.push(`<p data-field="chains">${counted(chains.length, 'force chain')} in this frame${chains.length ? ':' : ''}</p><ul>`);
        for (const c of chains.slice(0, CHAINS_LISTED)) {
          lines.push(`<li>to ${c.other + 1}: Fn ${formatValue(c.fn)} N, Ft ${formatValue(c.ft)} N</li>`);
        }
        if (chains.length > CHAINS_LISTED) lines.push(`<li>and ${chains.length - CHAINS_LISTED} more</li>`);
        lines.push('</ul>');
      }
    }
    if (found.length === 2) {
      const [a, b] = found;
      if (a.k >= 0 && b.k >= 0) {
        const p = frame.positions, r = frame.radii;
        const d = Math.hypot(p[a.k * 3] - p[b.k * 3], p[a.k * 3 + 1] - p[b.k * 3 + 1], p[a.k * 3 + 2] - p[b.k * 3 + 2]);
        const gap = d - r[a.k] - r[b.k];
        lines.push(`<p data-field="distance">From particle ${a.id} to ${b.id}: centres ${formatValue(d)} ${unit} apart, ` +
                   `surfaces ${formatValue(gap)} ${unit} (${gap < 0 ? 'overlapping' : 'a gap'})</p>`);
      } else {
        const missing = a.k < 0 ? a : b;
        lines.push(`<p data-field="distance">Particle ${missing.id} is not in this frame</p>`);
      }
    } else {
      lines.push('<p class="hint">Shift-click another particle to measure the distance.</p>');
    }
    $('probe-body').innerHTML = lines.join('');
  }

  // A ring (three circles, one per axis plane) round each probed particle.
  placeMarkers(frame, found) {
    this.marker.clear();
    for (const { k } of found) {
      const ring = new THREE.Group();
      const r = frame.radii[k] * 1.25;
      for (const axis of ['x', 'y', 'z']) {
        const circle = new THREE.LineLoop(CIRCLE, MARKER_MATERIAL);
        if (axis === 'x') circle.rotation.y = Math.PI / 2;
        if (axis === 'y') circle.rotation.x = Math.PI / 2;
        ring.add(circle);
      }
      ring.scale.setScalar(r);
      ring.position.set(frame.positions[k * 3], frame.positions[k * 3 + 1], frame.positions[k * 3 + 2]);
      this.marker.add(ring);
    }
    this.marker.visible = found.length > 0;
    this.viewer.stage.requestRender();
  }
}

const CIRCLE = new THREE.BufferGeometry().setFromPoints(
  Array.from({ length: 48 }, (_, i) => new THREE.Vector3(Math.cos((i / 48) * 2 * Math.PI), Math.sin((i / 48) * 2 * Math.PI), 0)));
const MARKER_MATERIAL = new THREE.LineBasicMaterial({ color: 0xff00ff, depthTest: false });
