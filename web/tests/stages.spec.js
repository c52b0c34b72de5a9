// A staged job followed live: the status line names the stage each frame belongs to.
import { test, expect, serverUrl, openViewer } from './helpers.js';

// 8 x 8 x 8 spheres falling into a box in one stage, the box tilted by gravity in the next. The first
// stage lasts some seconds of wall time (150,000 steps): a page still setting up its view when the
// first frames come shows the newest frame it has (a viewer behind skips by design), and a stage of
// one second ended unseen (2026-12-08).
const STAGED = {
  name: 'staged in the viewer',
  materials: [{ name: 'rock', density: 2600, normalStiffness: 2e4 }, { name: 'steel', rigid: true }],
  interactions: [{ a: 'rock', b: 'rock', restitution: 0.3, friction: 0.4 },
                 { a: 'rock', b: 'steel', restitution: 0.3, friction: 0.4 }],
  lattices: [{ kind: 'CUBIC', material: 'rock', radius: 0.005, spacing: 1.2,
               min: { x: 0, y: 0, z: 0.01 }, max: { x: 0.1, y: 0.1, z: 0.12 } }],
  walls: [{ name: 'floor', material: 'steel', plane: { normal: { z: 1 } } },
          { name: 'side', material: 'steel', plane: { point: { x: 0.1 }, normal: { x: -1 } } }],
  gravity: { z: -9.81 },
  outputs: { everySteps: 200 },
  stages: [{ name: 'fall', duration: 2.0 }, { name: 'lean', duration: 0.4, gravity: { x: 3, z: -9.81 } }],
};

test('a staged job shows its stage in the live status', async ({ page, request }) => {
  test.setTimeout(240_000);
  await openViewer(page);
  await page.locator('#case-spec').fill(JSON.stringify(STAGED, null, 2));
  await page.locator('#submit-case').click();
  const seen = new Set();
  await expect.poll(async () => {
    const text = (await page.locator('#live-status').textContent()) || '';
    const m = text.match(/stage (\w+),/);
    if (m) seen.add(m[1]);
    return [...seen].sort().join(' ');
  }, { message: '#live-status names both stages', timeout: 200_000, intervals: [100] }).toBe('fall lean');
  const jobs = (await (await request.get(`${serverUrl()}/api/jobs`)).json()).jobs;
  const job = jobs.find((j) => j.name === STAGED.name);
  expect(job, 'the job is on the server').toBeTruthy();
  const log = await (await request.get(`${serverUrl()}/api/jobs/${job.id}/artifacts/Stages.dat`)).text();
  expect(log.split('\n').filter((l) => l.trim()).length, 'Stages.dat: a header and a line a stage').toBe(3);
});
