// Force chains: one thin cylinder per contact between the two particle centres, coloured blue to
// red and made thicker with |Fn| (legacy "force chain": colour and width both tell the force).
// Cylinders are instanced: a single draw call for hundreds of thousands of chains, and their width
// is in scene units, so it keeps its proportion to the particles at any zoom.

import * as THREE from 'three';
import { mapLinear } from './colours.js';

export class ForceChainView {
  constructor(stage) {
    this.stage = stage;
    this.capacity = 0;
    this.mesh = null;
    // along +y, height 1, closed: an open end showed the tube's inside as notches and holes
    this.geometry = new THREE.CylinderGeometry(1, 1, 1, 8, 1, false);
    this.material = new THREE.MeshPhongMaterial({ color: 0xffffff, shininess: 20 });
    this.drawn = 0;
    this.unknown = 0; // chains of the frame naming a particle the frame does not have
    this.fnMax = 0; // the top of the colour scale: the strongest chain of the frame that can be drawn
    this.firstUnknownId = 0; // the first such particle's id (1-based, as in the files)
  }

  ensure(count) {
    if (this.mesh && count <= this.capacity) return;
    if (this.mesh) {
      this.stage.scene.remove(this.mesh);
      this.mesh.dispose();
    }
    this.capacity = Math.max(count, 1024);
    this.mesh = new THREE.InstancedMesh(this.geometry, this.material, this.capacity);
    this.mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    this.mesh.instanceColor = new THREE.InstancedBufferAttribute(new Float32Array(this.capacity * 3), 3);
    this.mesh.frustumCulled = false;
    this.stage.scene.add(this.mesh);
  }

  // chains: { i, j (0-based ids), fn } of the frame; indexOf(id0) gives the particle's index in the
  // frame or -1; shown: Uint8Array, 1 for the particles left visible by the section (a chain is
  // drawn when both its particles are); baseRadius: the radius of the strongest chain at thickness
  // 1. The colour scale's top (`fnMax`, kept for the legend) is the strongest chain whose particles
  // the frame has: one naming a missing particle is neither drawn nor counted.
  draw(frame, chains, indexOf, shown, baseRadius) {
    const count = chains ? chains.count ?? chains.i.length : 0; // live frames may carry no count
    if (!count) {
      this.hide();
      return;
    }
    this.ensure(count);
    const m = this.mesh.instanceMatrix.array;
    const col = this.mesh.instanceColor.array;
    const p = frame.positions;
    let fnMax = 0;
    for (let k = 0; k < count; k++) {
      if (indexOf(chains.i[k]) >= 0 && indexOf(chains.j[k]) >= 0) fnMax = Math.max(fnMax, Math.abs(chains.fn[k]));
    }
    this.fnMax = fnMax;
    const scale = fnMax > 0 ? 1 / fnMax : 0;
    let n = 0;
    let unknown = 0;
    for (let k = 0; k < count; k++) {
      const a = indexOf(chains.i[k]);
      const b = indexOf(chains.j[k]);
      if (a < 0 || b < 0) {
        if (!unknown++) this.firstUnknownId = (a < 0 ? chains.i[k] : chains.j[k]) + 1;
        continue;
      }
      if (!shown[a] || !shown[b]) continue;
      const ax = p[a * 3], ay = p[a * 3 + 1], az = p[a * 3 + 2];
      const dx = p[b * 3] - ax, dy = p[b * 3 + 1] - ay, dz = p[b * 3 + 2] - az;
      const length = Math.sqrt(dx * dx + dy * dy + dz * dz);
      if (length === 0) continue;
      const t = Math.abs(chains.fn[k]) * scale;
      const radius = baseRadius * (0.15 + 0.85 * Math.min(t, 1));
      // e1, e2: unit vectors across the chain (e1 from the cross product with the axis the chain is
      // least along, so it never degenerates). (e1, u, e2) must be right-handed, e2 = e1 x u: a
      // left-handed frame mirrors the cylinder, turning its faces inside out, and the near half is
      // culled.
      const ux = dx / length, uy = dy / length, uz = dz / length;
      let e1x, e1y, e1z;
      if (Math.abs(ux) < 0.9) { e1x = 0; e1y = uz; e1z = -uy; } else { e1x = -uz; e1y = 0; e1z = ux; }
      const e1 = Math.sqrt(e1x * e1x + e1y * e1y + e1z * e1z);
      e1x /= e1; e1y /= e1; e1z /= e1;
      const e2x = e1y * uz - e1z * uy, e2y = e1z * ux - e1x * uz, e2z = e1x * uy - e1y * ux;
      const o = n * 16;
      // columns: x across (radius), y along (the full chain), z across (radius), then the midpoint
      m[o] = e1x * radius; m[o + 1] = e1y * radius; m[o + 2] = e1z * radius; m[o + 3] = 0;
      m[o + 4] = dx; m[o + 5] = dy; m[o + 6] = dz; m[o + 7] = 0;
      m[o + 8] = e2x * radius; m[o + 9] = e2y * radius; m[o + 10] = e2z * radius; m[o + 11] = 0;
      m[o + 12] = ax + dx / 2; m[o + 13] = ay + dy / 2; m[o + 14] = az + dz / 2; m[o + 15] = 1;
      mapLinear(t, col, n * 3);
      n += 1;
    }
    this.drawn = n;
    this.unknown = unknown;
    this.mesh.count = n;
    this.mesh.visible = n > 0;
    this.mesh.instanceMatrix.needsUpdate = true;
    this.mesh.instanceColor.needsUpdate = true;
    this.stage.requestRender();
  }

  hide() {
    this.drawn = 0;
    this.unknown = 0;
    if (this.mesh) {
      this.mesh.count = 0;
      this.mesh.visible = false;
    }
    this.stage.requestRender();
  }
}
