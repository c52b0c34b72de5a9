// Colour control: the map (legacy blue to red, viridis, grey), the range (the run, the frame, by
// hand), any quantity of the files (height, displacement, spin, contacts, fragment size), and the
// legend in the saved picture.
import fs from 'node:fs';
import { test, expect, openViewer, loadFiles, showFrame, settle, canvasShot, keep, expectPicturesDiffer, countPixels } from './helpers.js';

// Two frames of 5 particles in a column (z 0..40 in frame 1, 0..80 in frame 2, each moved up by
// its id's share); spin |w| = id, contacts = id - 1, parts: 1,1,1,2,2.
function writeColumn(dir) {
  const frame = (step, stretch) => {
    const rows = [1, 2, 3, 4, 5].map((id) =>
      `${id} 0 0 ${(id - 1) * 10 * stretch} 8 0 0 ${id} ${id - 1} ${id} 0 0 ${id <= 3 ? 1 : 2}`);
    return ['3DA:', '-10 10 -10 10 -10 90', `${step / 100} 0 0 0`, '0', `${step} 5 0`, ...rows].join('\n');
  };
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, `${frame(100, 1)}\n${frame(200, 2)}\n`);
  return `${dir}/ANIMATION_3D.dat`;
}

const srgbToLinear = (c) => (c < 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);
const hex = (h) => [1, 3, 5].map((i) => srgbToLinear(parseInt(h.slice(i, i + 2), 16) / 255));
// The colour the viewer gave particle k (linear RGB).
const colourOf = (page, k) => page.evaluate((k) => [...window.demViewer.viewer.colours.slice(k * 3, k * 3 + 3)], k);
const near = (a, b) => a.every((v, i) => Math.abs(v - b[i]) < 0.01);
const range = (page) => page.evaluate(() => window.demViewer.viewer.colourRange());

test('the map, the range and the quantity change the colours', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, [writeColumn(testInfo.outputPath('column'))], 2);
  await showFrame(page, 0);
  await page.locator('#colour-mode').selectOption('height');
  await expect(page.locator('#colour-label')).toHaveText('Height (z)');
  expect(await range(page), 'the run\'s range of z').toEqual([0, 80]);
  const legacy = await canvasShot(page);
  // viridis: the top of the range is #fde725, the bottom #440154
  await page.locator('#colour-map').selectOption('viridis');
  await showFrame(page, 1);
  expect(near(await colourOf(page, 4), hex('#fde725')), 'z = 80 at the top of viridis').toBe(true);
  expect(near(await colourOf(page, 0), hex('#440154')), 'z = 0 at its bottom').toBe(true);
  await showFrame(page, 0);
  const viridis = await canvasShot(page);
  await keep(testInfo, 'viridis', viridis);
  await expectPicturesDiffer(page, legacy, viridis, 'legacy and viridis');
  expect(await page.locator('#colour-bar').evaluate((el) => getComputedStyle(el).backgroundImage)).toContain('rgb(68, 1, 84)');

  // this frame's range: 0..40 in frame 1, so its top particle is at the top of the map
  await page.locator('#colour-range').selectOption('frame');
  expect(await range(page)).toEqual([0, 40]);
  expect(near(await colourOf(page, 4), hex('#fde725'))).toBe(true);
  const frameRange = await canvasShot(page);
  await expectPicturesDiffer(page, viridis, frameRange, 'the run\'s and the frame\'s range');

  // by hand: 0..20, starting from the range in use
  await page.locator('#colour-range').selectOption('manual');
  await expect(page.locator('#colour-range-inputs')).toBeVisible();
  await expect(page.locator('#colour-range-max')).toHaveValue('40');
  await page.locator('#colour-range-max').fill('20');
  await page.locator('#colour-range-max').dispatchEvent('change');
  expect(await range(page)).toEqual([0, 20]);
  expect(near(await colourOf(page, 2), hex('#fde725')), 'z = 20: the top').toBe(true);
  expect(near(await colourOf(page, 4), hex('#fde725')), 'z = 40: past the top, clamped').toBe(true);
  expect(near(await colourOf(page, 1), hex('#21918c')), 'z = 10: the middle').toBe(true);
  // a reversed range is refused, the one before kept
  await page.locator('#colour-range-min').fill('30');
  await page.locator('#colour-range-min').dispatchEvent('change');
  expect(await range(page)).toEqual([0, 20]);
  expect(await page.locator('#colour-range-min').evaluate((el) => el.validationMessage)).toContain('From < to');
  await keep(testInfo, 'manual-range', await canvasShot(page));

  // other quantities over the run's range
  await page.locator('#colour-range').selectOption('run');
  await page.locator('#colour-map').selectOption('grey');
  for (const [mode, expected] of [['spin', [1, 5]], ['contacts', [0, 4]], ['displacement', [0, 40]], ['fragmentSize', [2, 3]]]) {
    await page.locator('#colour-mode').selectOption(mode);
    expect(await range(page), `${mode}: the run's range`).toEqual(expected);
  }
  await showFrame(page, 1);
  // displacement from frame 1: particle 5 moved 40, the most: the top of the grey map
  await page.locator('#colour-mode').selectOption('displacement');
  expect(near(await colourOf(page, 4), [0.92, 0.92, 0.92].map(srgbToLinear))).toBe(true);
});

test('the saved picture carries the legend and what is shown', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, [writeColumn(testInfo.outputPath('column'))], 2);
  await page.locator('#colour-map').selectOption('viridis');
  await settle(page);
  const [download] = await Promise.all([page.waitForEvent('download'), page.locator('#save-picture').click()]);
  const png = fs.readFileSync(await download.path());
  fs.writeFileSync(testInfo.outputPath('dem-view.png'), png);
  await keep(testInfo, 'saved-with-legend', png);
  // the lower left corner, where the bar is: viridis' dark purple and its yellow; the caption's text at the top
  const found = {
    ...(await countPixels(page, png, {
      purple: '(r, g, b) => Math.abs(r - 0x44) < 12 && g < 20 && Math.abs(b - 0x54) < 14',
      yellow: '(r, g, b) => r > 230 && g > 210 && b < 80',
    }, { x: 0, y: -80, width: 300, height: 80 })),
    ...(await countPixels(page, png, { text: '(r, g, b) => r < 100 && g < 100 && b < 100' }, { x: 0, y: 0, width: 400, height: 30 })),
  };
  expect(found.purple, `the bar's purple end (${JSON.stringify(found)})`).toBeGreaterThan(10);
  expect(found.yellow, 'its yellow end').toBeGreaterThan(10);
  expect(found.text, 'the caption at the top').toBeGreaterThan(30);
});

test('Part, as the legacy viewer: the large masses red, the small ones green, the largest listed', async ({ page }, testInfo) => {
  // parts 1 (six particles), 2 (three) and 3 (one), and one particle with no part (0)
  const parts = [1, 1, 1, 1, 1, 1, 2, 2, 2, 3, 0];
  const rows = parts.map((part, k) => `${k + 1} ${10 * k} 0 0 6 0 0 0 0 0 0 0 ${part}`);
  const dir = testInfo.outputPath('parts');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, ['3DA:', '-5 105 -5 5 -5 5', '0 0 0 0', '0', `1 ${rows.length} 0`, ...rows, ''].join('\n'));
  await openViewer(page);
  await loadFiles(page, [`${dir}/ANIMATION_3D.dat`], 1);
  await page.locator('#colour-mode').selectOption('part');
  await expect(page.locator('#colour-label')).toContainText('green (small) to red (large)');
  expect(await range(page), 'one sphere to the largest part').toEqual([1, 6]);
  const red = [0.84, 0.1, 0.1].map(srgbToLinear), green = [0.13, 0.63, 0.17].map(srgbToLinear);
  expect(near(await colourOf(page, 0), red), 'part 1, the largest: red').toBe(true);
  expect(near(await colourOf(page, 9), green), 'part 3, one particle: green').toBe(true);
  expect(near(await colourOf(page, 10), [0.6, 0.6, 0.6].map(srgbToLinear)), 'no part: grey').toBe(true);
  const items = page.locator('#part-legend li');
  await expect(items).toHaveCount(3);
  await expect(items.nth(0)).toHaveText('part 1: 6 particles');
  await expect(items.nth(1)).toHaveText('part 2: 3 particles');
  await expect(items.nth(2)).toHaveText('part 3: 1 particle');
  expect(await page.locator('#colour-bar').evaluate((el) => getComputedStyle(el).backgroundImage)).toContain('rgb(214, 26, 26)');
  await keep(testInfo, 'part-by-size', await canvasShot(page));
});

test('displacement names its reference frame, fragment size leaves out particles of no part, a reversed range is said', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, [writeColumn(testInfo.outputPath('column'))], 2);
  await page.locator('#colour-mode').selectOption('displacement');
  await expect(page.locator('#colour-label')).toContainText('since step 100');
  // parts 1, 1, 1, 2, 2 in the column; a file whose particles have no part (0) has no fragments
  const dir = testInfo.outputPath('no-parts');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, ['3DA:', '-5 5 -5 5 -5 5', '0 0 0 0', '0', '1 3 0',
    '1 0 0 0 2 0 0 0 0 0 0 0 0', '2 3 0 0 2 0 0 0 0 0 0 0 0', '3 6 0 0 2 0 0 0 0 0 0 0 4', ''].join('\n'));
  await loadFiles(page, [`${dir}/ANIMATION_3D.dat`], 1);
  await page.locator('#colour-mode').selectOption('fragmentSize');
  expect(await range(page), 'only particle 3 has a part: one fragment of one').toEqual([1, 1]);
  // a reversed range by hand is refused out loud
  await page.locator('#colour-mode').selectOption('speed');
  await page.locator('#colour-range').selectOption('manual');
  await expect(page.locator('#colour-range-max'), 'an empty range seeds a usable one').not.toHaveValue('0');
  await page.locator('#colour-range-min').fill('0.9');
  await page.locator('#colour-range-max').fill('0.2');
  await page.locator('#colour-range-max').dispatchEvent('change');
  await expect(page.locator('#message')).toContainText('From < to');
  await expect(page.locator('#message')).toHaveClass(/error/);
});
