// A 2D run's ANIMATION_2D.dat (docs/formats.md section 3a), written by the engine (global setup): opened as
// discs in the x-z plane, seen from the front, with the controls of 3D files; a damaged one named by its line.
import fs from 'node:fs';
import {
  test, expect, PLANAR, readAnimation, openViewer, state, shownNumber, loadFiles, showFrame, canvasShot, keep,
  keepPage, closeTo, expectPicturesDiffer, pngColourCount,
} from './helpers.js';

test('opens ANIMATION_2D.dat: its discs, frames and times, the plane seen from the front', async ({ page }, testInfo) => {
  const frames = readAnimation(PLANAR());
  expect(frames.length).toBeGreaterThanOrEqual(11);  // every 0.02 s, and the last step
  await openViewer(page);
  await loadFiles(page, [PLANAR()], frames.length);
  await expect(page.locator('#message')).toContainText(`${frames.length} frames of ${frames[0].particles} discs (2D`);
  const last = frames.length - 1;
  await showFrame(page, last);
  expect(await shownNumber(page, '#particle-count')).toBe(frames[last].particles);
  expect(await shownNumber(page, '#step')).toBe(frames[last].step);
  expect(closeTo(await shownNumber(page, '#time'), frames[last].time)).toBe(true);
  const s = await state(page);
  expect(s.planar, 'state().planar').toBe(true);
  expect(s.visible, 'every disc drawn').toBe(frames[last].particles);

  // the camera looks along +y at the plane: from -y, level with the scene's centre
  const view = await page.evaluate(() => {
    const stage = window.demViewer.viewer.stage;
    const d = stage.camera.position.clone().sub(stage.center).normalize();
    return [d.x, d.y, d.z];
  });
  expect(Math.abs(view[0]) < 1e-6 && Math.abs(view[2]) < 1e-6 && view[1] < -0.999999, `view direction ${view}`).toBe(true);

  // discs and the sloping plate's band are drawn; the first frame (discs up in the air) looks different
  const end = await canvasShot(page);
  await keep(testInfo, 'planar-last-frame', end);
  expect((await pngColourCount(page, end)).colours, 'a picture, not a blank view').toBeGreaterThan(8);
  await showFrame(page, 0);
  await expectPicturesDiffer(page, await canvasShot(page), end, 'the first and last frames of the 2D run');
  await keepPage(page, testInfo, 'planar-page');
});

test('a damaged ANIMATION_2D.dat is refused naming its line, a 3D line in it included', async ({ page }, testInfo) => {
  const lines = fs.readFileSync(PLANAR(), 'utf8').split('\n');
  // the first disc line of frame 1 given a third coordinate, as a 3D particle line would have
  const [, , plates] = lines[4].trim().split(/\s+/).map(Number);
  const nt = Number(lines[3].trim());
  const first = 5 + plates + nt;
  const cols = lines[first].split(' ');
  cols.splice(2, 0, '0.0');
  lines[first] = cols.join(' ');
  const bad = testInfo.outputPath('ANIMATION_2D.dat');
  fs.writeFileSync(bad, lines.join('\n'));
  await openViewer(page);
  await loadFiles(page, [bad]);
  const message = page.locator('#message');
  await expect(message).toHaveClass(/\berror\b/);
  await expect(message).toContainText(
    `ANIMATION_2D.dat: line ${first + 1}: expected 9 values on the disc line 1 of `);
  await expect(message).toContainText('(id x z D vx vz nc w part), found 10');
});
