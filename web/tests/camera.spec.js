// The camera: fit to the particles (a block on a 4 km terrain is a speck when the whole run is
// framed), views along the axes, orthographic, following the particles, the keyboard, and the
// axes indicator.
import fs from 'node:fs';
import { test, expect, openViewer, loadFiles, showFrame, settle, canvasShot, keep, keepPage, pngColourCount, expectPicturesDiffer, countPixels } from './helpers.js';

// A 4 km square terrain (two triangles) and a 20 m block of 27 particles on it at (1000, 500, 10),
// which moves 300 m along x in the second frame.
function writeScene(dir) {
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/terrain.dat`, '4 2\n-2000 -2000 0\n2000 -2000 0\n2000 2000 0\n-2000 2000 0\n1 2 3\n1 3 4\n');
  const frame = (step, dx) => {
    const rows = [];
    let id = 1;
    for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) for (let k = 0; k < 3; k++) {
      rows.push(`${id} ${1000 + dx + 8 * i} ${500 + 8 * j} ${10 + 8 * k} 8 0 0 0 0 0 0 0 ${id++}`);
    }
    return ['3DA:', '-2000 2000 -2000 2000 0 100', `${step / 100} 0 0 0`, '0', `${step} 27 0`, ...rows].join('\n');
  };
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, `${frame(100, 0)}\n${frame(200, 300)}\n`);
  return [`${dir}/ANIMATION_3D.dat`, `${dir}/terrain.dat`];
}

// The particles' extent on the canvas as a share of its width and height.
const particlesOnScreen = (page) => page.evaluate(() => {
  const v = window.demViewer.viewer;
  const frame = v.currentFrame();
  const cam = v.stage.camera;
  let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
  for (let k = 0; k < frame.count; k++) {
    const p = cam.position.clone().set(frame.positions[k * 3], frame.positions[k * 3 + 1], frame.positions[k * 3 + 2]).project(cam);
    x0 = Math.min(x0, p.x); x1 = Math.max(x1, p.x); y0 = Math.min(y0, p.y); y1 = Math.max(y1, p.y);
  }
  return { width: (x1 - x0) / 2, height: (y1 - y0) / 2, inside: x0 > -1 && x1 < 1 && y0 > -1 && y1 < 1 };
});
const lookDirection = (page) => page.evaluate(() => {
  const cam = window.demViewer.viewer.stage.camera;
  const d = cam.getWorldDirection(cam.position.clone());
  return [d.x, d.y, d.z].map((c) => Math.round(c * 1000) / 1000 + 0);  // + 0: -0 is 0
});

test('fit to the particles, reset, and views along the axes', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, writeScene(testInfo.outputPath('scene')), 2);
  await showFrame(page, 0);
  const speck = await particlesOnScreen(page);
  expect(Math.max(speck.width, speck.height), 'framing the terrain, the block is a speck').toBeLessThan(0.05);
  await keep(testInfo, 'whole-run', await canvasShot(page));
  await page.locator('#camera-fit').click();
  await settle(page);
  const fitted = await particlesOnScreen(page);
  expect(fitted.inside, 'the block fits in the view').toBe(true);
  expect(Math.max(fitted.width, fitted.height), 'and fills it').toBeGreaterThan(0.4);
  await keep(testInfo, 'fit-particles', await canvasShot(page));
  for (const [button, direction] of [['+x', [1, 0, 0]], ['-y', [0, -1, 0]], ['-z', [0, 0, -1]], ['+z', [0, 0, 1]]]) {
    await page.locator(`[data-camera="${button}"]`).click();
    expect(await lookDirection(page), `looking along ${button}`).toEqual(direction);
    expect((await particlesOnScreen(page)).inside, `the block stays in view along ${button}`).toBe(true);
  }
  await page.locator('#camera-reset').click();
  expect(Math.max((await particlesOnScreen(page)).width, (await particlesOnScreen(page)).height)).toBeLessThan(0.05);
});

test('orthographic keeps the scene, follows the particles, and the keyboard moves the view', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, writeScene(testInfo.outputPath('scene')), 2);
  await showFrame(page, 0);
  await page.locator('#camera-fit').click();
  const perspective = await canvasShot(page);
  const before = await particlesOnScreen(page);
  await page.locator('#camera-orthographic').check();
  expect(await page.evaluate(() => window.demViewer.viewer.stage.camera.isOrthographicCamera)).toBe(true);
  const after = await particlesOnScreen(page);
  expect(after.inside).toBe(true);
  expect(Math.abs(after.width - before.width) / before.width, 'about the same size on the screen').toBeLessThan(0.3);
  const ortho = await canvasShot(page);
  await keep(testInfo, 'orthographic', ortho);
  expect((await pngColourCount(page, ortho)).colours, 'particles drawn').toBeGreaterThan(8);
  await expectPicturesDiffer(page, perspective, ortho, 'perspective and orthographic');

  // follow: the block moves 300 m along x in frame 2, the camera's target with it
  await page.locator('#camera-follow').check();
  const target = () => page.evaluate(() => window.demViewer.viewer.stage.controls.target.toArray());
  const t0 = await target();
  await showFrame(page, 1);
  const t1 = await target();
  expect(t1[0] - t0[0]).toBeCloseTo(300, 3);
  expect((await particlesOnScreen(page)).inside, 'the moved block is still in view').toBe(true);
  await page.locator('#camera-follow').uncheck();

  // keys: x looks along +x, Shift+z along -z, arrows turn, + zooms in, o back to perspective
  await page.locator('#view-canvas').click({ position: { x: 5, y: 5 } });
  await page.keyboard.press('x');
  expect(await lookDirection(page)).toEqual([1, 0, 0]);
  await page.keyboard.press('Shift+Z');
  expect(await lookDirection(page)).toEqual([0, 0, -1]);
  await page.keyboard.press('y');
  await page.keyboard.press('ArrowLeft');
  const turned = await lookDirection(page);
  expect(Math.abs(turned[0]), 'ArrowLeft turns the view').toBeGreaterThan(0.1);
  await page.keyboard.press('o');
  expect(await page.evaluate(() => window.demViewer.viewer.stage.camera.isPerspectiveCamera)).toBe(true);
  const distance = () => page.evaluate(() => { const s = window.demViewer.viewer.stage; return s.camera.position.distanceTo(s.controls.target); });
  const d0 = await distance();
  await page.keyboard.press('+');
  expect(await distance()).toBeCloseTo(d0 / 1.2, 3);
  await page.keyboard.press('f');
  expect((await particlesOnScreen(page)).inside).toBe(true);
});

test('the axes indicator in the corner turns with the view', async ({ page }, testInfo) => {
  await openViewer(page, { axes: true });
  await loadFiles(page, writeScene(testInfo.outputPath('scene')), 2);
  const corner = async () => {
    const shot = await canvasShot(page);
    return countPixels(page, shot, {
      red: '(r, g, b) => r > 150 && g < 90 && b < 90',
      green: '(r, g, b) => g > 120 && r < 90 && b < 90',
      blue: '(r, g, b) => b > 150 && r < 90 && g < 160',
    }, { x: -110, y: -110, width: 110, height: 110 });
  };
  const start = await corner();
  expect(start.red > 20 && start.green > 20 && start.blue > 20, `x, y and z drawn: ${JSON.stringify(start)}`).toBe(true);
  await page.locator('[data-camera="+x"]').click();  // looking along x: the x arrow points away, nearly a dot
  const alongX = await corner();
  expect(alongX.red, `the x arrow seen end-on (${JSON.stringify(alongX)})`).toBeLessThan(start.red);
  await page.locator('#show-axes').uncheck();
  const off = await corner();
  expect(off.red + off.green + off.blue, 'switched off').toBe(0);
  await keepPage(page, testInfo, 'axes');
});

test('the keys work after a click on a checkbox or a button of the panel', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, writeScene(testInfo.outputPath('scene')), 2);
  await page.locator('#camera-orthographic').click();
  expect(await page.evaluate(() => window.demViewer.viewer.stage.camera.isOrthographicCamera)).toBe(true);
  await page.keyboard.press('o');
  expect(await page.evaluate(() => window.demViewer.viewer.stage.camera.isPerspectiveCamera), 'o after clicking the checkbox').toBe(true);
  await page.locator('#show-force-chains').click();
  await page.keyboard.press('y');
  expect(await lookDirection(page)).toEqual([0, 1, 0]);
});
