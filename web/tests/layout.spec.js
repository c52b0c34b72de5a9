// The page in windows of every size: on a phone the view fills the width above the panel, and
// messages show over the view whatever the panel's scroll.
import fs from 'node:fs';
import { test, expect, serverUrl, ANIMATION, MALFORMED, readAnimation, openViewer, loadFiles, canvasShot, keep, keepPage, pngColourCount, fallingSpheres } from './helpers.js';

for (const [name, width, height] of [['phone', 390, 844], ['narrow', 700, 900], ['small laptop', 1024, 640]]) {
  test(`a ${name} window (${width} x ${height}): the view is not cropped to a strip`, async ({ page }, testInfo) => {
    await page.setViewportSize({ width, height });
    await openViewer(page);
    await loadFiles(page, [ANIMATION()], readAnimation(ANIMATION()).length);
    const view = await page.locator('#view-canvas').boundingBox();
    const panel = await page.locator('#side-panel').boundingBox();
    await keepPage(page, testInfo, `${name}-page`);
    expect(view.width, 'the view\'s width').toBeGreaterThanOrEqual(Math.min(width, 1024) * (width <= 720 ? 0.95 : 0.6));
    expect(view.height, 'the view\'s height').toBeGreaterThanOrEqual(height * 0.5);
    expect(view.x, 'the view starts in the window').toBeGreaterThanOrEqual(0);
    expect(view.y + 40, 'the view starts in the window').toBeLessThanOrEqual(height);
    if (width <= 720) {
      expect(view.y, 'on a narrow window the view is on top').toBeLessThan(panel.y);
      expect(panel.width, 'and the panel below it is the window\'s width').toBeGreaterThanOrEqual(width * 0.95);
    }
    const shot = await canvasShot(page);
    await keep(testInfo, `${name}-view`, shot);
    expect((await pngColourCount(page, shot)).colours, 'particles drawn in the view').toBeGreaterThan(8);
  });
}

test('a message shows over the view even with the panel scrolled to its end, and can be dismissed', async ({ page }, testInfo) => {
  await page.setViewportSize({ width: 1280, height: 700 });
  await openViewer(page);
  await page.locator('#side-panel').evaluate((el) => { el.scrollTop = el.scrollHeight; });
  await page.locator('#file-input').setInputFiles(MALFORMED());
  const box = page.locator('#message-box');
  await expect(box).toBeVisible();
  await expect(page.locator('#message')).toHaveClass(/error/);
  await expect(page.locator('#message')).toContainText('ANIMATION_3D.dat');
  const where = await box.boundingBox();
  const view = await page.locator('#view').boundingBox();
  expect(where.y >= 0 && where.y + where.height <= 700, `in the window: ${JSON.stringify(where)}`).toBe(true);
  expect(where.x >= view.x && where.x + where.width <= view.x + view.width, 'over the view').toBe(true);
  await keepPage(page, testInfo, 'message-over-the-view');
  await page.locator('#message-close').click();
  await expect(box).toBeHidden();
});

test('the first screen: the bundled cases and the jobs first, a hint in the empty view, sections that fold', async ({ page, request }, testInfo) => {
  // the panel at its tallest: a job list that scrolls (it had pushed the files off the screen once
  // the server had run the other tests' jobs) and a study
  for (let k = 0; k < 8; k++) await request.post(`${serverUrl()}/api/v1/jobs`, { data: fallingSpheres(`first screen ${k}`, 0.01) });
  await request.post(`${serverUrl()}/api/v1/studies`,
                     { data: { name: 'first screen', base: fallingSpheres('first screen', 0.01), parameters: [{ path: 'gravity.z', values: [-9.81] }] } });
  await page.setViewportSize({ width: 1280, height: 800 });
  await page.goto(`${serverUrl()}/`);
  await page.waitForFunction(() => window.demViewer && typeof window.demViewer.state === 'function');
  await expect(page.locator('#case-select')).toBeVisible();
  await expect.poll(() => page.locator('#case-select').evaluate((s) => s.options.length)).toBeGreaterThan(1);
  for (const id of ['#jobs', '#case-select', '#submit-case', '#file-input']) {
    const box = await page.locator(id).boundingBox();
    expect(box && box.y + box.height <= 800, `${id} on the first screen: ${JSON.stringify(box)}`).toBe(true);
  }
  await expect(page.locator('#empty-hint')).toBeVisible();
  await expect(page.locator('#empty-hint')).toContainText('Drop');
  // folded: the camera, the section and the boundary; a click on a title opens it
  for (const id of ['#group-camera', '#group-section', '#group-boundary']) {
    expect(await page.locator(id).evaluate((d) => d.open), `${id} folded`).toBe(false);
  }
  await keepPage(page, testInfo, 'first-screen');
  await expect(page.locator('#camera-fit')).toBeHidden();
  await page.locator('#group-camera > summary').click();
  await expect(page.locator('#camera-fit')).toBeVisible();
  // a run loaded: the hint goes
  await page.locator('#file-input').setInputFiles(ANIMATION());
  await expect(page.locator('#empty-hint')).toBeHidden();
});

test('a terrain shows its creases', async ({ page }, testInfo) => {
  // a roof: two slopes meeting at a ridge along y at x = 0, z = 10
  const dir = testInfo.outputPath('roof');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/roof.dat`, '6 4\n-20 -20 0\n0 -20 10\n20 -20 0\n-20 20 0\n0 20 10\n20 20 0\n1 2 5\n1 5 4\n2 3 6\n2 6 5\n');
  await openViewer(page);
  await page.locator('#file-input').setInputFiles(`${dir}/roof.dat`);
  await expect(page.locator('#message')).toContainText('mesh of 6 vertices and 4 triangles');
  const edges = await page.evaluate(() => {
    const b = window.demViewer.viewer.boundary;
    return b.fixedEdges.geometry.attributes.position.count / 2;
  });
  expect(edges, 'the rim (6 segments) and the ridge (1)').toBe(7);
  await keep(testInfo, 'roof', await canvasShot(page));
});
