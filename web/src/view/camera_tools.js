// The camera's controls beyond the mouse: fit to the particles, reset to the whole run, views along
// +-x, +-y, +-z, perspective or orthographic, following the particles' centre as they move, an axes
// indicator in the view's corner (in saved pictures too), and the keyboard:
//   f fit to the particles, r reset, x / y / z look along +x / +y / +z (with Shift: along -x...),
//   o orthographic on or off, arrows turn the view round its centre, + and - zoom.

import * as THREE from 'three';

const $ = (id) => document.getElementById(id);
const TURN = Math.PI / 24; // an arrow key turns the view by 7.5 degrees
const ZOOM = 1.2; // + and - bring the camera 1.2 times closer or farther
const INDICATOR = 100; // px: the axes indicator's square

export function wireCamera(viewer) {
  const stage = viewer.stage;
  const view = (d) => () => stage.viewAlong(d);
  const actions = {
    fit: () => viewer.fitParticles(),
    reset: () => viewer.frameCamera(),
    '+x': view([1, 0, 0]), '-x': view([-1, 0, 0]),
    '+y': view([0, 1, 0]), '-y': view([0, -1, 0]),
    '+z': view([0, 0, 1]), '-z': view([0, 0, -1]),
  };
  for (const button of document.querySelectorAll('[data-camera]')) {
    button.addEventListener('click', () => actions[button.dataset.camera]());
  }
  const ortho = $('camera-orthographic');
  ortho.addEventListener('change', () => stage.setProjection(ortho.checked ? 'orthographic' : 'perspective'));

  // Following: the camera keeps its offset from the particles' centre as they move.
  let followed = null;
  const follow = $('camera-follow');
  follow.addEventListener('change', () => { followed = follow.checked ? viewer.particlesCentre() : null; });
  viewer.onChange(() => {
    if (!follow.checked) return;
    const centre = viewer.particlesCentre();
    if (!centre) return;
    if (followed) {
      const shift = new THREE.Vector3(centre[0] - followed[0], centre[1] - followed[1], centre[2] - followed[2]);
      if (shift.lengthSq() > 0) {
        stage.camera.position.add(shift);
        stage.controls.target.add(shift);
        stage.controls.update();
        stage.requestRender();
      }
    }
    followed = centre;
  });

  document.addEventListener('keydown', (event) => {
    if (event.ctrlKey || event.metaKey || event.altKey) return;
    const t = event.target;
    // not while typing or moving a slider (its arrows); a checkbox or button clicked keeps the focus
    const typing = t && (t.isContentEditable || ['SELECT', 'TEXTAREA'].includes(t.tagName) ||
                         (t.tagName === 'INPUT' && !['checkbox', 'radio', 'button', 'submit', 'file', 'color'].includes(t.type)));
    if (typing) return;
    const key = event.key.toLowerCase();
    let handled = true;
    if (key === 'f') actions.fit();
    else if (key === 'r') actions.reset();
    else if (key === 'x' || key === 'y' || key === 'z') actions[`${event.shiftKey ? '-' : '+'}${key}`]();
    else if (key === 'o') { ortho.checked = !ortho.checked; ortho.dispatchEvent(new Event('change')); }
    else if (event.key.startsWith('Arrow')) turn(stage, event.key);
    else if (key === '+' || key === '=') zoom(stage, 1 / ZOOM);
    else if (key === '-' || key === '_') zoom(stage, ZOOM);
    else handled = false;
    if (handled) event.preventDefault();
  });

  addAxesIndicator(stage, () => Boolean(viewer.run && (viewer.run.frames.length || viewer.run.mesh)));
}

// Turns the camera round the target: left and right about the up axis, up and down about the
// camera's right-hand axis.
function turn(stage, key) {
  const camera = stage.camera;
  const target = stage.controls.target;
  const offset = camera.position.clone().sub(target);
  if (key === 'ArrowLeft' || key === 'ArrowRight') {
    offset.applyAxisAngle(camera.up.clone().normalize(), key === 'ArrowLeft' ? -TURN : TURN);
  } else {
    const right = new THREE.Vector3().crossVectors(offset, camera.up).normalize();
    const turned = offset.clone().applyAxisAngle(right, key === 'ArrowUp' ? -TURN : TURN);
    // not over the pole: the view would flip
    if (Math.abs(turned.clone().normalize().dot(camera.up.clone().normalize())) < 0.995) offset.copy(turned);
  }
  camera.position.copy(target).add(offset);
  camera.lookAt(target);
  stage.controls.update();
  stage.requestRender();
}

function zoom(stage, factor) {
  const camera = stage.camera;
  if (stage.orthographic) {
    camera.zoom /= factor;
    camera.updateProjectionMatrix();
  } else {
    const target = stage.controls.target;
    const offset = camera.position.clone().sub(target).multiplyScalar(factor);
    camera.position.copy(target).add(offset);
  }
  stage.controls.update();
  stage.requestRender();
}

// x (red), y (green) and z (blue) arrows in the view's lower right corner, turned as the camera
// (#show-axes).
function addAxesIndicator(stage, somethingShown) {
  const scene = new THREE.Scene();
  const camera = new THREE.OrthographicCamera(-1.45, 1.45, 1.45, -1.45, 0.1, 10);
  const colours = { x: 0xd62728, y: 0x2ca02c, z: 0x1f77b4 };
  for (const [axis, colour] of Object.entries(colours)) {
    const direction = new THREE.Vector3(axis === 'x' ? 1 : 0, axis === 'y' ? 1 : 0, axis === 'z' ? 1 : 0);
    scene.add(new THREE.ArrowHelper(direction, new THREE.Vector3(), 1, colour, 0.4, 0.22));
    const label = textSprite(axis, colour);
    label.position.copy(direction).multiplyScalar(1.22);
    scene.add(label);
  }
  const shown = $('show-axes');
  shown.addEventListener('change', () => stage.requestRender());
  stage.afterRender.push((main) => {
    if (!shown.checked || !somethingShown()) return;
    const r = stage.renderer;
    const size = r.getSize(new THREE.Vector2());
    const s = Math.min(INDICATOR, size.x / 4, size.y / 4);
    camera.position.set(0, 0, 4).applyQuaternion(main.quaternion);
    camera.quaternion.copy(main.quaternion);
    camera.updateMatrixWorld();
    const clear = r.autoClear;
    r.autoClear = false;
    r.clearDepth();
    r.setScissorTest(true);
    r.setScissor(size.x - s - 4, 4, s, s);
    r.setViewport(size.x - s - 4, 4, s, s);
    r.render(scene, camera);
    r.setScissorTest(false);
    r.setViewport(0, 0, size.x, size.y);
    r.autoClear = clear;
  });
}

function textSprite(text, colour) {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = 64;
  const g = canvas.getContext('2d');
  g.font = 'bold 44px sans-serif';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillStyle = `#${colour.toString(16).padStart(6, '0')}`;
  g.fillText(text, 32, 34);
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), depthTest: false }));
  sprite.scale.setScalar(0.55);
  return sprite;
}
