// A live view that cannot keep up: whatever the time a picture takes, the page shows the newest
// frame it has and skips the ones in between, and it says the run has ended when it has.
import { test, expect, serverUrl, openViewer, state, keepPage, submitDemo } from './helpers.js';

// s of the demo case: several seconds of frames at the server's 30 a second on a quiet machine
// (0.3 s ended before the view had been sampled twice)
const DURATION = 0.8;
const SLOW_DRAW_MS = 250;  // each picture of the view takes this long (a slow GPU, a huge run)

test('a slow view shows the newest live frame and ends with the job', async ({ page, request }, testInfo) => {
  test.setTimeout(300_000);
  const api = (p) => `${serverUrl()}${p}`;
  await openViewer(page);
  // every redraw of the view busy-waits SLOW_DRAW_MS first
  await page.evaluate((ms) => {
    const viewer = window.demViewer.viewer;
    const draw = viewer.redraw.bind(viewer);
    window.slowDraws = 0;
    viewer.redraw = () => {
      const start = performance.now();
      while (performance.now() - start < ms) { /* a slow renderer */ }
      window.slowDraws += 1;
      return draw();
    };
  }, SLOW_DRAW_MS);

  const job = await submitDemo(page, request, DURATION);
  await expect.poll(async () => (await state(page)).live, { message: 'the page follows the job live' }).toBe(true);

  // while it runs, the view moves on (each picture shows the newest frame the page has)
  const shownSteps = new Set();
  for (;;) {
    const { state: jobState } = await (await request.get(api(`/api/jobs/${job.id}`))).json();
    if (jobState !== 'running' && jobState !== 'queued') {
      expect(jobState).toBe('succeeded');
      break;
    }
    const { step } = await state(page);
    if (step !== null) shownSteps.add(step);
    await page.waitForTimeout(300);
  }
  const ended = Date.now();
  // the job has ended: within a few pictures, its last frame is shown and the page no longer says live
  await expect.poll(async () => (await state(page)).step, { message: 'the view reaches the last step', timeout: 5_000, intervals: [100] })
    .toBe(job.totalSteps);
  await expect.poll(async () => (await state(page)).live, { message: 'the page says the run ended', timeout: 5_000, intervals: [100] })
    .toBe(false);
  const caughtUp = Date.now() - ended;
  const counts = await page.evaluate(() => ({ frames: window.demViewer.viewer.run.frames.length, draws: window.slowDraws }));
  await keepPage(page, testInfo, 'slow-view-after-the-job');
  testInfo.annotations.push({ type: 'measured', description: `${counts.frames} frames, ${counts.draws} slow draws, ${shownSteps.size} steps seen while running, caught up ${caughtUp} ms after the job ended` });
  expect(counts.frames, 'frames received').toBeGreaterThan(20);
  expect(shownSteps.size, 'steps shown while the job ran').toBeGreaterThanOrEqual(2);
  expect(counts.draws, 'the view skipped frames rather than drawing each').toBeLessThan(counts.frames);
});
