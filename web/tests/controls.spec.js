// Small behaviours of the side panel: Help closes with Escape, counts read "1 frame", Part and
// Constant modes show no rainbow scale, a chain naming a particle the frame lacks is reported, and
// showing force chains makes opaque particles translucent.
import fs from 'node:fs';
import { test, expect, ANIMATION, FORCE_CHAINS, readAnimation, openViewer, loadFiles, showFrame, settle, serverUrl } from './helpers.js';

// One frame of two particles, and force chains naming a third that is not in it.
function writeOneFrame(dir) {
  const particle = (id, x) => `${id} ${x} 0 0 2 0 0 0 1 0 0 0 ${id}`;
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`,
                   ['3DA:', '-5 5 -5 5 -5 5', '0 0 0 0', '0', '7 2 0', particle(1, -1), particle(2, 1), ''].join('\n'));
  fs.writeFileSync(`${dir}/ForceChain_3D.dat`, ['3DF: 7 2', '1 0 2 10 0', '2 1 5 20 0', ''].join('\n'));
  return [`${dir}/ANIMATION_3D.dat`, `${dir}/ForceChain_3D.dat`];
}

test('Escape closes Help', async ({ page }) => {
  await openViewer(page);
  await page.locator('#help-button').click();
  await expect(page.locator('#help-panel')).toBeVisible();
  await page.keyboard.press('Escape');
  await expect(page.locator('#help-panel')).toBeHidden();
  await expect(page.locator('#help-button')).toHaveAttribute('aria-expanded', 'false');
});

test('a one-frame file, and a chain to a particle the frame does not have', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, writeOneFrame(testInfo.outputPath('one')), 1);
  await expect(page.locator('#message')).toContainText('ANIMATION_3D.dat: 1 frame of 2 particles');
  await expect(page.locator('#message')).toContainText('1 frame of force chains');
  await expect(page.locator('#message')).not.toContainText('1 frames');
  await page.locator('#show-force-chains').check();
  await expect(page.locator('#chain-unknown')).toBeVisible();
  await expect(page.locator('#chain-unknown')).toContainText('1 chain of this frame not drawn');
  await expect(page.locator('#chain-unknown')).toContainText('id 5');
  // the scale's top is the strongest chain drawn (10 N), not the 20 N one to the missing particle
  await expect(page.locator('#chain-max')).toHaveText('10');
  await page.locator('#show-force-chains').uncheck();
  await expect(page.locator('#chain-unknown')).toBeHidden();
});

test('Parts and Constant modes show no rainbow scale', async ({ page }) => {
  await openViewer(page);
  await loadFiles(page, [ANIMATION()], readAnimation(ANIMATION()).length);
  const bar = page.locator('#colour-bar');
  const looks = () => bar.evaluate((el) => ({ shown: el.offsetParent !== null, background: getComputedStyle(el).backgroundImage,
                                              colour: getComputedStyle(el).backgroundColor, inactive: el.classList.contains('inactive') }));
  const speed = await looks();
  expect(speed.shown && speed.background.includes('gradient') && !speed.inactive, JSON.stringify(speed)).toBe(true);
  await page.locator('#colour-mode').selectOption('parts');
  expect((await looks()).shown, 'Parts mode (a colour each): no bar').toBe(false);
  await page.locator('#colour-mode').selectOption('constant');
  const constant = await looks();
  expect(constant.shown && constant.background === 'none' && !constant.inactive, JSON.stringify(constant)).toBe(true);
  expect(constant.colour).toBe('rgb(46, 139, 87)');  // #2e8b57, the constant colour's default
});

test('showing force chains makes the particles translucent, unless an opacity was chosen', async ({ page }, testInfo) => {
  await openViewer(page);
  await loadFiles(page, [ANIMATION(), FORCE_CHAINS()], readAnimation(ANIMATION()).length);
  await showFrame(page, readAnimation(ANIMATION()).length - 1);
  const opacity = () => page.evaluate(() => window.demViewer.viewer.particles.opacity);
  expect(await opacity()).toBe(1);
  await page.locator('#show-force-chains').check();
  await settle(page);
  expect(await opacity(), 'chains on').toBeLessThan(0.5);
  expect(Number(await page.locator('#particle-opacity').inputValue())).toBeLessThan(50);
  await page.locator('#show-force-chains').uncheck();
  expect(await opacity(), 'chains off again').toBe(1);
  // chains on, then a run with none: nothing to see through, the particles opaque again
  await page.locator('#show-force-chains').check();
  expect(await opacity()).toBeLessThan(0.5);
  await loadFiles(page, writeOneFrame(testInfo.outputPath('one')).slice(0, 1), 1);
  expect(await opacity(), 'a run without chains').toBe(1);
  expect(Number(await page.locator('#particle-opacity').inputValue())).toBe(100);
  await page.locator('#show-force-chains').uncheck();
  await loadFiles(page, [ANIMATION(), FORCE_CHAINS()], readAnimation(ANIMATION()).length);
  await showFrame(page, readAnimation(ANIMATION()).length - 1);
  // the user's own opacity is kept
  await page.locator('#particle-opacity').evaluate((el) => { el.value = '80'; el.dispatchEvent(new Event('input', { bubbles: true })); });
  await page.locator('#show-force-chains').check();
  expect(await opacity()).toBeCloseTo(0.8, 5);
});

test('counts of one read in the singular everywhere', async ({ page }, testInfo) => {
  const dir = testInfo.outputPath('singular');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, ['3DA:', '-5 5 -5 5 -5 5', '0 0 0 0', '0', '7 1 0', '1 0 0 0 2 0 0 0 0 0 0 0 1', ''].join('\n'));
  fs.writeFileSync(`${dir}/one_triangle.dat`, '3 1\n0 0 0\n1 0 0\n0 1 0\n1 2 3\n');
  await openViewer(page);
  await loadFiles(page, [`${dir}/ANIMATION_3D.dat`, `${dir}/one_triangle.dat`], 1);
  await expect(page.locator('#message')).toContainText('1 frame of 1 particle');
  await expect(page.locator('#message')).toContainText('mesh of 3 vertices and 1 triangle');
  await expect(page.locator('#message')).not.toContainText(/\b1 (particles|triangles|frames)\b/);
  await page.locator('#colour-mode').selectOption('parts');
  await expect(page.locator('#colour-label')).toHaveText('Parts, a colour each (1 part)');
});

test('a particle id of 2,147,483,647 does not freeze the page', async ({ page }, testInfo) => {
  const dir = testInfo.outputPath('huge-id');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, ['3DA:', '-5 5 -5 5 -5 5', '0 0 0 0', '0', '7 2 0',
    '1 -1 0 0 2 0 0 0 1 0 0 0 1', '2147483647 1 0 0 2 0 0 0 1 0 0 0 2', ''].join('\n'));
  fs.writeFileSync(`${dir}/ForceChain_3D.dat`, '3DF: 7 2\n1 0 2147483647 10 0\n1 0 5 10 0\n');
  await openViewer(page);
  const started = Date.now();
  await loadFiles(page, [`${dir}/ANIMATION_3D.dat`, `${dir}/ForceChain_3D.dat`], 1);
  await page.locator('#show-force-chains').check({ timeout: 10_000 });
  await expect(page.locator('#chain-unknown')).toContainText('1 chain of this frame not drawn', { timeout: 10_000 });
  expect(Date.now() - started, 'ms to open the files and show the chains').toBeLessThan(10_000);
  expect(await page.evaluate(() => window.demViewer.viewer.chains.drawn), 'the chain to particle 2147483647').toBe(1);
});

test('messages say what was loaded: the file names in the saved caption, particle counts that vary', async ({ page }, testInfo) => {
  const dir = testInfo.outputPath('vary');
  fs.mkdirSync(dir, { recursive: true });
  const frame = (step, n) => ['3DA:', '-9 9 -9 9 -9 9', '0 0 0 0', '0', `${step} ${n} 0`,
    ...Array.from({ length: n }, (_, k) => `${k + 1} ${k} 0 0 1 0 0 0 0 0 0 0 1`)].join('\n');
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, `${frame(1, 3)}\n${frame(2, 6)}\n${frame(3, 2)}\n`);
  await openViewer(page);
  await loadFiles(page, [`${dir}/ANIMATION_3D.dat`], 3);
  await expect(page.locator('#message')).toContainText('3 frames of 2 to 6 particles');
  expect(await page.evaluate(() => window.demViewer.viewer.run.source)).toBe('ANIMATION_3D.dat');
});

test('a particle id given twice in a frame is named when the file opens', async ({ page }, testInfo) => {
  const dir = testInfo.outputPath('repeated-id');
  fs.mkdirSync(dir, { recursive: true });
  const frame = (step, ids) => ['3DA:', '-9 9 -9 9 -9 9', '0 0 0 0', '0', `${step} ${ids.length} 0`,
    ...ids.map((id, k) => `${id} ${k} 0 0 1 0 0 0 0 0 0 0 1`)].join('\n');
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, `${frame(10, [1, 2, 3])}\n${frame(20, [1, 3, 2, 3])}\n${frame(30, [1, 3, 3])}\n`);
  await openViewer(page);
  await loadFiles(page, [`${dir}/ANIMATION_3D.dat`], 3);
  await expect(page.locator('#message')).toContainText('particle id 3 is given twice at step 20 (and in 1 more frame)');
  await expect(page.locator('#message')).toContainText('force chains and the probe take the last particle of an id');
});

test('a ?job= that is not a job number is named', async ({ page }) => {
  // 0x2 opened job 2 (helper-34): decimal digits only, as the REST paths
  for (const value of ['abc', '0x2']) {
    await page.goto(`${serverUrl()}/?job=${value}`);
    await expect(page.locator('#message')).toContainText(`?job=${value} in the address is not a job number`);
  }
});

test('the case form: a staged case has no duration box, and frictions that differ are not shown as one', async ({ page }) => {
  await openViewer(page);
  const select = page.locator('#case-select');
  await expect.poll(() => select.evaluate((s) => [...s.options].some((o) => o.value === 'ballast-box'))).toBe(true);
  await select.selectOption('ballast-box');
  await expect.poll(() => page.locator('#case-spec').inputValue()).toContain('"stages"');
  // before: the box took a duration, which the server refuses beside stages
  await expect(page.locator('#case-duration')).toBeDisabled();
  // before: it showed 1, the first pair's, and typing set every pair without a word
  await expect(page.locator('#case-friction')).toHaveValue('');
  await expect(page.locator('#case-friction')).toHaveAttribute('placeholder', 'varies');
  await page.locator('#case-friction').fill('0.7');
  const spec = JSON.parse(await page.locator('#case-spec').inputValue());
  // every pair, in every stage too: a stage's interactions hold from its start on (helper-34: the
  // box set the top level only, and the load stage ran with its own)
  const all = [...spec.interactions, ...spec.stages.flatMap((s) => s.interactions || [])];
  expect(all.length).toBeGreaterThan(spec.interactions.length);
  expect(all.map((i) => i.friction)).toEqual(all.map(() => 0.7));
});
