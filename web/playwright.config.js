// Browser tests of the viewer (web/tests/*.spec.js): Debian's chromium-headless-shell, driven by
// Playwright, against the real dem-server on loopback serving web/dist (see tests/global-setup.js).
//   cd web && npx playwright test            (after scripts/build: needs build/dem, build/dem-server, web/dist)
// Environment: DEM_BUILD_DIR (default ../build), DEM_CHROMIUM (default /usr/bin/chromium-headless-shell,
// Debian's Chromium without its browser UI; a full chromium works too, at about 4x the CPU a page).
// Each test keeps screenshots in web/test-results/<test>/ (and attaches them to the report).
import { defineConfig } from '@playwright/test';

export default defineConfig({
  testDir: './tests',
  testMatch: '*.spec.js',
  outputDir: './test-results',
  globalSetup: './tests/global-setup.js',
  // one browser at a time: the machine has 2 cores, and WebGL is software-rendered (SwiftShader)
  workers: 1,
  fullyParallel: false,
  retries: 0,
  timeout: 180_000,
  globalTimeout: 15 * 60_000,
  expect: { timeout: 30_000 },
  reporter: [['list'], ['html', { open: 'never', outputFolder: './playwright-report' }]],
  use: {
    browserName: 'chromium',
    headless: true,
    viewport: { width: 1280, height: 800 },
    acceptDownloads: true,
    actionTimeout: 30_000,
    navigationTimeout: 60_000,
    screenshot: 'on',
    trace: 'retain-on-failure',
    launchOptions: {
      executablePath: process.env.DEM_CHROMIUM || '/usr/bin/chromium-headless-shell',
      args: [
        '--no-sandbox',
        // WebGL without a GPU: SwiftShader, Chromium's software GL
        '--use-gl=angle',
        '--use-angle=swiftshader',
        '--enable-unsafe-swiftshader',
        '--ignore-gpu-blocklist',
        // MediaRecorder and <video> without user gestures
        '--autoplay-policy=no-user-gesture-required',
      ],
    },
  },
});
