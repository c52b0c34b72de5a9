// Force-chain tubes drawn the right way out: a tube is a closed surface seen from outside, so a
// small sphere inside it must not show. A tube whose frame is left-handed has its near half culled
// and shows its inside, and the sphere in it, as notches and "blades" along the chain.
import fs from 'node:fs';
import { test, expect, openViewer, loadFiles, canvasShot, keep, setRange, countPixels } from './helpers.js';

// One frame, three particles along x: two of D 10 at the chain's ends, one of D 4 at its middle;
// one chain between the outer two (ids 1 and 3), the frame's strongest, so its radius is the
// thickness setting's full radius (thickness 60: the largest particle's radius, 5, > the middle
// sphere's 2).
function writeTubeFixture(dir) {
  const particle = (id, x, d) => `${id} ${x} 0 0 ${d} 0 0 0 0 0 0 0 ${id}`;
  const animation = ['3DA:', '-60 60 -60 60 -60 60', '0 0 0 0', '0', '100 3 0',
                     particle(1, -50, 10), particle(2, 0, 4), particle(3, 50, 10), ''].join('\n');
  const chains = ['3DF: 100 1', '1 0 3 1000 0', ''].join('\n');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(`${dir}/ANIMATION_3D.dat`, animation);
  fs.writeFileSync(`${dir}/ForceChain_3D.dat`, chains);
  return [`${dir}/ANIMATION_3D.dat`, `${dir}/ForceChain_3D.dat`];
}

// Pixels of a PNG that are pure enough green (the spheres' constant colour) within the middle
// sphere's reach (the tube's radius, 5, around the scene's origin as the camera projects it), and red
// (the strongest chain's colour) anywhere.
async function countColours(page, png) {
  const [cx, cy, reach] = await page.evaluate(() => {
    const { stage } = window.demViewer.viewer;
    const canvas = stage.canvas.getBoundingClientRect();
    const at = (x, y, z) => {
      const v = stage.camera.position.clone().set(x, y, z).project(stage.camera);
      return [(v.x + 1) / 2 * canvas.width, (1 - v.y) / 2 * canvas.height];
    };
    const [x0, y0] = at(0, 0, 0);
    const up = stage.camera.up.clone().normalize().multiplyScalar(5);
    const [x1, y1] = at(up.x, up.y, up.z);
    return [x0, y0, Math.max(4, Math.hypot(x1 - x0, y1 - y0))];
  });
  const near = `Math.hypot(x - ${cx}, y - ${cy}) <= ${reach}`;
  return countPixels(page, png, {
    green: `(r, g, b, x, y) => ${near} && g > 60 && g > 2 * r && g > 2 * b`,
    red: '(r, g, b) => r > 60 && r > 2 * g && r > 2 * b',
  });
}

test('a force-chain tube hides what is inside it, from every side', async ({ page }, testInfo) => {
  const files = writeTubeFixture(testInfo.outputPath('tube'));
  await openViewer(page);
  await loadFiles(page, files, 1);
  await page.locator('#colour-mode').selectOption('constant');
  await page.locator('#constant-colour').evaluate((el) => {
    el.value = '#00ff00';
    el.dispatchEvent(new Event('input', { bubbles: true }));
  });
  await page.locator('#show-force-chains').check();
  // opaque particles (showing the chains makes them translucent until the user sets an opacity)
  await page.locator('#particle-opacity').evaluate((el) => {
    el.value = '100';
    el.dispatchEvent(new Event('input', { bubbles: true }));
  });
  await setRange(page, '#chain-thickness', 60);
  const shot = await canvasShot(page);
  await keep(testInfo, 'tube', shot);
  const seen = await countColours(page, shot);
  expect(seen.red, 'the chain is drawn').toBeGreaterThan(500);
  expect(seen.green, 'green pixels of the sphere inside the tube').toBe(0);
  // around the chain: from above, from the side and from below, each view must hide the sphere
  for (const [name, from] of [['above', [0, 0, 1]], ['side', [0, -1, 0.01]], ['below', [0.3, 0.2, -1]]]) {
    await page.evaluate((dir) => {
      const stage = window.demViewer.viewer.stage;
      const d = Math.hypot(...dir);
      const far = stage.camera.position.distanceTo(stage.center);
      stage.camera.position.set(stage.center.x + (dir[0] / d) * far, stage.center.y + (dir[1] / d) * far,
                                stage.center.z + (dir[2] / d) * far);
      stage.controls.update();
      stage.requestRender();
    }, from);
    const view = await canvasShot(page);
    await keep(testInfo, `tube-from-${name}`, view);
    const c = await countColours(page, view);
    expect(c.red, `the chain seen from ${name}`).toBeGreaterThan(500);
    expect(c.green, `green pixels of the sphere inside the tube, seen from ${name}`).toBe(0);
  }
});

test('a force-chain tube is closed at its ends: seen end-on it is a disc, not a ring', async ({ page }, testInfo) => {
  const files = writeTubeFixture(testInfo.outputPath('tube'));
  await openViewer(page);
  await loadFiles(page, files, 1);
  await page.locator('#show-force-chains').check();
  await page.locator('#chain-show-particles').uncheck();
  await setRange(page, '#chain-thickness', 100);
  // from beyond the chain's end at x = 50, looking back along it a little askew
  await page.evaluate(() => {
    const stage = window.demViewer.viewer.stage;
    stage.camera.position.set(120, 3, 2);
    stage.controls.target.set(0, 0, 0);
    stage.controls.update();
    stage.requestRender();
  });
  const shot = await canvasShot(page);
  await keep(testInfo, 'tube-end-on', shot);
  const [x, y] = await page.evaluate(() => {
    const { stage } = window.demViewer.viewer;
    const v = stage.camera.position.clone().set(50, 0, 0).project(stage.camera);
    const rect = stage.canvas.getBoundingClientRect();
    return [Math.round((v.x + 1) / 2 * rect.width), Math.round((1 - v.y) / 2 * rect.height)];
  });
  // the pixels round the end's centre: white background through an open end, the cap's red otherwise
  const { white: centre } = await countPixels(page, shot, { white: '(r, g, b) => r > 240 && g > 240 && b > 240' },
                                              { x: x - 3, y: y - 3, width: 7, height: 7 });
  expect(centre, 'background pixels seen through the end of the tube').toBe(0);
});
