// Force chains of a job followed live: they come only with the job's output frames, so between them
// the view shows the latest chains received (by particle id, at the particles' new places) and says
// from which step; switching them on says nothing false about files.
import { test, expect, serverUrl, openViewer, state, keepPage, submitDemo } from './helpers.js';

test('live force chains: shown between output frames, no message about files', async ({ page, request }, testInfo) => {
  test.setTimeout(300_000);
  await openViewer(page);
  // long enough to be still running when the box is ticked (0.4 s ended first on a quiet machine)
  const job = await submitDemo(page, request, 1.0);
  await expect.poll(async () => (await state(page)).live, { message: 'following the job' }).toBe(true);
  await page.locator('#show-force-chains').check();
  await expect(page.locator('#message')).not.toContainText('No force chains loaded');
  // while the job runs, frames without chains of their own show the latest chains received
  let between = 0;
  await expect.poll(async () => {
    const seen = await page.evaluate(() => {
      const v = window.demViewer.viewer;
      const frame = v.currentFrame();
      return { own: Boolean(frame && frame.forceChains), drawn: v.chains.drawn, live: v.live };
    });
    if (!seen.own && seen.drawn > 0) between += 1;
    return between > 0 || !seen.live;
  }, { message: 'a live frame without chains of its own shows the latest chains', timeout: 240_000, intervals: [200] }).toBe(true);
  expect(between, 'seen while the job ran').toBeGreaterThan(0);
  await expect(page.locator('#chain-legend')).toBeVisible();
  await expect(page.locator('#chain-step')).toContainText('the latest received, from step');
  // Seen: the job is not needed to its end. Left running beside software WebGL on two cores, it made
  // the picture below take 11 s and this test 22 s; cancelled, the test took 14.5 s (2026-12-07).
  await request.post(`${serverUrl()}/api/v1/jobs/${job.id}/cancel`);
  await keepPage(page, testInfo, 'live-chains');
});
