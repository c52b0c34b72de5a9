// Offline use: legacy files written by the engine (global setup), opened with the file input.
import {
  settle,
  test, expect, ANIMATION, FORCE_CHAINS, MALFORMED, TRUNCATED, readAnimation, readForceChains, openViewer,
  state, shownNumber, loadFiles, setRange, showFrame, pause, canvasShot, keep, keepPage, closeTo,
  pixelDiff, expectPicturesDiffer,
} from './helpers.js';

// What the page shows must be frame `index` (0-based) of the file.
async function expectShowing(page, frames, index) {
  const f = frames[index];
  expect(await shownNumber(page, '#frame-index'), '#frame-index (1-based)').toBe(index + 1);
  expect(await shownNumber(page, '#frame-count'), '#frame-count').toBe(frames.length);
  expect(await shownNumber(page, '#particle-count'), '#particle-count').toBe(f.particles);
  expect(await shownNumber(page, '#step'), '#step').toBe(f.step);
  const time = await shownNumber(page, '#time');
  expect(closeTo(time, f.time), `#time shows ${time}, the file's frame ${index + 1} has ${f.time}`).toBe(true);
  const s = await state(page);
  expect(s.particles, 'state().particles').toBe(f.particles);
  expect(s.frames, 'state().frames').toBe(frames.length);
  expect(s.step, 'state().step').toBe(f.step);
  expect(closeTo(s.time, f.time), `state().time ${s.time} vs ${f.time}`).toBe(true);
}

test('loads ANIMATION_3D.dat and ForceChain_3D.dat: counts and time match the files', async ({ page }, testInfo) => {
  const frames = readAnimation(ANIMATION());
  const chains = readForceChains(FORCE_CHAINS());
  expect(frames.length).toBeGreaterThan(2);
  expect(chains.some((c) => c.chains > 0)).toBe(true);

  await openViewer(page);
  await loadFiles(page, [ANIMATION(), FORCE_CHAINS()], frames.length);
  await pause(page);
  const shown = (await shownNumber(page, '#frame-index')) - 1;
  await expectShowing(page, frames, shown);
  await keepPage(page, testInfo, 'loaded');

  // step forward / back moves one frame, and the numbers follow
  const next = shown + 1 < frames.length ? shown + 1 : shown - 1;
  await page.locator(next > shown ? '#step-forward' : '#step-back').click();
  await expect(page.locator('#frame-index')).toHaveText(new RegExp(`\\b${next + 1}\\b`));
  await expectShowing(page, frames, next);

  // the last frame, through the time slider; it has force chains
  const last = frames.length - 1;
  await showFrame(page, last);
  await expectShowing(page, frames, last);
  expect(chains.find((c) => c.step === frames[last].step)?.chains).toBeGreaterThan(0);
  await keepPage(page, testInfo, 'last-frame');

  // force chains: on, then without the particles (opaque spheres hide the chains inside them)
  const particlesOnly = await canvasShot(page);
  await page.locator('#show-force-chains').check();
  await settle(page);
  await keep(testInfo, 'force-chains-with-particles', await canvasShot(page));
  await page.locator('#chain-show-particles').uncheck();
  await settle(page);
  const chainsOnly = await canvasShot(page);
  await keep(testInfo, 'force-chains-alone', chainsOnly);
  await keepPage(page, testInfo, 'force-chains-alone-page');
  await expectPicturesDiffer(page, particlesOnly, chainsOnly, 'force chains alone vs particles alone');
  // the first frame has no chains: with the particles hidden only the boundary is left
  expect(chains[0].chains).toBe(0);
  await showFrame(page, 0);
  const noChains = await canvasShot(page);
  await keep(testInfo, 'force-chains-alone-first-frame', noChains);
  await expectPicturesDiffer(page, noChains, chainsOnly, 'the last frame\'s force chains are drawn (vs the first frame, which has none)');
  await showFrame(page, last);
  await page.locator('#chain-show-particles').check();
  await page.locator('#show-force-chains').uncheck();
  await expect.poll(async () => pixelDiff(page, await canvasShot(page), particlesOnly),
                    { message: 'unchecking #show-force-chains gives the particles-only picture back' }).toBeLessThan(0.002);
});

test('colour modes change the picture', async ({ page }, testInfo) => {
  const frames = readAnimation(ANIMATION());
  await openViewer(page);
  await loadFiles(page, [ANIMATION()], frames.length);
  await showFrame(page, frames.length - 1);  // moving spheres of two sizes

  const shots = {};
  for (const mode of ['speed', 'diameter', 'constant', 'part']) {
    await page.locator('#colour-mode').selectOption(mode);
    await expect.poll(async () => (await state(page)).colourMode).toBe(mode);
    shots[mode] = await canvasShot(page);
    await keep(testInfo, `colour-${mode}`, shots[mode]);
  }
  // the same mode again gives the same picture, so the differences below are the modes'
  await page.locator('#colour-mode').selectOption('speed');
  const again = await canvasShot(page);
  expect(await pixelDiff(page, shots.speed, again), 'speed colouring drawn twice gives the same picture').toBeLessThan(0.002);
  for (const [a, b] of [['speed', 'diameter'], ['speed', 'constant'], ['diameter', 'constant']]) {
    await expectPicturesDiffer(page, shots[a], shots[b], `colour modes ${a} and ${b}`);
  }
  // the constant colour itself
  await page.locator('#colour-mode').selectOption('constant');
  await page.locator('#constant-colour').fill('#00ff00');
  const green = await canvasShot(page);
  await keep(testInfo, 'colour-constant-green', green);
  await expectPicturesDiffer(page, shots.constant, green, '#constant-colour set to green');
  await keepPage(page, testInfo, 'page');
});

test('the section sliders hide particles', async ({ page }, testInfo) => {
  const frames = readAnimation(ANIMATION());
  const last = frames.length - 1;
  const total = frames[last].particles;
  await openViewer(page);
  await loadFiles(page, [ANIMATION()], frames.length);
  await showFrame(page, last);

  const visible = async () => {
    const shown = await shownNumber(page, '#visible-count');
    expect((await state(page)).visible, 'state().visible equals #visible-count').toBe(shown);
    return shown;
  };
  const front0 = await page.locator('#section-front').inputValue();
  const rear0 = await page.locator('#section-rear').inputValue();
  expect(await visible(), 'all particles are visible before sectioning').toBe(total);
  const whole = await canvasShot(page);

  await setRange(page, '#section-front', 500);
  await expect.poll(visible, { message: '#section-front at 500 hides particles' }).toBeLessThan(total);
  const front = await visible();
  expect(front).toBeGreaterThan(0);
  const cut = await canvasShot(page);
  await keep(testInfo, 'section-front-500', cut);
  await expectPicturesDiffer(page, whole, cut, '#section-front at 500');

  await setRange(page, '#section-front', front0);
  await expect.poll(visible, { message: 'moving #section-front back shows all' }).toBe(total);

  await setRange(page, '#section-rear', 500);
  await expect.poll(visible, { message: '#section-rear at 500 hides particles' }).toBeLessThan(total);
  const rear = await visible();
  expect(rear).toBeGreaterThan(0);
  await keep(testInfo, 'section-rear-500', await canvasShot(page));

  // a slice: front and rear together hide at least what the front one hides alone
  await setRange(page, '#section-rear', rear0);
  await setRange(page, '#section-front', 400);
  await expect.poll(visible).toBeLessThan(total);
  const front400 = await visible();
  await setRange(page, '#section-rear', 600);
  await expect.poll(visible).toBeLessThanOrEqual(front400);
  await keep(testInfo, 'section-slice-400-600', await canvasShot(page));
  await keepPage(page, testInfo, 'page');

  await setRange(page, '#section-front', front0);
  await setRange(page, '#section-rear', rear0);
  await expect.poll(visible).toBe(total);
});

test('a malformed file gives a clear error and the page keeps working', async ({ page }, testInfo) => {
  const frames = readAnimation(ANIMATION());
  const message = page.locator('#message');
  await openViewer(page);

  // nothing loaded yet
  await loadFiles(page, [MALFORMED()]);
  await expect(message).toHaveClass(/\berror\b/);
  await expect(message).toBeVisible();
  await expect(message, 'the error names the file and the line (docs/viewer.md)').toContainText(/ANIMATION_3D\.dat: line \d+/);
  testInfo.annotations.push({ type: 'message', description: (await message.textContent()) || '' });
  await keepPage(page, testInfo, 'malformed-message');

  // the page keeps working: a good file loads
  await loadFiles(page, [ANIMATION()], frames.length);
  await pause(page);
  const shown = (await shownNumber(page, '#frame-index')) - 1;
  expect(await shownNumber(page, '#particle-count')).toBe(frames[shown].particles);
  await expect(message).not.toHaveClass(/\berror\b/);
  await keepPage(page, testInfo, 'good-file-after');

  // a malformed file leaves the run shown before untouched
  await loadFiles(page, [MALFORMED()]);
  await expect(message).toHaveClass(/\berror\b/);
  const after = await state(page);
  expect(after.frames, 'the run loaded before is kept').toBe(frames.length);
  expect(after.particles).toBe(frames[after.frameIndex].particles);
  expect(await shownNumber(page, '#frame-count')).toBe(frames.length);
  await keepPage(page, testInfo, 'malformed-over-good');
});

test('a file cut inside a frame loads up to its last complete frame', async ({ page }, testInfo) => {
  const frames = readAnimation(ANIMATION());
  const complete = readAnimation(TRUNCATED()).length - 1;  // the last header starts the cut frame
  expect(complete).toBe(6);
  await openViewer(page);
  await loadFiles(page, [TRUNCATED()], complete);
  const message = page.locator('#message');
  await expect(message).toContainText('ANIMATION_3D.dat');
  await expect(message, 'a cut file is not an error').not.toHaveClass(/\berror\b/);
  testInfo.annotations.push({ type: 'message', description: (await message.textContent()) || '' });
  await showFrame(page, complete - 1);
  expect(closeTo(await shownNumber(page, '#time'), frames[complete - 1].time)).toBe(true);
  expect(await shownNumber(page, '#particle-count')).toBe(frames[complete - 1].particles);
  await keepPage(page, testInfo, 'truncated');
});
