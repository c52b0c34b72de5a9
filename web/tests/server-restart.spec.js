// A job followed live while its server restarts: the server checkpoints it at SIGTERM and resumes
// it after the restart, and the page joins it again (src/live/follow.js). A server of the test's
// own, on the same port both times, so that the shared one of the other tests is not disturbed.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { test, expect, openViewer, state, fallingSpheres } from './helpers.js';
import { waitForListening } from './global-setup.js';

const build = path.resolve(process.env.DEM_BUILD_DIR || path.join(import.meta.dirname, '..', '..', 'build'));
const dist = path.resolve(process.env.DEM_WEB_DIR || path.join(import.meta.dirname, '..', 'dist'));

function startServer(data, port) {
  const server = spawn(path.join(build, 'dem-server'), ['--port', String(port), '--data', data, '--web', dist],
                       { stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, OMP_WAIT_POLICY: 'PASSIVE' } });
  return { server, listening: waitForListening(server, 30_000) };
}

async function stop(server) {
  if (server.exitCode !== null || server.signalCode !== null) return;
  const exited = new Promise((resolve) => server.once('exit', resolve));
  server.kill('SIGTERM');
  await exited;
}

test('a job followed live goes on being followed after its server restarts', async ({ page, request }) => {
  test.setTimeout(240_000);
  const data = fs.mkdtempSync(path.join(os.tmpdir(), 'dem-restart-'));
  let { server, listening } = startServer(data, 0);
  const url = await listening;
  const port = Number(new URL(url).port);
  try {
    const job = await (await request.post(`${url}/api/v1/jobs`, { data: fallingSpheres('followed across a restart', 60, 0.1) })).json();
    await openViewer(page, { url });
    await page.locator(`#jobs li[data-id="${job.id}"]`).click();
    await expect.poll(async () => (await state(page)).frames, { message: 'live frames', timeout: 60_000 }).toBeGreaterThan(3);
    await stop(server);
    const before = (await state(page)).frames;
    await expect(page.locator('#live-status')).toContainText('joining again', { timeout: 30_000 });
    ({ server, listening } = startServer(data, port));
    await listening;
    // before: "the server is shutting down; the job goes on after its restart", and no frame after it
    await expect.poll(async () => (await state(page)).frames, { message: 'frames after the restart', timeout: 90_000 })
      .toBeGreaterThan(before + 3);
    expect((await state(page)).live).toBe(true);
    await request.post(`${url}/api/v1/jobs/${job.id}/cancel`);
  } finally {
    await stop(server);
    fs.rmSync(data, { recursive: true, force: true });
  }
});
