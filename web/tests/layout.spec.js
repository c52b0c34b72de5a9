// The page in windows of every size: on a phone the view fills the width above the panel, and
// messages show over the view whatever the panel's scroll.
import { test, expect, ANIMATION, MALFORMED, readAnimation, openViewer, loadFiles, canvasShot, keep, keepPage, pngColourCount } from './helpers.js';

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
