// Saving what the view shows: a PNG of the canvas (legacy "save picture") and a WebM video of the
// canvas while it plays (MediaRecorder on canvas.captureStream).

// MediaRecorder writes a WebM as a live stream, without its duration: players then show no length
// and cannot seek. fix-webm-duration writes the Duration element into the file's Segment Info.
import fixWebmDuration from 'fix-webm-duration';

// Offers a Blob as a download named `name`.
export function download(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

// The view as a picture: the scene drawn once more, then `decorate(context2d, width, height)`
// (optional: the legend) drawn over it. A canvas.
export function composePicture(stage, decorate = null) {
  stage.renderNow(); // preserveDrawingBuffer keeps it, but draw so the picture is current
  if (!decorate) return stage.canvas;
  const canvas = document.createElement('canvas');
  canvas.width = stage.canvas.width;
  canvas.height = stage.canvas.height;
  const g = canvas.getContext('2d');
  g.drawImage(stage.canvas, 0, 0);
  decorate(g, canvas.width, canvas.height);
  return canvas;
}

// Downloads the view (composePicture) as a PNG named `name`; resolves with the Blob.
export function savePicture(stage, name = 'dem-view.png', decorate = null) {
  const canvas = composePicture(stage, decorate);
  return new Promise((resolve, reject) => {
    canvas.toBlob((blob) => {
      if (!blob) return reject(new Error('the browser could not encode the picture'));
      download(blob, name);
      resolve(blob);
    }, 'image/png');
  });
}

// The best WebM the browser records: VP9, then VP8, then whatever WebM it has.
export function webmType() {
  if (typeof MediaRecorder === 'undefined') return null;
  for (const type of ['video/webm;codecs=vp8', 'video/webm;codecs=vp9', 'video/webm']) {
    if (MediaRecorder.isTypeSupported(type)) return type;
  }
  return null;
}

// Records the view; stop() downloads dem-run.webm. The stage draws every animation frame while a
// recording runs (a canvas stream only gets a video frame when the canvas is drawn). The video is
// of a copy of the view at the size it had when the recording began: the view itself changes size
// when the charts appear under it (a followed job's), and Chromium's recorder then stopped with
// nothing written.
export class Recorder {
  constructor(stage, onError = () => {}) {
    this.stage = stage;
    this.onError = onError;
    this.recorder = null;
  }

  get recording() {
    return this.recorder !== null;
  }

  start() {
    const type = webmType();
    const view = this.stage.canvas;
    const frame = document.createElement('canvas');
    if (!type || !frame.captureStream) throw new Error('this browser cannot record WebM video');
    frame.width = view.width - (view.width % 2); // even sizes: the encoders want them
    frame.height = view.height - (view.height % 2);
    const g = frame.getContext('2d');
    // the view scaled into the frame whole, centred, black bars where the shapes differ
    this.copy = () => {
      const scale = Math.min(frame.width / view.width, frame.height / view.height);
      const w = view.width * scale, h = view.height * scale;
      g.fillStyle = '#000';
      g.fillRect(0, 0, frame.width, frame.height);
      g.drawImage(view, (frame.width - w) / 2, (frame.height - h) / 2, w, h);
    };
    // a video frame for each drawing of the view, asked for: a slow view (software WebGL, a large
    // live run) draws about once a second, and a stream sampling at 30 fps had let the few frames
    // through to no video at all
    const stream = frame.captureStream(0);
    const track = stream.getVideoTracks()[0];
    const draw = this.copy;
    this.frames = 0; // drawings of the view recorded
    this.copy = () => {
      draw();
      track.requestFrame();
      this.frames += 1;
    };
    this.copy();
    this.stage.afterRender.push(this.copy);
    const chunks = [];
    const recorder = new MediaRecorder(stream, { mimeType: type, videoBitsPerSecond: 8e6 });
    recorder.ondataavailable = (event) => { if (event.data.size) chunks.push(event.data); };
    recorder.onerror = (event) => this.onError(new Error(`the recording failed: ${event.error ? event.error.message : 'unknown error'}`));
    this.stopped = new Promise((resolve) => {
      recorder.onstop = async () => {
        stream.getTracks().forEach((t) => t.stop());
        const milliseconds = performance.now() - started;
        if (!chunks.length) {
          // an empty file would look like a video: say why there is none instead
          this.onError(new Error(`the recording has no video: the view was drawn ${this.frames === 1 ? 'once' : `${this.frames} times`} in ` +
            `${(milliseconds / 1000).toFixed(1)} s and the browser encoded none of it (a view drawn without a graphics card, under load, ` +
            'draws rarely: record for longer); nothing was saved'));
          resolve(null);
          return;
        }
        const blob = await fixWebmDuration(new Blob(chunks, { type: 'video/webm' }), milliseconds, { logger: false });
        download(blob, 'dem-run.webm');
        resolve(blob);
      };
    });
    const started = performance.now();
    recorder.start(1000); // a chunk a second, so a long recording does not sit in one buffer
    this.recorder = recorder;
    this.stage.continuous += 1;
  }

  // Stops and downloads; resolves with the video Blob (null when the browser encoded nothing).
  stop() {
    if (!this.recorder) return Promise.resolve(null);
    this.recorder.stop();
    this.recorder = null;
    this.stage.continuous -= 1;
    this.stage.afterRender.splice(this.stage.afterRender.indexOf(this.copy), 1);
    return this.stopped;
  }
}
