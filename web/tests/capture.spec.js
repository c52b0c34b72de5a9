// Save picture (#save-picture -> dem-view.png) and record (#record -> dem-run.webm).
import fs from 'node:fs';
import {
  test, expect, ANIMATION, readAnimation, openViewer, state, loadFiles, showFrame, viewCanvas,
  keep, keepPage, pngColourCount, fallingSpheres,
} from './helpers.js';

const PNG_SIGNATURE = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
const EBML_HEADER = Buffer.from([0x1a, 0x45, 0xdf, 0xa3]);

// Plays a WebM in a fresh page from a blob URL: its metadata, and how far it played.
async function playedVideo(context, webm) {
  const player = await context.newPage();
  await player.setContent('<body style="margin:0;background:#222"><video id="v" muted playsinline style="width:100%"></video></body>');
  const played = await player.evaluate(async (b64) => {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const video = document.getElementById('v');
    const ready = new Promise((resolve, reject) => {
      video.onloadedmetadata = resolve;
      video.onerror = () => reject(new Error(`video error ${video.error && video.error.code}: ${video.error && video.error.message}`));
    });
    video.src = URL.createObjectURL(new Blob([bytes], { type: 'video/webm' }));
    await ready;
    const result = { readyState: video.readyState, duration: video.duration, width: video.videoWidth, height: video.videoHeight };
    await video.play();
    await new Promise((resolve) => {
      const t0 = performance.now();
      const check = () => (video.currentTime > 0 || video.ended || performance.now() - t0 > 10000 ? resolve() : setTimeout(check, 50));
      check();
    });
    video.pause();
    result.currentTime = video.currentTime;
    return result;
  }, webm.toString('base64'));
  played.player = player;
  return played;
}

// Clicks #record to stop, keeps the downloaded dem-run.webm as `name`, checks it is a WebM of more
// than `minBytes`, and plays it (playedVideo).
async function stopAndPlay(page, context, testInfo, name, minBytes) {
  const [download] = await Promise.all([page.waitForEvent('download', { timeout: 60_000 }), page.locator('#record').click()]);
  expect(download.suggestedFilename()).toBe('dem-run.webm');
  const webm = fs.readFileSync(await download.path());
  fs.writeFileSync(testInfo.outputPath(name), webm);
  await testInfo.attach(name, { path: testInfo.outputPath(name), contentType: 'video/webm' });
  expect(webm.subarray(0, 4).equals(EBML_HEADER), `${name} starts with the EBML header 1A 45 DF A3`).toBe(true);
  expect(webm.length, `${name} holds more than a header`).toBeGreaterThan(minBytes);
  const played = await playedVideo(context, webm);
  testInfo.annotations.push({ type: 'video', description: JSON.stringify({ ...played, player: undefined }) });
  return played;
}

test('save picture downloads a PNG of the view', async ({ page }, testInfo) => {
  const frames = readAnimation(ANIMATION());
  await openViewer(page);
  await loadFiles(page, [ANIMATION()], frames.length);
  await showFrame(page, frames.length - 1);

  const [download] = await Promise.all([
    page.waitForEvent('download'),
    page.locator('#save-picture').click(),
  ]);
  expect(download.suggestedFilename()).toBe('dem-view.png');
  const png = fs.readFileSync(await download.path());
  expect(png.subarray(0, 8).equals(PNG_SIGNATURE), 'dem-view.png starts with the PNG signature').toBe(true);
  await keep(testInfo, 'dem-view', png);
  await keepPage(page, testInfo, 'page');

  // the picture is the view: the canvas's shape, and not blank (a WebGL canvas read after it was
  // presented without preserveDrawingBuffer comes out empty)
  const picture = await pngColourCount(page, png);
  const box = await (await viewCanvas(page)).boundingBox();
  expect(picture.width).toBeGreaterThan(0);
  expect(Math.abs(picture.width / picture.height - box.width / box.height),
         `dem-view.png is ${picture.width}x${picture.height}, the view ${box.width}x${box.height}`).toBeLessThan(0.02);
  expect(picture.colours, 'dem-view.png is not blank').toBeGreaterThan(16);
});

test('record downloads a WebM that Chromium plays', async ({ page, context }, testInfo) => {
  const frames = readAnimation(ANIMATION());
  await openViewer(page);
  await loadFiles(page, [ANIMATION()], frames.length);
  await showFrame(page, 0);

  const record = page.locator('#record');
  await page.locator('#play').click();
  await expect.poll(async () => (await state(page)).playing).toBe(true);
  await record.click();
  await page.waitForTimeout(2500);
  await keepPage(page, testInfo, 'recording');
  const played = await stopAndPlay(page, context, testInfo, 'dem-run.webm', 1000);
  expect(played.readyState, 'the video has metadata').toBeGreaterThanOrEqual(1);
  // MediaRecorder's own WebM has no duration (the player says Infinity): it must be written in
  expect(Number.isFinite(played.duration), `the video has a duration (${played.duration})`).toBe(true);
  expect(played.duration, 'the video lasts as long as it was recorded (2.5 s and the clicks)').toBeGreaterThan(2);
  expect(played.duration).toBeLessThan(30);
  expect(played.width, 'the video has frames of the view').toBeGreaterThan(0);
  expect(played.currentTime, 'the video plays').toBeGreaterThan(0);
  await keep(testInfo, 'webm-playing', await played.player.screenshot());
  await played.player.close();
});

test('print: the view as a picture with its legend, caption and time stamp, alone with the charts', async ({ page }, testInfo) => {
  const frames = readAnimation(ANIMATION());
  await openViewer(page);
  await loadFiles(page, [ANIMATION()], frames.length);
  await showFrame(page, frames.length - 1);
  // what the Print button does before the browser's print dialog (which a headless page has not)
  await page.evaluate(() => window.dispatchEvent(new Event('beforeprint')));
  await page.emulateMedia({ media: 'print' });
  await expect(page.locator('#side-panel')).toBeHidden();
  await expect(page.locator('#view')).toBeHidden();
  const picture = page.locator('#print-picture');
  await expect(picture).toBeVisible();
  await expect.poll(() => picture.evaluate((img) => img.naturalWidth), { message: 'the picture is decoded' }).toBeGreaterThan(100);
  const caption = page.locator('#print-caption');
  await expect(caption).toContainText(`step ${frames[frames.length - 1].step}`);
  await expect(caption).toContainText('ANIMATION_3D.dat');
  await expect(caption).toContainText(/printed \d{4}-\d\d-\d\d \d\d:\d\d/);
  const sheet = await page.screenshot({ fullPage: true });
  await keep(testInfo, 'print', sheet);
  expect((await pngColourCount(page, await picture.screenshot())).colours, 'the printed picture is not blank').toBeGreaterThan(16);
  const pdf = await page.pdf({ format: 'A4' });
  expect(pdf.subarray(0, 5).toString(), 'a PDF of the page').toBe('%PDF-');
});

test('recording while a job is followed live gives a video of the live view', async ({ page, context }, testInfo) => {
  test.setTimeout(240_000);
  await openViewer(page);
  await page.locator('#case-spec').fill(JSON.stringify(fallingSpheres('recorded live', 20, 0.1)));
  await page.locator('#submit-case').click();
  await expect.poll(async () => (await state(page)).frames, { message: 'live frames arrive', timeout: 120_000 }).toBeGreaterThan(1);
  const record = page.locator('#record');
  await record.click();
  // the view changes size meanwhile (the charts appear under it); a software-drawn view draws a few
  // times a second at best: wait for drawings rather than for time
  await expect.poll(() => page.evaluate(() => window.demViewer.viewer.recorder.frames), { message: 'drawings recorded', timeout: 120_000 })
    .toBeGreaterThanOrEqual(8);
  // before: an empty file, 4 recordings in 5 (the view resized under the recorder, and a recorder
  // sampling at 30 fps got nothing from a view drawn twice a second)
  const played = await stopAndPlay(page, context, testInfo, 'live.webm', 5000);
  expect(played.width, 'the video has frames of the view').toBeGreaterThan(0);
  expect(Number.isFinite(played.duration) && played.duration > 0, `a duration (${played.duration})`).toBe(true);
  await played.player.close();
  await page.locator('#live-cancel').click();
});

test('a recording the browser encoded nothing of is not saved as an empty video, and says why', async ({ page }) => {
  const frames = readAnimation(ANIMATION());
  await openViewer(page);
  await loadFiles(page, [ANIMATION()], frames.length);
  let downloads = 0;
  page.on('download', () => { downloads += 1; });
  // stopped at once: one drawing, which the encoder has not reached
  const blob = await page.evaluate(async () => {
    const recorder = window.demViewer.viewer.recorder;
    recorder.start();
    return (await recorder.stop()) === null;
  });
  expect(blob, 'no video').toBe(true);
  await expect(page.locator('#message')).toContainText('the recording has no video');
  await expect(page.locator('#message')).toContainText('nothing was saved');
  await page.waitForTimeout(500);
  expect(downloads).toBe(0);
});

test('print with nothing shown: no empty frame', async ({ page }) => {
  await openViewer(page);
  await page.evaluate(() => window.dispatchEvent(new Event('beforeprint')));
  await page.emulateMedia({ media: 'print' });
  await expect(page.locator('#print-sheet')).toBeHidden();
});
