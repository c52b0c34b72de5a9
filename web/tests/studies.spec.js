// A parameter study's runs overlaid in the charts (src/live/studies.js): three runs of a bonded
// block under a cyclically loaded plate, the plate's peak load the parameter; each line checked
// against its job's own file.
import fs from 'node:fs';
import { test, expect, serverUrl, openViewer, countPixels, keepPage } from './helpers.js';
import { runNames, shortNames } from '../src/live/studies.js';

const BASE = {
  name: 'block under a plate',
  materials: [{ name: 'rock', density: 2500, youngsModulus: 1e7, poissonRatio: 0.25 },
              { name: 'steel', rigid: true, density: 7800 }],
  interactions: [{ a: 'rock', b: 'rock', restitution: 0.5, friction: 0.5 },
                 { a: 'rock', b: 'steel', restitution: 0.5, friction: 0.5 }],
  contact: { normal: 'HERTZ' },
  lattices: [{ kind: 'CUBIC', min: { x: 0, y: 0, z: 0.01 }, max: { x: 0.06, y: 0.06, z: 0.07 },
               radius: 0.01, spacing: 1.0, material: 'rock' }],
  bonds: { youngsModulus: 1e7, tensileStrength: 2e3, shearStrength: 2e3, gapTolerance: 0.01 },
  walls: [{ name: 'floor', material: 'steel', plane: { point: { z: 0 }, normal: { z: 1 } } },
          { name: 'press', material: 'steel', plate: { c1: { x: -0.1, y: -0.1, z: 0.08 }, c2: { x: 0.1, y: -0.1, z: 0.08 },
            c3: { x: 0.1, y: 0.1, z: 0.08 }, c4: { x: -0.1, y: 0.1, z: 0.08 } },
            load: { direction: { z: -1 }, mass: 0.5, cyclic: { fMin: 2, fMax: 30, frequency: 20, cycles: 2 } } }],
  gravity: { z: -9.81 },
  time: { steps: 6000 },
  outputs: { everySteps: 200, lengthUnit: 'mm' },
};
const PEAKS = [10, 30, 60];
const COLOURS = { first: [0x1f, 0x77, 0xb4], second: [0xd6, 0x27, 0x28], third: [0x2c, 0xa0, 0x2c] };

test('a study\'s runs are overlaid in the charts, one line a run, and leave for a job', async ({ page, request }, testInfo) => {
  test.setTimeout(240_000);
  const api = (p) => `${serverUrl()}${p}`;
  const made = await request.post(api('/api/v1/studies'), {
    data: { name: 'peak load', base: BASE, parameters: [{ path: 'walls[1].load.cyclic.fMax', values: PEAKS }] },
  });
  expect(made.status(), await made.text()).toBe(201);
  const study = await made.json();
  await expect.poll(async () => (await (await request.get(api(`/api/v1/studies/${study.id}`))).json()).finished,
                    { message: 'the study ends', timeout: 180_000 }).toBe(true);

  await openViewer(page);
  // a job replayed first: its charts give way to the study's
  await page.locator(`#jobs li[data-id="${study.jobs[0].job}"]`).click();
  await expect(page.locator('canvas[data-chart="kinetic-energy"]')).toBeVisible({ timeout: 60_000 });
  // folded, its title saying how many studies the server has (folded and silent, no one found it)
  await expect(page.locator('#live-studies summary')).toContainText(/Studies \(\d+\)/);
  await page.locator('#live-studies summary').click();
  const select = page.locator('#study-select');
  await expect.poll(() => select.evaluate((s, id) => [...s.options].some((o) => o.value === String(id)), study.id),
                    { message: '#study-select offers the study' }).toBe(true);
  await select.selectOption(String(study.id));

  const force = page.locator('canvas[data-chart="study-plate-force"]');
  await expect(force).toBeVisible();
  await expect(page.locator('#charts canvas:not([data-chart^="study-"])'), 'the job\'s own charts are gone').toHaveCount(0);
  await expect(page.locator('#study-status')).toContainText('3 of 3 runs with time series');
  await expect(page.locator('#study-legend')).toContainText(`Study #${study.id} peak load: walls[1].load.cyclic.fMax`);
  await expect(page.locator('#study-legend li')).toHaveText(PEAKS.map((p, k) => `fMax = ${p} · job ${study.jobs[k].job}`));
  const series = await page.evaluate(() => window.demLive.studies.charts.chart('study-plate-force').series
    .map((s) => ({ name: s.name, x: s.x, y: s.y })));
  expect(series.map((s) => s.name)).toEqual(PEAKS.map((p) => `fMax = ${p}`));
  // the chart's own legend: the values alone (helper-34: names cut to one prefix told no run apart)
  expect(await page.evaluate(() => window.demLive.studies.charts.chart('study-plate-force').series.map((s) => s.label)))
    .toEqual(PEAKS.map(String));
  // each line is its own run's Force_Displacement.dat: time, and the force column
  for (let k = 0; k < PEAKS.length; k++) {
    const text = await (await request.get(api(`/api/v1/jobs/${study.jobs[k].job}/artifacts/Force_Displacement.dat`))).text();
    const rows = text.trim().split('\n').map((l) => l.trim().split(/\s+/).map(Number));
    expect(series[k].x.length, `${series[k].name}: a point a row`).toBe(rows.length);
    expect(rows.length).toBeGreaterThan(10);
    expect(series[k].x).toEqual(rows.map((r) => r[0]));
    expect(series[k].y).toEqual(rows.map((r) => r[2]));
  }
  expect(series[0].y, 'the runs differ').not.toEqual(series[2].y);
  await expect(page.locator('canvas[data-chart="study-plate-displacement"]')).toBeVisible();
  await expect(page.locator('canvas[data-chart="study-broken-bonds"]')).toBeVisible();

  // the three lines are drawn, each in its own colour
  await page.waitForTimeout(300);
  const png = await force.screenshot();
  await testInfo.attach('study-plate-force.png', { body: png, contentType: 'image/png' });
  await keepPage(page, testInfo, 'study-overlay');
  const near = ([r, g, b]) => `(r, g, b) => Math.abs(r - ${r}) + Math.abs(g - ${g}) + Math.abs(b - ${b}) < 60`;
  const counts = await countPixels(page, png, Object.fromEntries(Object.entries(COLOURS).map(([k, c]) => [k, near(c)])));
  for (const [name, n] of Object.entries(counts)) expect(n, `pixels of the ${name} run's colour`).toBeGreaterThan(30);

  // the overlay's numbers as CSV: a series a run
  const [download] = await Promise.all([
    page.waitForEvent('download'),
    page.locator('.chart[data-chart="study-plate-force"] button[data-export="csv"]').click(),
  ]);
  const text = fs.readFileSync(await download.path(), 'utf8');
  expect(text.endsWith('\r\n') && !/[^\r]\n/.test(text), 'lines end in CRLF (RFC 4180)').toBe(true);
  const csv = text.trim().split(/\r?\n/);
  expect(csv[0]).toBe('series,time (s),"force (N)"');
  expect(new Set(csv.slice(1).map((l) => l.split(',')[0]))).toEqual(new Set(PEAKS.map((p) => `"fMax = ${p}"`)));

  // a job chosen ends the overlay: its own charts only
  await page.locator(`#jobs li[data-id="${study.jobs[1].job}"]`).click();
  await expect(page.locator('canvas[data-chart^="study-"]')).toHaveCount(0);
  await expect(select).toHaveValue('');
  await expect(page.locator('canvas[data-chart="plate-force"]')).toBeVisible();
});

test('run names tell parameters apart, keep the study\'s order, and say when a run did not succeed', () => {
  expect(shortNames(['interactions[0].friction', 'interactions[1].friction'])).toEqual(['interactions[0].friction', 'interactions[1].friction']);
  expect(shortNames(['bonds.tensileStrength', 'walls[1].load.servo.maxSpeed'])).toEqual(['tensileStrength', 'maxSpeed']);
  expect(shortNames(['/walls/1/load/cyclic/fMax'])).toEqual(['fMax']);
  // each path as short as it can be: a JSON pointer's index stays with its list
  expect(shortNames(['/interactions/0/friction', 'walls[0].plate.c1.z', 'walls[0].plate.c2.z'])).toEqual(['friction', 'c1.z', 'c2.z']);
  expect(shortNames(['/interactions/0/friction', '/interactions/1/friction'])).toEqual(['interactions[0].friction', 'interactions[1].friction']);
  const study = {
    parameters: ['walls[1].load.servo.maxSpeed', 'bonds.tensileStrength = bonds.shearStrength'],
    jobs: [
      // the server's parameters object comes back with its keys sorted
      { run: 1, job: 4, state: 'succeeded', parameters: { 'bonds.tensileStrength = bonds.shearStrength': 5e5, 'walls[1].load.servo.maxSpeed': 0.03 } },
      { run: 2, job: 5, state: 'cancelled', parameters: { 'bonds.tensileStrength = bonds.shearStrength': 2e6, 'walls[1].load.servo.maxSpeed': 0.03 } },
      { run: 3, job: 6, state: 'failed', parameters: { 'bonds.tensileStrength = bonds.shearStrength': { a: 1 }, 'walls[1].load.servo.maxSpeed': 0.3 } },
    ],
  };
  expect(runNames(study)).toEqual([
    'maxSpeed = 0.03, tensileStrength = shearStrength = 5e5',
    'maxSpeed = 0.03, tensileStrength = shearStrength = 2e6 (cancelled)',
    'maxSpeed = 0.3, tensileStrength = shearStrength = {"a":1} (failed)',
  ]);
});

test('a study\'s many runs: each its own colour, a legend of at most three lines in the chart, all of them above the charts', async ({ page }, testInfo) => {
  await openViewer(page);
  const names = Array.from({ length: 12 }, (_, k) => `walls[1].load.servo.gain = {"proportional": ${k}, "integral": ${k * 10}} and more words`);
  const drawn = await page.evaluate((names) => {
    const chart = window.demLive.studies.charts.chart('study-plate-force');
    chart.setSeries(names);
    names.forEach((_, k) => chart.set(k, [0, 1, 2], [k, k + 1, k + 2]));
    chart.draw();
    chart.draw(); // its second drawing has the height the first asked for
    return { colours: chart.series.map((s) => s.colour), height: chart.canvas.clientHeight };
  }, names);
  expect(new Set(drawn.colours).size, 'twelve runs, twelve colours').toBe(12);
  expect(drawn.height, 'a legend of three lines at most').toBeLessThanOrEqual(150 + 2 * 13);
  const canvas = page.locator('canvas[data-chart="study-plate-force"]');
  const png = await canvas.screenshot();
  await testInfo.attach('many-runs.png', { body: png, contentType: 'image/png' });
  // nothing in a run's colour left of the plot: long names are cut, not drawn off the left edge
  const coloured = '(r, g, b) => Math.max(r, g, b) - Math.min(r, g, b) > 80';
  const left = await countPixels(page, png, { coloured }, { x: 0, y: 0, width: 60, height: 60 });
  expect(left.coloured, 'run-coloured pixels left of the plot').toBe(0);
});
