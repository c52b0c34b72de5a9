// Loading is cancellable: the Cancel button stops a load, and a new choice of files cancels the one
// still loading, so a small file does not wait behind a large one. The run shown before stays.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { test, expect, ANIMATION, PLANAR, readAnimation, openViewer, state, loadFiles, fallingSpheres } from './helpers.js';

// A large ANIMATION_3D.dat: the fixture's frames over and over, about `megabytes` MB.
function largeAnimation(megabytes) {
  const text = fs.readFileSync(ANIMATION(), 'utf8');
  const file = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'dem-viewer-large-')), 'ANIMATION_3D.dat');
  const copies = Math.ceil((megabytes << 20) / text.length);
  const fd = fs.openSync(file, 'w');
  for (let k = 0; k < copies; k++) fs.writeSync(fd, text);
  fs.closeSync(fd);
  return file;
}

let large;
test.beforeAll(() => { large = largeAnimation(120); });
test.afterAll(() => { if (large) fs.rmSync(path.dirname(large), { recursive: true, force: true }); });

// Chooses the large file and waits until its load is under way (the progress bar moves).
async function startLargeLoad(page) {
  await page.locator('#file-input').setInputFiles(large);
  await expect(page.locator('#load-cancel')).toBeVisible();
  await expect.poll(() => page.locator('#load-progress').evaluate((p) => p.value), { intervals: [50] }).toBeGreaterThan(0);
}

test('Cancel stops a load and the run shown before stays', async ({ page }) => {
  const frames = readAnimation(PLANAR()).length;
  await openViewer(page);
  await loadFiles(page, [PLANAR()], frames);
  await startLargeLoad(page);
  const progressWhenCancelled = await page.locator('#load-progress').evaluate((p) => p.value);
  expect(progressWhenCancelled, 'cancelled part way').toBeLessThan(0.9);
  await page.locator('#load-cancel').click();
  await expect(page.locator('#load-progress')).toBeHidden({ timeout: 3_000 });
  await expect(page.locator('#load-cancel')).toBeHidden();
  await expect(page.locator('#message')).toContainText('cancelled');
  const after = await state(page);
  expect(after.frames, 'the run shown before').toBe(frames);
  expect(after.planar).toBe(true);
  // and the viewer loads again afterwards (a new worker)
  await loadFiles(page, [ANIMATION()], readAnimation(ANIMATION()).length);
});

test('a new choice cancels the load still under way', async ({ page }) => {
  const small = readAnimation(PLANAR()).length;
  await openViewer(page);
  await startLargeLoad(page);
  const chosen = Date.now();
  await page.locator('#file-input').setInputFiles(PLANAR());
  await expect.poll(async () => (await state(page)).frames, { timeout: 10_000, intervals: [50] }).toBe(small);
  const waited = Date.now() - chosen;
  expect(waited, 'ms the small file took to show').toBeLessThan(10_000);
  expect((await state(page)).planar, 'the small file is the run shown').toBe(true);
  await expect(page.locator('#message')).toContainText(`${small} frames of`);
  // the large file's load does not come back over it
  await page.waitForTimeout(1_000);
  expect((await state(page)).frames).toBe(small);
  await expect(page.locator('#load-progress')).toBeHidden();
});

test('cancelling one parse leaves another parse under way alone (a replay beside a file load)', async ({ page }) => {
  await openViewer(page);
  const text = fs.readFileSync(ANIMATION(), 'utf8');
  const frames = readAnimation(ANIMATION()).length;
  const outcome = await page.evaluate(async ({ text, copies }) => {
    const big = () => new Blob(Array.from({ length: copies }, () => text), { type: 'text/plain' });
    const parse = window.demViewer.parseFile;
    const other = parse(big()).then((r) => `parsed ${r.frames.length} frames`, (e) => `failed: ${e.name} ${e.message}`);
    const controller = new AbortController();
    let started = false;
    const mine = parse(big(), () => { started = true; }, controller.signal).then(() => 'parsed', (e) => e.name);
    while (!started) await new Promise((r) => setTimeout(r, 20));
    controller.abort();
    return { mine: await mine, other: await other };
  }, { text, copies: Math.ceil((30 << 20) / text.length) });
  expect(outcome.mine).toBe('AbortError');
  expect(outcome.other, 'the other parse').toBe(`parsed ${frames * Math.ceil((30 << 20) / text.length)} frames`);
});

// A finished job of the server (a few spheres on a floor), for the replay tests.
async function finishedJob(request) {
  const api = (p) => `${process.env.DEM_SERVER_URL}${p}`;
  const spec = fallingSpheres('replay to cancel', 0.05);
  const job = await (await request.post(api('/api/v1/jobs'), { data: spec })).json();
  await expect.poll(async () => (await (await request.get(api(`/api/v1/jobs/${job.id}`))).json()).state,
                    { timeout: 60_000 }).toBe('succeeded');
  return job;
}

// Holds the job's ANIMATION_3D.dat download until release() is called.
async function holdAnimation(page, job) {
  let release;
  const released = new Promise((resolve) => { release = resolve; });
  await page.route(`**/jobs/${job.id}/artifacts/ANIMATION_3D.dat`, async (route) => {
    await released;
    await route.continue().catch(() => {}); // the page may have aborted it meanwhile
  });
  return release;
}


// Clicks `job` in the job list with its ANIMATION_3D.dat held (holdAnimation), and waits until the
// replay is under way; returns the release.
async function startHeldReplay(page, job) {
  const release = await holdAnimation(page, job);
  await page.locator(`#jobs li[data-id="${job.id}"]`).click();
  await expect(page.locator('#load-cancel')).toBeVisible();
  return release;
}

// Replays `job` to the end: its run and its charts shown.
async function showJob(page, job) {
  await page.locator(`#jobs li[data-id="${job.id}"]`).click();
  await expect(page.locator('#message')).toContainText(`job ${job.id}:`);
  await expect(page.locator('canvas[data-chart="kinetic-energy"]')).toBeVisible();
}

// Lets the held download go and checks that the files' run is still the one shown.
async function expectFilesRunStays(page, release, frames) {
  release();
  await page.waitForTimeout(1500);
  expect((await state(page)).frames, 'the files\' run').toBe(frames);
  expect(await page.evaluate(() => window.demViewer.viewer.run.source)).toBe('ANIMATION_3D.dat');
}

// A study of one short run on the server, chosen in the page's Studies.
async function studyOfOneRun(request, name) {
  const made = await request.post(`${process.env.DEM_SERVER_URL}/api/v1/studies`, {
    data: { name, base: fallingSpheres('study base', 0.02), parameters: [{ path: 'gravity.z', values: [-9.81] }] },
  });
  expect(made.status(), await made.text()).toBe(201);
  return made.json();
}

async function chooseStudy(page, study) {
  await expect.poll(() => page.locator('#study-select').evaluate((s, id) => [...s.options].some((o) => o.value === String(id)), study.id))
    .toBe(true);
  await page.locator('#live-studies').evaluate((d) => { d.open = true; });
  await page.locator('#study-select').selectOption(String(study.id));
}

test('a replay can be cancelled, and the run shown before stays', async ({ page, request }) => {
  const job = await finishedJob(request);
  const frames = readAnimation(ANIMATION());
  await openViewer(page);
  await loadFiles(page, [ANIMATION()], frames.length);
  const release = await startHeldReplay(page, job);
  await page.locator('#load-cancel').click();
  await expect(page.locator('#message')).toContainText('replay cancelled');
  await expect(page.locator('#load-cancel')).toBeHidden();
  await expect(page.locator('#load-progress')).toBeHidden();
  await expectFilesRunStays(page, release, frames.length);
});

test('files chosen during a replay end it: the replay does not replace them when its download ends', async ({ page, request }) => {
  const job = await finishedJob(request);
  const frames = readAnimation(ANIMATION());
  await openViewer(page);
  const release = await startHeldReplay(page, job);
  await loadFiles(page, [ANIMATION()], frames.length);
  // before: the status line said "downloading ANIMATION_3D.dat: 7.8%" for good (helper-34)
  await expect(page.locator('#live-status')).toContainText(`the replay of job ${job.id} stopped: files were opened`);
  await expect(page.locator('#live-job')).toHaveText('none');
  await expectFilesRunStays(page, release, frames.length);
});

test('a replay that fails hands the panel back to the job shown', async ({ page, request }) => {
  const shown = await finishedJob(request);
  const other = await finishedJob(request);
  await openViewer(page);
  await showJob(page, shown);
  await page.route(`**/jobs/${other.id}/artifacts/ANIMATION_3D.dat`, (route) => route.abort('connectionreset'));
  await page.locator(`#jobs li[data-id="${other.id}"]`).click();
  await expect(page.locator('#live-status')).toContainText('replay failed');
  // before: the panel named the failed job over the run still shown (helper-34)
  await expect(page.locator('#live-job')).toContainText(`#${shown.id}`);
  await expect(page.locator('#jobs li.selected')).toHaveAttribute('data-id', String(shown.id));
  await expect(page.locator('canvas[data-chart="kinetic-energy"]')).toBeVisible();
});

test('a replay cancelled after a study had the charts brings the shown job\'s charts back', async ({ page, request }) => {
  const study = await studyOfOneRun(request, 'between two jobs');
  const shown = await finishedJob(request);
  const other = await finishedJob(request);
  await openViewer(page);
  await showJob(page, shown);
  await chooseStudy(page, study);
  await expect(page.locator('canvas[data-chart="kinetic-energy"]')).toHaveCount(0);
  const release = await startHeldReplay(page, other);
  await page.locator('#load-cancel').click();
  // before: no chart at all (helper-34)
  await expect(page.locator('#live-job')).toContainText(`#${shown.id}`);
  await expect(page.locator('canvas[data-chart="kinetic-energy"]')).toBeVisible();
  release();
});

test('a cancelled replay hands the panel back to the job shown, with its charts', async ({ page, request }) => {
  const shown = await finishedJob(request);
  const other = await finishedJob(request);
  await openViewer(page);
  await showJob(page, shown);
  const frames = (await state(page)).frames;
  const release = await startHeldReplay(page, other);
  await expect(page.locator('#live-job')).toContainText(`#${other.id}`);
  await page.locator('#load-cancel').click();
  // before: the panel named the cancelled job, and the charts of the run still shown were gone
  await expect(page.locator('#live-job')).toContainText(`#${shown.id}`);
  await expect(page.locator('#jobs li.selected')).toHaveAttribute('data-id', String(shown.id));
  await expect(page.locator('canvas[data-chart="kinetic-energy"]')).toBeVisible();
  expect((await state(page)).frames).toBe(frames);
  release();
});

test('a study chosen during a replay stops it and says so', async ({ page, request }) => {
  const study = await studyOfOneRun(request, 'chosen mid-replay');
  const job = await finishedJob(request);
  await openViewer(page);
  const release = await startHeldReplay(page, job);
  await chooseStudy(page, study);
  // before: the bar vanished and the status said "downloading ... 45%" for good
  await expect(page.locator('#message')).toContainText(`the replay of job ${job.id} stopped: a study was chosen`);
  await expect(page.locator('#live-status')).not.toContainText('downloading');
  await expect(page.locator('#load-progress')).toBeHidden();
  await expect(page.locator('#live-job')).toHaveText('none');
  release();
});
