// Boundaries (legacy "Boundary"): the plates and moving mesh triangles written in each animation
// frame, and a fixed triangle mesh (.dat) loaded on its own. One colour and one opacity for all of
// them, as in the legacy viewers; double-sided, since a plate is seen from both sides.

import * as THREE from 'three';

// A fixed mesh's edges are drawn where its faces meet at more than this angle (and along its rim).
const CREASE_DEGREES = 12;

export class BoundaryView {
  constructor(stage) {
    this.stage = stage;
    this.material = new THREE.MeshPhongMaterial({
      color: 0x9aa4b0, side: THREE.DoubleSide, shininess: 10,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1, // edges drawn over faces
    });
    this.edgeMaterial = new THREE.LineBasicMaterial({ color: 0x39424e });
    this.group = new THREE.Group();
    stage.scene.add(this.group);

    this.moving = new THREE.Mesh(new THREE.BufferGeometry(), this.material);
    this.movingEdges = new THREE.LineSegments(new THREE.BufferGeometry(), this.edgeMaterial);
    // A terrain reads as relief with faceted shading and its creases drawn: a smooth, see-through
    // grey surface looked flat (the slope of a 4 km mountain was hard to tell from a plane).
    this.fixedMaterial = this.material.clone();
    this.fixedMaterial.flatShading = true;
    this.fixed = new THREE.Mesh(new THREE.BufferGeometry(), this.fixedMaterial);
    this.fixedEdges = new THREE.LineSegments(new THREE.BufferGeometry(), this.edgeMaterial);
    for (const o of [this.moving, this.movingEdges, this.fixed, this.fixedEdges]) {
      o.frustumCulled = false;
      this.group.add(o);
    }
    this.setOpacity(0.5);
  }

  // The plates (12 floats each: 4 corners) and triangles (9 floats each) of a frame.
  drawFrame(frame) {
    const plates = frame ? frame.plates || new Float32Array(0) : new Float32Array(0);
    const triangles = frame ? frame.triangles || new Float32Array(0) : new Float32Array(0);
    const np = plates.length / 12;
    const nt = triangles.length / 9;
    const faces = new Float32Array((np * 2 + nt) * 9);
    const edges = new Float32Array((np * 4 + nt * 3) * 6);
    let f = 0, e = 0;
    const corner = (src, at, k) => [src[at + k * 3], src[at + k * 3 + 1], src[at + k * 3 + 2]];
    for (let k = 0; k < np; k++) {
      const c = [0, 1, 2, 3].map((q) => corner(plates, k * 12, q));
      for (const q of [0, 1, 2, 0, 2, 3]) { faces.set(c[q], f); f += 3; }
      for (let q = 0; q < 4; q++) { edges.set(c[q], e); edges.set(c[(q + 1) % 4], e + 3); e += 6; }
    }
    for (let k = 0; k < nt; k++) {
      const c = [0, 1, 2].map((q) => corner(triangles, k * 9, q));
      for (const q of [0, 1, 2]) { faces.set(c[q], f); f += 3; }
      for (let q = 0; q < 3; q++) { edges.set(c[q], e); edges.set(c[(q + 1) % 3], e + 3); e += 6; }
    }
    this.replace(this.moving, faces);
    this.movingEdges.geometry.dispose();
    this.movingEdges.geometry = new THREE.BufferGeometry();
    this.movingEdges.geometry.setAttribute('position', new THREE.BufferAttribute(edges, 3));
    this.stage.requestRender();
  }

  replace(mesh, faces) {
    mesh.geometry.dispose();
    mesh.geometry = new THREE.BufferGeometry();
    mesh.geometry.setAttribute('position', new THREE.BufferAttribute(faces, 3));
    if (faces.length) mesh.geometry.computeVertexNormals(); // unindexed: flat normals per face
  }

  // A fixed mesh { vertices, triangles } (or null to remove it).
  setMesh(mesh) {
    this.fixed.geometry.dispose();
    this.fixed.geometry = new THREE.BufferGeometry();
    this.fixedEdges.geometry.dispose();
    this.fixedEdges.geometry = new THREE.BufferGeometry();
    if (mesh) {
      this.fixed.geometry.setAttribute('position', new THREE.BufferAttribute(mesh.vertices, 3));
      this.fixed.geometry.setIndex(new THREE.BufferAttribute(mesh.triangles, 1));
      this.fixed.geometry.computeVertexNormals();
      // creases: edges where the faces meet at more than CREASE_DEGREES, and the mesh's rim
      this.fixedEdges.geometry = new THREE.EdgesGeometry(this.fixed.geometry, CREASE_DEGREES);
    }
    this.stage.requestRender();
  }

  // Bounds of the fixed mesh, for framing the camera when only a mesh is loaded.
  meshBounds() {
    const g = this.fixed.geometry;
    if (!g.attributes.position) return null;
    g.computeBoundingBox();
    return [g.boundingBox.min.toArray(), g.boundingBox.max.toArray()];
  }

  setVisible(on) {
    this.group.visible = on;
    this.stage.requestRender();
  }

  setColour(colour) {
    this.material.color.set(colour);
    this.fixedMaterial.color.set(colour);
    this.stage.requestRender();
  }

  setOpacity(opacity) {
    for (const m of [this.material, this.fixedMaterial]) {
      m.opacity = opacity;
      m.transparent = opacity < 1;
      m.depthWrite = opacity >= 1; // see-through walls must not hide what is behind them
      m.needsUpdate = true;
    }
    this.edgeMaterial.opacity = Math.max(opacity, 0.3);
    this.edgeMaterial.transparent = opacity < 1;
    this.stage.requestRender();
  }
}
