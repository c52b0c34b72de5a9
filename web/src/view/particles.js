// Draws the particles of one frame. Up to IMPOSTOR_THRESHOLD spheres: an InstancedMesh of
// low-poly spheres (real geometry, three's own lighting). Past that, sphere impostors
// (impostors.js): one quad per sphere, so a million particles cost 4 vertices each instead of
// hundreds. Only the visible particles (after the Front/Rear section) are packed into the
// instances, so hidden ones cost nothing.

import * as THREE from 'three';
import { SphereImpostors } from './impostors.js';

export const IMPOSTOR_THRESHOLD = 100000;

// ?impostorsAbove=N in the page's address moves the switch (bench/viewer compares the two ways).
function impostorThreshold() {
  const given = typeof window === 'undefined' ? null : new URLSearchParams(window.location.search).get('impostorsAbove');
  const n = Number(given);
  return given !== null && given.trim() !== '' && Number.isFinite(n) && n >= 0 ? n : IMPOSTOR_THRESHOLD;
}

export class Particles {
  constructor(stage) {
    this.stage = stage;
    this.capacity = 0;
    this.mesh = null;
    this.impostors = new SphereImpostors(stage);
    this.material = new THREE.MeshPhongMaterial({ color: 0xffffff, shininess: 40, specular: 0x333333 });
    this.opacity = 1;
    this.drawn = 0;
  }

  // Fewer facets for more spheres: the picture stays smooth enough and the triangle count bounded.
  static geometryFor(count) {
    if (count <= 5000) return new THREE.SphereGeometry(1, 20, 14);
    if (count <= 30000) return new THREE.SphereGeometry(1, 14, 10);
    return new THREE.SphereGeometry(1, 10, 7);
  }

  // (Re)creates the InstancedMesh when more instances are needed or the detail level changes.
  ensureMesh(count) {
    const detail = count <= 5000 ? 0 : count <= 30000 ? 1 : 2;
    if (this.mesh && count <= this.capacity && detail === this.detail) return;
    if (this.mesh) {
      this.stage.scene.remove(this.mesh);
      this.mesh.geometry.dispose();
      this.mesh.dispose();
    }
    this.capacity = Math.max(count, 1);
    this.detail = detail;
    this.mesh = new THREE.InstancedMesh(Particles.geometryFor(count), this.material, this.capacity);
    this.mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    this.mesh.instanceColor = new THREE.InstancedBufferAttribute(new Float32Array(this.capacity * 3), 3);
    this.mesh.instanceColor.setUsage(THREE.DynamicDrawUsage);
    this.mesh.frustumCulled = false; // instances move every frame; no stale bounding sphere
    this.stage.scene.add(this.mesh);
  }

  // frame: the run model's frame; visible: Uint32Array of the particle indices to draw, `drawn`
  // of them; colours: linear RGB per particle (3 floats each).
  draw(frame, visible, drawn, colours) {
    this.drawn = drawn;
    if (frame.count > impostorThreshold()) {
      if (this.mesh) this.mesh.visible = false;
      this.impostors.draw(frame, visible, drawn, colours);
      this.stage.requestRender();
      return;
    }
    this.impostors.hide();
    this.ensureMesh(frame.count);
    const m = this.mesh.instanceMatrix.array;
    const c = this.mesh.instanceColor.array;
    const p = frame.positions;
    const r = frame.radii;
    for (let k = 0; k < drawn; k++) {
      const i = visible[k];
      const o = k * 16;
      const radius = r[i];
      // scale by the radius, translate to the centre (column-major 4x4)
      m[o] = radius; m[o + 1] = 0; m[o + 2] = 0; m[o + 3] = 0;
      m[o + 4] = 0; m[o + 5] = radius; m[o + 6] = 0; m[o + 7] = 0;
      m[o + 8] = 0; m[o + 9] = 0; m[o + 10] = radius; m[o + 11] = 0;
      m[o + 12] = p[i * 3]; m[o + 13] = p[i * 3 + 1]; m[o + 14] = p[i * 3 + 2]; m[o + 15] = 1;
      c[k * 3] = colours[i * 3]; c[k * 3 + 1] = colours[i * 3 + 1]; c[k * 3 + 2] = colours[i * 3 + 2];
    }
    this.mesh.count = drawn;
    this.mesh.visible = drawn > 0 && !this.hidden;
    this.mesh.instanceMatrix.clearUpdateRanges();
    this.mesh.instanceMatrix.addUpdateRange(0, drawn * 16);
    this.mesh.instanceMatrix.needsUpdate = true;
    this.mesh.instanceColor.clearUpdateRanges();
    this.mesh.instanceColor.addUpdateRange(0, drawn * 3);
    this.mesh.instanceColor.needsUpdate = true;
    this.stage.requestRender();
  }

  // Transparency of the particles, so force chains inside the packing can be seen (legacy "T").
  setOpacity(opacity) {
    this.opacity = opacity;
    this.material.opacity = opacity;
    this.material.transparent = opacity < 1;
    this.material.depthWrite = opacity >= 1;
    this.material.needsUpdate = true;
    this.impostors.setOpacity(opacity);
    this.stage.requestRender();
  }

  setVisible(on) {
    this.hidden = !on;
    if (this.mesh) this.mesh.visible = on && this.drawn > 0 && !this.impostors.active;
    this.impostors.setVisible(on);
    this.stage.requestRender();
  }

  // Which renderer draws the current frame: 'instanced' or 'impostor'.
  get technique() {
    return this.impostors.active ? 'impostor' : 'instanced';
  }

  clear() {
    this.drawn = 0;
    if (this.mesh) this.mesh.count = 0;
    this.impostors.hide();
    this.stage.requestRender();
  }
}
