// The charts' lines (src/live/charts.js) drawn from known series.
import fs from 'node:fs';
import { test, expect, openViewer, countPixels } from './helpers.js';

test('a count that jumps is drawn as a step, not a slope from the start', async ({ page }, testInfo) => {
  await openViewer(page);
  // 18 bonds broken in tension at t = 0.5 s, the run ending at 1 s (Bond_Breaks.dat: time i j mode)
  const rows = Array.from({ length: 18 }, (_, k) => `0.5 ${k + 1} ${k + 2} 1`).join('\n') + '\n';
  const series = await page.evaluate((text) => {
    const charts = window.demLive.charts;
    charts.setBondBreaks(text, 1);
    return charts.chart('broken-bonds').series.map((s) => ({ x: s.x, y: s.y }));
  }, rows);
  const total = series[0];
  expect(total.y[0], 'nothing broken at the start').toBe(0);
  expect(total.x[1], 'still none just before the breaks').toBe(0.5);
  expect(total.y[1]).toBe(0);
  expect(total.y[total.y.length - 1]).toBe(18);
  for (let k = 1; k < total.x.length; k++) expect(total.x[k] >= total.x[k - 1], 'time never goes back').toBe(true);

  const canvas = page.locator('canvas[data-chart="broken-bonds"]');
  await expect(canvas).toBeVisible();
  await page.waitForTimeout(300);
  const png = await canvas.screenshot();
  await testInfo.attach('broken-bonds.png', { body: png, contentType: 'image/png' });
  const box = await canvas.boundingBox();
  // the plot's first half in time, above its bottom sixth: a slope from (0, 0) to (0.5, 18) crosses it
  const plotLeft = 64, plotRight = box.width - 10;
  const region = { x: Math.round(plotLeft + 0.1 * (plotRight - plotLeft)), y: 40, width: Math.round(0.3 * (plotRight - plotLeft)), height: Math.round(box.height - 32 - 40 - 20) };
  const counts = await countPixels(page, png, { line: '(r, g, b) => Math.abs(r - 0x1f) + Math.abs(g - 0x77) + Math.abs(b - 0xb4) < 90 || Math.abs(r - 0xd6) + Math.abs(g - 0x27) + Math.abs(b - 0x28) < 90' }, region);
  expect(counts.line, 'line pixels between the start and the jump, above zero').toBe(0);
});

test('a log y axis keeps the time axis of its neighbours; a saved chart is sharp', async ({ page }) => {
  await openViewer(page);
  // Fragments.dat: time, fragments, largest, intact bonds, broken in tension, in shear; no breaks
  // until 0.02 s, the run to 0.03 s
  const rows = [[0, 1, 27, 50, 0, 0], [0.01, 1, 27, 50, 0, 0], [0.02, 2, 20, 40, 10, 0], [0.03, 3, 9, 30, 20, 0]]
    .map((r) => r.join(' ')).join('\n') + '\n';
  const axes = await page.evaluate((text) => {
    const charts = window.demLive.charts;
    charts.setFragments(text);
    const chart = charts.chart('broken-bonds');
    chart.draw();
    const linear = chart.axes.x;
    chart.log = true;
    chart.draw();
    return { linear, log: chart.axes.x };
  }, rows);
  // before: the log axis dropped the zero counts' times and began at 0.02
  expect(axes.log).toEqual(axes.linear);
  const canvas = page.locator('canvas[data-chart="broken-bonds"]');
  const box = await canvas.boundingBox();
  const [download] = await Promise.all([page.waitForEvent('download'), page.locator('.chart[data-chart="broken-bonds"] button[data-export="png"]').click()]);
  const png = fs.readFileSync(await download.path());
  const width = png.readUInt32BE(16);
  // before: the screen's own pixels (312 wide)
  expect(width, 'three pixels a CSS pixel').toBe(Math.round(3 * box.width));
});
