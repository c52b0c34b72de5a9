// Milliseconds to draw one frame of N spheres in the viewer, in headless Chromium with its software
// WebGL (SwiftShader): a relative figure only (a laptop GPU is many times faster). Draws with the
// camera turning a little each time, and reads one pixel back after each draw so that the GPU work
// is counted, not just queued.
// usage: node fps.mjs URL FILE   (URL: the viewer page, with ?impostorsAbove=N to choose the way)
import { existsSync } from 'node:fs';
import { createRequire } from 'node:module';

// playwright-core is web/'s (npm, pinned by its lockfile)
const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { chromium } = require('playwright-core');

const [url, file] = process.argv.slice(2);
const browser = await chromium.launch({
  // the full chromium the docs' figures were measured with, else the tests' headless shell
  executablePath: process.env.CHROMIUM || (existsSync('/usr/bin/chromium') ? '/usr/bin/chromium' : '/usr/bin/chromium-headless-shell'),
  args: ['--no-sandbox', '--use-gl=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});
const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
await page.goto(url);
await page.setInputFiles('#file-input', file);
await page.waitForFunction(() => window.demViewer.state().frames >= 2, null, { timeout: 600000 });
const result = await page.evaluate(() => {
  const stage = window.demViewer.viewer.stage;
  const gl = stage.renderer.getContext();
  const pixel = new Uint8Array(4);
  const draw = () => {
    stage.controls.rotateLeft?.(0.01);
    stage.camera.position.applyAxisAngle({ x: 0, y: 0, z: 1, isVector3: true }, 0.01);
    stage.camera.lookAt(stage.center);
    stage.renderNow();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  };
  draw();  // the first draw compiles the shaders
  const count = 10;
  const start = performance.now();
  for (let k = 0; k < count; ++k) draw();
  const ms = (performance.now() - start) / count;
  return { ms, particles: window.demViewer.state().particles };
});
console.log(JSON.stringify(result));
await browser.close();
