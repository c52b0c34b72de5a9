// The 3D stage: renderer, camera, orbit controls and lights. Draws on demand (requestRender) rather
// than every animation frame, so an idle page costs nothing on a shared CPU-rendered machine;
// continuous drawing is turned on only while a video is recorded.

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

export class Stage {
  constructor(container) {
    this.container = container;
    // preserveDrawingBuffer: the canvas keeps its last picture, so "save picture" and toBlob work
    // at any moment, not only right after a draw.
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.canvas = this.renderer.domElement;
    this.canvas.id = 'view-canvas';
    container.appendChild(this.canvas);

    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color('#ffffff');
    // DEM cases have gravity along -z: z is up, as in the legacy viewers' pictures.
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.enableDamping = false; // damping would need continuous drawing
    this.controls.addEventListener('change', () => this.requestRender());

    // A soft ambient term so that the side away from the light is still readable, plus the
    // movable light of the legacy "light position X / Y / Z".
    const sky = new THREE.HemisphereLight(0xffffff, 0x444444, 0.9);
    sky.position.set(0, 0, 1); // sky above along z
    this.scene.add(sky);
    this.light = new THREE.DirectionalLight(0xffffff, 2.2);
    this.scene.add(this.light, this.light.target);

    this.center = new THREE.Vector3();
    this.size = 1;
    this.lightAxis = 'y';
    this.needsRender = true;
    this.continuous = 0; // users of continuous drawing (recording)
    this.beforeRender = [];

    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    this.renderer.setAnimationLoop(() => this.tick());
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  requestRender() {
    this.needsRender = true;
  }

  // Draws now (for a picture taken right away).
  renderNow() {
    this.camera.updateMatrixWorld(); // the hooks read the view matrix before render() refreshes it
    for (const hook of this.beforeRender) hook(this.camera);
    this.renderer.render(this.scene, this.camera);
    this.needsRender = false;
  }

  tick() {
    if (this.needsRender || this.continuous > 0) this.renderNow();
  }

  // Frames the camera on a box [min, max] (run bounds): from the front (-y), a little above; a 2D run's plane
  // (x-z, `planar`) straight from the front.
  frame(min, max, { planar = false } = {}) {
    const box = new THREE.Box3(new THREE.Vector3(...min), new THREE.Vector3(...max));
    if (box.isEmpty()) return;
    box.getCenter(this.center);
    this.size = Math.max(box.getSize(new THREE.Vector3()).length(), 1e-9);
    const distance = this.size / (2 * Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2))) * 1.1;
    this.camera.near = distance / 1000;
    this.camera.far = distance * 100;
    const from = planar ? new THREE.Vector3(0, -1, 0) : new THREE.Vector3(0.35, -1, 0.45).normalize();
    this.camera.position.copy(this.center).add(from.multiplyScalar(distance));
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(this.center);
    this.controls.update();
    this.placeLight(this.lightAxis);
  }

  // Moves the light onto an axis through the scene's centre (legacy "light position X, Y, Z"). The
  // light sits on the axis's negative side for y (the side the camera starts on), positive for x, z.
  placeLight(axis) {
    this.lightAxis = axis;
    const offset = { x: [1, 0, 0], y: [0, -1, 0], z: [0, 0, 1] }[axis];
    this.light.position.copy(this.center).add(new THREE.Vector3(...offset).multiplyScalar(this.size * 2));
    this.light.target.position.copy(this.center);
    this.light.target.updateMatrixWorld();
    this.requestRender();
  }

  // The light's direction in view space (towards the light), for the sphere impostor shader.
  lightDirectionInView(out) {
    out.copy(this.light.position).sub(this.light.target.position).normalize();
    return out.transformDirection(this.camera.matrixWorldInverse);
  }

  setBackground(colour) {
    this.scene.background.set(colour);
    this.requestRender();
  }
}
