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
    // DEM cases have gravity along -z: z is up, as in the legacy viewers' pictures. Two cameras,
    // perspective and orthographic (setProjection); `camera` is the one in use.
    this.perspectiveCamera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.orthographicCamera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.01, 1000);
    for (const c of [this.perspectiveCamera, this.orthographicCamera]) c.up.set(0, 0, 1);
    this.camera = this.perspectiveCamera;
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
    this.afterRender = []; // drawn over the scene (the axes indicator)

    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    this.renderer.setAnimationLoop(() => this.tick());
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.aspect = w / h;
    this.perspectiveCamera.aspect = this.aspect;
    this.perspectiveCamera.updateProjectionMatrix();
    this.fitOrthographic();
    this.requestRender();
  }

  // The orthographic camera's box: as tall as the perspective camera's view at the target's
  // distance, so that switching keeps the scene's size on the screen.
  fitOrthographic() {
    const o = this.orthographicCamera;
    const distance = this.camera.position.distanceTo(this.controls ? this.controls.target : this.center) || this.size;
    const half = distance * Math.tan(THREE.MathUtils.degToRad(this.perspectiveCamera.fov / 2));
    o.left = -half * (this.aspect || 1);
    o.right = half * (this.aspect || 1);
    o.top = half;
    o.bottom = -half;
    o.near = this.perspectiveCamera.near;
    o.far = this.perspectiveCamera.far;
    o.updateProjectionMatrix();
  }

  get orthographic() {
    return this.camera === this.orthographicCamera;
  }

  // 'perspective' or 'orthographic': the other camera takes the same place, direction and zoom.
  setProjection(kind) {
    const next = kind === 'orthographic' ? this.orthographicCamera : this.perspectiveCamera;
    if (next === this.camera) return;
    const previous = this.camera;
    next.position.copy(previous.position);
    next.quaternion.copy(previous.quaternion);
    next.up.copy(previous.up);
    if (next === this.orthographicCamera) {
      next.zoom = 1;
      this.camera = next;
      this.fitOrthographic();
    } else {
      // the orthographic zoom becomes a distance: the view keeps its size
      const target = this.controls.target;
      const offset = previous.position.clone().sub(target).divideScalar(previous.zoom || 1);
      next.position.copy(target).add(offset);
      this.camera = next;
    }
    this.controls.object = next;
    this.controls.update();
    this.requestRender();
  }

  // Looks along `direction` ([x, y, z], towards the scene) at the scene's centre, from its framing
  // distance; z stays up, except looking along z, where y is up.
  viewAlong(direction) {
    const d = new THREE.Vector3(...direction).normalize();
    const distance = this.camera.position.distanceTo(this.controls.target) || this.size;
    const up = Math.abs(d.z) > 0.99 ? new THREE.Vector3(0, 1, 0) : new THREE.Vector3(0, 0, 1);
    for (const c of [this.perspectiveCamera, this.orthographicCamera]) c.up.copy(up);
    this.camera.position.copy(this.controls.target).addScaledVector(d, -distance);
    this.camera.lookAt(this.controls.target);
    this.controls.update();
    this.fitOrthographic();
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
    for (const hook of this.afterRender) hook(this.camera);
    this.needsRender = false;
  }

  tick() {
    if (this.needsRender || this.continuous > 0) this.renderNow();
  }

  // Frames the camera on a box [min, max] (run bounds): from the front (-y), a little above; a 2D run's plane
  // (x-z, `planar`) straight from the front.
  // `direction` ([x, y, z], optional): look along it instead (keeps the user's view while fitting).
  frame(min, max, { planar = false, direction = null } = {}) {
    const box = new THREE.Box3(new THREE.Vector3(...min), new THREE.Vector3(...max));
    if (box.isEmpty()) return;
    box.getCenter(this.center);
    this.size = Math.max(box.getSize(new THREE.Vector3()).length(), 1e-9);
    const distance = this.size / (2 * Math.tan(THREE.MathUtils.degToRad(this.perspectiveCamera.fov / 2))) * 1.1;
    for (const c of [this.perspectiveCamera, this.orthographicCamera]) {
      c.near = distance / 1000;
      c.far = distance * 100;
      if (!direction) c.up.set(0, 0, 1);
      c.zoom = 1;
    }
    const from = direction ? new THREE.Vector3(...direction).normalize().negate()
      : planar ? new THREE.Vector3(0, -1, 0) : new THREE.Vector3(0.35, -1, 0.45).normalize();
    this.camera.position.copy(this.center).add(from.multiplyScalar(distance));
    this.perspectiveCamera.updateProjectionMatrix();
    this.controls.target.copy(this.center);
    this.controls.update();
    this.fitOrthographic();
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

  // Where the camera looks, as [x, y, z] (a unit vector).
  viewDirection() {
    const d = this.camera.getWorldDirection(new THREE.Vector3());
    return [d.x, d.y, d.z];
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
