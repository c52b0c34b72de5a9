// The probe: a click on a particle shows its values from the file, a shift-click measures to a
// second one, the pointer's particle is named, and the probed particle is followed by id when the
// next frame lists the particles in another order.
import fs from 'node:fs';
import { test, expect, openViewer, loadFiles, showFrame, settle } from './helpers.js';

// Two frames of four particles (id x y z D vx vy vz nc wx wy wz part), the second in reverse order
// and moved; force chains between 1-2 and 2-3 in the first frame.
const FRAME_1 = [
  [1, -30, 0, 0, 10, 1, 0, 0, 1, 0, 0, 0, 1],
  [2, -10, 0, 0, 8, 0.5, -2, 3, 2, 0.25, -1.5, 4, 7],
  [3, 10, 0, 0, 6, 0, 0, 0, 1, 0, 0, 0, 2],
  [4, 30, 0, 5, 12, 0, 0, -1, 0, 0, 0, 0, 3],
];
const FRAME_2 = FRAME_1.map((p) => [p[0], p[1], p[2], p[3] + 2, ...p.slice(4)]).reverse();

function writeFixture(dir) {
  const frame = (step, time, rows) => ['3DA:', '-50 50 -50 50 -50 50', `${time} 0 0 0`, '0', `${step} ${rows.length} 0`,
                                      ...rows.map((r) => r.join(' '))].join('\n');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, `${frame(10, 0.1, FRAME_1)}\n${frame(20, 0.2, FRAME_2)}\n`);
  fs.writeFileSync(`${dir}/ForceChain_3D.dat`, '3DF: 10 2\n1 0 2 125.5 20.25\n2 1 3 60 5\n3DF: 20 0\n');
  return [`${dir}/ANIMATION_3D.dat`, `${dir}/ForceChain_3D.dat`];
}

// Where particle `id`'s centre is on the page (client pixels), in the current frame.
async function whereIs(page, id) {
  return page.evaluate((id) => {
    const viewer = window.demViewer.viewer;
    const frame = viewer.currentFrame();
    const k = [...frame.ids].indexOf(id);
    const p = frame.positions;
    const v = viewer.stage.camera.position.clone().set(p[k * 3], p[k * 3 + 1], p[k * 3 + 2]).project(viewer.stage.camera);
    const rect = viewer.stage.canvas.getBoundingClientRect();
    return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height };
  }, id);
}

test('click a particle to see its values; shift-click another for the distance', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, writeFixture(testInfo.outputPath('probe')), 2);
  await showFrame(page, 0);
  const probe = page.locator('#probe');
  await expect(probe).toBeHidden();

  const at2 = await whereIs(page, 2);
  await page.mouse.click(at2.x, at2.y);
  await expect(probe).toBeVisible();
  await expect(probe.locator('h3')).toHaveText('Particle 2');
  const field = (name) => probe.locator(`[data-field="${name}"]`);
  await expect(field('position')).toHaveText('-10, 0, 0 (file length unit)');
  await expect(field('velocity')).toHaveText('0.5, -2, 3 (file length unit)/s');
  await expect(field('speed')).toContainText(String(Number(Math.hypot(0.5, 2, 3).toPrecision(4))));
  await expect(field('diameter')).toHaveText('8 (file length unit)');
  await expect(field('spin')).toHaveText('0.25, -1.5, 4 rad/s');
  await expect(field('part')).toHaveText('7');
  await expect(field('contacts')).toHaveText('2');
  await expect(field('chains')).toContainText('2 force chains in this frame');
  await expect(probe.locator('li').first()).toHaveText('to 1: Fn 125.5 N, Ft 20.25 N');
  await expect(probe.locator('li').nth(1)).toHaveText('to 3: Fn 60 N, Ft 5 N');

  // shift-click particle 3: centres 20 apart, radii 4 and 3: a gap of 13
  const at3 = await whereIs(page, 3);
  await page.keyboard.down('Shift');
  await page.mouse.click(at3.x, at3.y);
  await page.keyboard.up('Shift');
  await expect(field('distance')).toHaveText('From particle 2 to 3: centres 20 (file length unit) apart, surfaces 13 (file length unit) (a gap)');

  // the next frame lists the particles in reverse order and 2 higher: still particle 2
  await showFrame(page, 1);
  await expect(probe.locator('h3')).toHaveText('Particle 2');
  await expect(field('position')).toHaveText('-10, 0, 2 (file length unit)');
  await expect(field('chains')).toContainText('0 force chains');

  // the pointer over particle 4 names it
  const at4 = await whereIs(page, 4);
  await page.mouse.move(at4.x, at4.y);
  await expect(page.locator('#hover-readout')).toBeVisible();
  await expect(page.locator('#hover-readout')).toContainText('particle 4');

  // a click on nothing stops probing
  const rect = await page.locator('#view-canvas').boundingBox();
  await page.mouse.click(rect.x + 5, rect.y + rect.height - 5);
  await expect(probe).toBeHidden();
  await settle(page);
});

// Three frames: frame 3 has lost particle 3 (ids 1, 2, 4 left).
function writeVanishing(dir) {
  const row = (id, x, v) => `${id} ${x} 0 0 8 ${v} 0 0 0 0 0 0 ${id}`;
  const frame = (step, rows) => ['3DA:', '-50 50 -50 50 -50 50', `${step / 100} 0 0 0`, '0', `${step} ${rows.length} 0`, ...rows].join('\n');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, [
    frame(10, [row(1, -30, 5), row(2, -10, 0), row(3, 10, 0), row(4, 30, 0)]),
    frame(20, [row(1, -30, 5), row(2, -10, 0), row(3, 10, 0), row(4, 30, 0)]),
    frame(30, [row(1, -45, 1), row(2, -10, 0), row(4, 30, 0)]), ''].join('\n'));
  return `${dir}/ANIMATION_3D.dat`;
}

test('the probe after frames change and files change: the right particle named, nothing stale', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, [writeVanishing(testInfo.outputPath('vanishing'))], 3);
  await showFrame(page, 0);
  const probe = page.locator('#probe');
  const field = (name) => probe.locator(`[data-field="${name}"]`);
  // probe 3, measure to 1; in frame 3 particle 3 is gone: it is the one named missing
  const at3 = await whereIs(page, 3);
  await page.mouse.click(at3.x, at3.y);
  const at1 = await whereIs(page, 1);
  await page.keyboard.down('Shift');
  await page.mouse.click(at1.x, at1.y);
  await page.keyboard.up('Shift');
  await showFrame(page, 2);
  await expect(probe.locator('h3')).toHaveText('Particle 3');
  await expect(field('distance')).toHaveText('Particle 3 is not in this frame');
  // shift-click the probed particle itself: no distance to itself
  await showFrame(page, 0);
  await page.mouse.click(at3.x, at3.y);
  await page.keyboard.down('Shift');
  await page.mouse.click(at3.x, at3.y);
  await page.keyboard.up('Shift');
  await expect(field('distance')).toHaveCount(0);
  // the hover readout follows the frame: particle 1 under the pointer at speed 5, then gone from there
  await page.mouse.move(at1.x, at1.y);
  await expect(page.locator('#hover-readout')).toContainText('particle 1 · speed 5');
  await showFrame(page, 2);
  await expect(page.locator('#hover-readout'), 'particle 1 has moved away from the pointer').toBeHidden();
  // another file: the probe stops
  await loadFiles(page, [writeFixture(testInfo.outputPath('other'))[0]], 2);
  await expect(probe).toBeHidden();
});
