// Live use: submit a bundled case from the page, follow its frames, replay the finished run.
import fs from 'node:fs';
import { test, expect, serverUrl, openViewer, state, shownNumber, pause, canvasShot, keep, keepPage, submitDemo } from './helpers.js';

const DURATION = 0.2;  // s of the demo case (1,571 spheres): a few seconds of wall time, ~20 frames

test('submit the demo case, follow it live, replay it', async ({ page, request }, testInfo) => {
  test.setTimeout(360_000);
  const api = (p) => `${serverUrl()}${p}`;

  await openViewer(page);
  const job = await submitDemo(page, request, DURATION);
  expect(job.totalSteps * job.timeStep, `the job runs ${DURATION} s (#case-duration)`).toBeCloseTo(DURATION, 3);

  // frames arrive: #live-step shows two different steps
  const steps = new Set();
  await expect.poll(async () => {
    const text = ((await page.locator('#live-step').textContent()) || '').replace(/,/g, '');
    const m = text.match(/\d+/);
    if (m) steps.add(Number(m[0]));
    if (steps.size === 1) await keepPage(page, testInfo, 'live-first-frame');
    return steps.size;
  }, { message: '#live-step advances', timeout: 120_000, intervals: [100] }).toBeGreaterThanOrEqual(2);
  expect((await state(page)).particles, 'live frames carry every particle').toBe(job.particles);
  await keep(testInfo, 'live-view', await canvasShot(page));
  await keepPage(page, testInfo, 'live');
  await expect(page.locator(`#jobs li[data-id="${job.id}"]`), 'the job is listed in #jobs').toHaveCount(1);

  // the job finishes
  await expect.poll(async () => (await (await request.get(api(`/api/jobs/${job.id}`))).json()).state,
                    { message: 'the job succeeds', timeout: 240_000, intervals: [500] }).toBe('succeeded');
  const animation = await (await request.get(api(`/api/jobs/${job.id}/artifacts/ANIMATION_3D.dat`))).text();
  const fileFrames = animation.split('\n').filter((l) => l.trim() === '3DA:').length;
  expect(fileFrames).toBeGreaterThan(1);
  await expect.poll(async () => Number(((await page.locator('#live-step').textContent()) || '').replace(/\D/g, '')),
                    { message: '#live-step reaches the last step' }).toBe(job.totalSteps);

  // replay the finished run from its files
  await page.locator('#replay').click();
  await expect.poll(async () => (await state(page)).frames, { message: 'the replay holds every frame of ANIMATION_3D.dat', timeout: 120_000 })
    .toBe(fileFrames);
  expect(await shownNumber(page, '#frame-count')).toBe(fileFrames);
  expect(await shownNumber(page, '#frame-count')).toBeGreaterThan(1);
  expect(await shownNumber(page, '#particle-count')).toBe(job.particles);
  await pause(page);
  await keep(testInfo, 'replay-view', await canvasShot(page));
  await keepPage(page, testInfo, 'replay');

  // a chart's numbers and picture, exported
  const chart = page.locator('.chart[data-chart="kinetic-energy"]');
  await expect(chart).toBeVisible();
  const points = Number(await chart.locator('canvas').getAttribute('data-points'));
  expect(points).toBeGreaterThan(1);
  const [csvDownload] = await Promise.all([page.waitForEvent('download'), chart.locator('[data-export="csv"]').click()]);
  expect(csvDownload.suggestedFilename()).toBe('kinetic-energy.csv');
  const csv = fs.readFileSync(await csvDownload.path(), 'utf8').trim().split(/\r?\n/);
  expect(csv[0]).toBe('series,time (s),"kinetic energy (J)"');
  expect(csv.length - 1, 'a row a point').toBe(points);
  const [first] = csv.slice(1).map((row) => row.split(','));
  expect(first[0]).toBe('"kinetic energy"');
  expect(Number.isFinite(Number(first[1])) && Number.isFinite(Number(first[2]))).toBe(true);
  const [pngDownload] = await Promise.all([page.waitForEvent('download'), chart.locator('[data-export="png"]').click()]);
  expect(pngDownload.suggestedFilename()).toBe('kinetic-energy.png');
  expect(fs.readFileSync(await pngDownload.path()).subarray(1, 4).toString()).toBe('PNG');
});
