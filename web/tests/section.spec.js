// The section along x, y, z or the view's direction: Front hides from the small side, Rear from
// the large side, in thousandths of the run's extent along the axis; the two leave a slice.
import fs from 'node:fs';
import { test, expect, openViewer, loadFiles, setRange, state, canvasShot, keep, expectPicturesDiffer } from './helpers.js';

// One frame: 5 x 5 x 5 particles at 0, 10, 20, 30, 40 on each axis.
function writeGrid(dir) {
  const rows = [];
  let id = 1;
  for (let i = 0; i < 5; i++) for (let j = 0; j < 5; j++) for (let k = 0; k < 5; k++) {
    rows.push(`${id} ${10 * i} ${10 * j} ${10 * k} 6 0 0 0 0 0 0 0 ${id++}`);
  }
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, ['3DA:', '-5 45 -5 45 -5 45', '0 0 0 0', '0', `1 ${rows.length} 0`, ...rows, ''].join('\n'));
  return `${dir}/ANIMATION_3D.dat`;
}

const visible = async (page) => (await state(page)).visible;

for (const axis of ['x', 'z']) {
  test(`a section along ${axis}`, async ({ page }, testInfo) => {
    await openViewer(page);
    await loadFiles(page, [writeGrid(testInfo.outputPath('grid'))], 1);
    expect(await visible(page)).toBe(125);
    const whole = await canvasShot(page);
    await page.locator('#section-axis').selectOption(axis);
    await setRange(page, '#section-front', 500);  // hides below 20: the layers at 0 and 10
    expect(await visible(page)).toBe(75);
    const cut = await canvasShot(page);
    await keep(testInfo, `front-500-along-${axis}`, cut);
    await expectPicturesDiffer(page, whole, cut, `Front at 500 along ${axis}`);
    await setRange(page, '#section-front', 250);
    await setRange(page, '#section-rear', 750);  // a slice: the layers at 10, 20 and 30
    expect(await visible(page)).toBe(75);
    await setRange(page, '#section-front', 400);
    await setRange(page, '#section-rear', 600);  // the layer at 20 alone
    expect(await visible(page)).toBe(25);
    const layer = await page.evaluate((axis) => {
      const v = window.demViewer.viewer;
      const c = { x: 0, y: 1, z: 2 }[axis];
      const p = v.currentFrame().positions;
      return [...v.visible.subarray(0, v.drawnCount)].map((k) => p[k * 3 + c]);
    }, axis);
    expect(new Set(layer), `the slice keeps the particles at ${axis} = 20`).toEqual(new Set([20]));
    await keep(testInfo, `slice-along-${axis}`, await canvasShot(page));
  });
}

test('a section along the view hides the particles nearest the camera first', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, [writeGrid(testInfo.outputPath('grid'))], 1);
  await page.locator('#section-axis').selectOption('view');
  await setRange(page, '#section-front', 500);
  const seen = await page.evaluate(() => {
    const v = window.demViewer.viewer;
    const d = v.stage.camera.getWorldDirection(v.stage.camera.position.clone());
    const p = v.currentFrame().positions;
    const depth = (k) => p[k * 3] * d.x + p[k * 3 + 1] * d.y + p[k * 3 + 2] * d.z;
    const kept = [...v.visible.subarray(0, v.drawnCount)];
    const hidden = [...Array(v.currentFrame().count).keys()].filter((k) => !kept.includes(k));
    return { kept: kept.length, nearestKept: Math.min(...kept.map(depth)), farthestHidden: Math.max(...hidden.map(depth)) };
  });
  expect(seen.kept).toBeGreaterThan(0);
  expect(seen.kept).toBeLessThan(125);
  expect(seen.farthestHidden, 'every hidden particle is nearer the camera than every kept one').toBeLessThan(seen.nearestKept);
  await keep(testInfo, 'front-500-along-the-view', await canvasShot(page));
});
