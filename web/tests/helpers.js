// Shared pieces of the viewer's browser tests: the test fixture (page errors fail the test, the
// console is attached), a tiny legacy-file reader independent of the viewer's, and helpers that
// drive the controls of docs/viewer.md.
import { test as base, expect } from '@playwright/test';
import fs from 'node:fs';
import path from 'node:path';

export { expect };

export const serverUrl = () => {
  if (!process.env.DEM_SERVER_URL) throw new Error('DEM_SERVER_URL is not set: run through playwright.config.js (global setup)');
  return process.env.DEM_SERVER_URL;
};
export const fixture = (...parts) => path.join(process.env.DEM_FIXTURES, ...parts);
export const ANIMATION = () => fixture('offline', 'ANIMATION_3D.dat');
export const FORCE_CHAINS = () => fixture('offline', 'ForceChain_3D.dat');
export const MALFORMED = () => fixture('malformed', 'ANIMATION_3D.dat');
export const TRUNCATED = () => fixture('truncated', 'ANIMATION_3D.dat');
export const PLANAR = () => fixture('planar', 'ANIMATION_2D.dat');

// `test` with an automatic fixture: any uncaught exception in the page fails the test, and the
// page's console is attached to the report.
export const test = base.extend({
  pageErrors: [async ({ page }, use, testInfo) => {
    const errors = [];
    const consoleLines = [];
    page.on('pageerror', (e) => errors.push(`${e.name}: ${e.message}\n${e.stack || ''}`));
    page.on('console', (m) => consoleLines.push(`[${m.type()}] ${m.text()}`));
    await use(errors);
    if (consoleLines.length) {
      await testInfo.attach('console.txt', { body: consoleLines.join('\n'), contentType: 'text/plain' });
    }
    expect(errors, 'uncaught exceptions in the page').toEqual([]);
  }, { auto: true }],
});

// --- a tiny reader of ANIMATION_3D.dat and ForceChain_3D.dat (docs/formats.md sections 3, 4) ---

// Frames of an ANIMATION_3D.dat (or a 2D run's ANIMATION_2D.dat): [{ step, particles, time }], from each
// '3DA:' ('2DA:') header, the first scalar (time, s) two lines after it and the "step NP NW" line four after it.
export function readAnimation(file) {
  const lines = fs.readFileSync(file, 'utf8').split(/\r?\n/).filter((l) => l.trim() !== '');
  const frames = [];
  for (let i = 0; i < lines.length; i++) {
    if (lines[i].trim() !== '3DA:' && lines[i].trim() !== '2DA:') continue;
    const time = Number(lines[i + 2].trim().split(/\s+/)[0]);
    const [step, particles] = lines[i + 4].trim().split(/\s+/).map(Number);
    frames.push({ step, particles, time });
  }
  return frames;
}

// Frames of a ForceChain_3D.dat: [{ step, chains }] from the '3DF: step NC' headers.
export function readForceChains(file) {
  return fs.readFileSync(file, 'utf8').split(/\r?\n/)
    .filter((l) => l.startsWith('3DF:'))
    .map((l) => { const [, step, chains] = l.trim().split(/\s+/).map(Number); return { step, chains }; });
}

// --- driving the page ---

// The axes indicator is switched off: the tests' pictures are of the scene alone (camera.spec.js
// checks the indicator); the panel's folded sections are opened (layout.spec.js checks the folds).
export async function openViewer(page, { axes = false, url = serverUrl() } = {}) {
  await page.goto(`${url}/`);
  await page.waitForFunction(() => window.demViewer && typeof window.demViewer.state === 'function',
                             null, { timeout: 60_000 });
  // every folded section of the panel opened, so that the tests reach its controls
  await page.evaluate(() => document.querySelectorAll('details.group').forEach((d) => { d.open = true; }));
  if (!axes) await page.locator('#show-axes').uncheck();
}

export const state = (page) => page.evaluate(() => window.demViewer.state());

// The number shown in an element ("1,571" or "1571 particles" -> 1571; "0.1 s" -> 0.1).
export async function shownNumber(page, selector) {
  const text = (await page.locator(selector).textContent()) || '';
  const m = text.replace(/,/g, '').match(/[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?/);
  if (!m) throw new Error(`${selector} shows no number: ${JSON.stringify(text)}`);
  return Number(m[0]);
}

// Loads files through #file-input and waits until the viewer holds `frames` frames.
export async function loadFiles(page, files, frames) {
  await page.locator('#file-input').setInputFiles(files);
  if (frames !== undefined) {
    await expect.poll(async () => (await state(page)).frames, { timeout: 60_000 }).toBe(frames);
    await expect(page.locator('#frame-count')).toHaveText(new RegExp(`\\b${frames}\\b`));
  }
}

// Sets an <input type=range> (Playwright cannot fill those) and fires input and change.
export async function setRange(page, selector, value) {
  await page.locator(selector).evaluate((el, v) => {
    el.value = String(v);
    el.dispatchEvent(new Event('input', { bubbles: true }));
    el.dispatchEvent(new Event('change', { bubbles: true }));
  }, value);
  await settle(page);
}

// Waits for two animation frames, so that the last change is drawn.
export async function settle(page) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => setTimeout(r, 50)))));
}

export async function pause(page) {
  if ((await state(page)).playing) await page.locator('#pause').click();
  await expect.poll(async () => (await state(page)).playing).toBe(false);
}

// Shows frame `index` (0-based) with #time-slider (from its min: 0-based or 1-based) and waits
// until #frame-index says so.
export async function showFrame(page, index) {
  await pause(page);
  const min = Number(await page.locator('#time-slider').getAttribute('min')) || 0;
  await setRange(page, '#time-slider', min + index);
  await expect(page.locator('#frame-index')).toHaveText(new RegExp(`\\b${index + 1}\\b`));
  await settle(page);
}

// The three.js canvas: the largest <canvas> on the page (the colour bar and the charts are smaller).
export async function viewCanvas(page) {
  await page.evaluate(() => {
    const all = [...document.querySelectorAll('canvas')];
    if (!all.length) throw new Error('no canvas on the page');
    const area = (c) => { const r = c.getBoundingClientRect(); return r.width * r.height; };
    all.sort((a, b) => area(b) - area(a));
    for (const c of all) c.removeAttribute('data-test-view');
    all[0].setAttribute('data-test-view', '');
  });
  return page.locator('canvas[data-test-view]');
}

// A PNG of the view (the canvas as composited on the page).
// Messages and the probe's boxes shown over the view are left out (hidden while the picture is taken).
export async function canvasShot(page) {
  await settle(page);
  return (await viewCanvas(page)).screenshot({ style: '#message-box, #probe, #hover-readout, #empty-hint { visibility: hidden !important; }' });
}

// Keeps a picture for a person: a PNG in the test's output folder, attached to the report.
export async function keep(testInfo, name, png) {
  const file = testInfo.outputPath(`${name}.png`);
  fs.writeFileSync(file, png);
  await testInfo.attach(name, { path: file, contentType: 'image/png' });
}

// A screenshot of the whole page, kept.
export async function keepPage(page, testInfo, name) {
  await settle(page);
  await keep(testInfo, name, await page.screenshot());
}

// Runs `measure(images, arg)` in the page on PNGs decoded there (each an ImageData). `measure` is
// sent as its source: it sees only its arguments, not this file's names.
async function onPixels(page, pngs, measure, arg = null) {
  return page.evaluate(async ([pngs64, source, arg]) => {
    const decode = async (data) => {
      const img = new Image();
      img.src = `data:image/png;base64,${data}`;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.naturalWidth; c.height = img.naturalHeight;
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      return g.getImageData(0, 0, c.width, c.height);
    };
    const images = await Promise.all(pngs64.map(decode));
    return new Function(`return (${source});`)()(images, arg);
  }, [pngs.map((png) => png.toString('base64')), measure.toString(), arg]);
}

// Measures one or two PNGs: the size and the number of distinct colours (sampled) of the first, and
// with a second the share of pixels (0 to 1) with a channel that differs by more than 8 of 255 (so
// that dithering and rounding do not count; 1 when the sizes differ).
async function measurePngs(page, a, b) {
  return onPixels(page, b ? [a, b] : [a], ([pa, pb]) => {
    const seen = new Set();
    const stride = Math.max(1, Math.floor(pa.data.length / 4 / 200000)) * 4;
    for (let i = 0; i < pa.data.length; i += stride)
      seen.add((pa.data[i] << 24) | (pa.data[i + 1] << 16) | (pa.data[i + 2] << 8) | pa.data[i + 3]);
    const out = { width: pa.width, height: pa.height, colours: seen.size, differ: null };
    if (!pb) return out;
    if (pa.width !== pb.width || pa.height !== pb.height) return { ...out, differ: 1 };
    let differ = 0;
    for (let i = 0; i < pa.data.length; i += 4) {
      if (Math.abs(pa.data[i] - pb.data[i]) > 8 || Math.abs(pa.data[i + 1] - pb.data[i + 1]) > 8 ||
          Math.abs(pa.data[i + 2] - pb.data[i + 2]) > 8) differ++;
    }
    return { ...out, differ: differ / (pa.width * pa.height) };
  });
}

// Distinct colours in a PNG (sampled): a blank picture has one or two.
export async function pngColourCount(page, png) {
  const { width, height, colours } = await measurePngs(page, png);
  return { width, height, colours };
}

// The share of pixels that differ between two PNGs of the same size (see measurePngs).
export async function pixelDiff(page, a, b) {
  return (await measurePngs(page, a, b)).differ;
}

// Expects two pictures of the view to differ visibly: at least 0.2% of the pixels.
export async function expectPicturesDiffer(page, a, b, what) {
  const share = await pixelDiff(page, a, b);
  expect(share, `${what}: ${(100 * share).toFixed(3)}% of the pixels differ`).toBeGreaterThan(0.002);
  return share;
}

export const closeTo = (a, b) => Math.abs(a - b) <= 1e-5 * Math.max(Math.abs(a), Math.abs(b)) + 1e-9;

// Counts the pixels of a PNG (decoded in the page) that each predicate accepts. `kinds` maps a name
// to the source of a predicate `(r, g, b, x, y) => boolean` (a string: it runs in the page);
// `region` ({ x, y, width, height }, optional; negative x and y count from the right and bottom)
// limits the count to part of the picture.
export async function countPixels(page, png, kinds, region = null) {
  return onPixels(page, [png], ([image], { kinds, region }) => {
    const r = region || { x: 0, y: 0, width: image.width, height: image.height };
    const x0 = r.x < 0 ? image.width + r.x : r.x, y0 = r.y < 0 ? image.height + r.y : r.y;
    const tests = Object.entries(kinds).map(([name, source]) => [name, new Function(`return (${source});`)()]);
    const counts = Object.fromEntries(tests.map(([name]) => [name, 0]));
    for (let y = y0; y < y0 + r.height; y++) {
      for (let x = x0; x < x0 + r.width; x++) {
        if (x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
        const i = (y * image.width + x) * 4;
        const d = image.data;
        for (const [name, test] of tests) if (test(d[i], d[i + 1], d[i + 2], x, y)) counts[name] += 1;
      }
    }
    return counts;
  }, { kinds, region });
}

// Submits the bundled demo case for `duration` s from the page's case form; returns the new job
// (the server's record) once the server lists it.
export async function submitDemo(page, request, duration) {
  const api = (p) => `${serverUrl()}${p}`;
  const jobsBefore = new Set(((await (await request.get(api('/api/jobs'))).json()).jobs).map((j) => j.id));
  const select = page.locator('#case-select');
  await expect.poll(() => select.evaluate((s) => [...s.options].some((o) => o.value === 'demo')),
                    { message: '#case-select offers the demo case' }).toBe(true);
  await select.selectOption('demo');
  // the demo's own name: the first case (ballast, also granite) loads at start and may arrive late
  await expect.poll(() => page.locator('#case-spec').inputValue(), { message: '#case-spec holds the demo spec' })
    .toContain('spheres poured into a box');
  await page.locator('#case-duration').fill(String(duration));
  await page.locator('#case-duration').dispatchEvent('change');
  await expect.poll(() => page.locator('#case-spec').inputValue().then((t) => JSON.parse(t).time.duration),
                    { message: '#case-spec takes the duration typed' }).toBe(duration);
  await page.locator('#submit-case').click();
  let job;
  await expect.poll(async () => {
    const jobs = (await (await request.get(api('/api/jobs'))).json()).jobs.filter((j) => !jobsBefore.has(j.id));
    job = jobs[jobs.length - 1];
    return jobs.length;
  }, { message: 'submitting makes one job on the server' }).toBe(1);
  return job;
}

// A job spec of spheres in a cubic lattice falling onto a floor, small enough to run anywhere:
// `top` the lattice's top (0.1: 112 spheres), `duration` in seconds.
export function fallingSpheres(name, duration, top = 0.05) {
  return {
    name,
    materials: [{ name: 'rock', density: 2600, normalStiffness: 2e4 }, { name: 'steel', rigid: true }],
    interactions: [{ a: 'rock', b: 'rock', restitution: 0.3, friction: 0.4 }, { a: 'rock', b: 'steel', restitution: 0.3, friction: 0.4 }],
    lattices: [{ kind: 'CUBIC', material: 'rock', radius: 0.005, spacing: 1.2, min: { x: 0, y: 0, z: 0.01 }, max: { x: 0.05, y: 0.05, z: top } }],
    walls: [{ name: 'floor', material: 'steel', plane: { normal: { z: 1 } } }],
    gravity: { z: -9.81 },
    time: { duration },
    outputs: { everySteps: 200 },
  };
}
