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
  for (const type of ['video/webm;codecs=vp9', 'video/webm;codecs=vp8', 'video/webm']) {
    if (MediaRecorder.isTypeSupported(type)) return type;
  }
  return null;
}

// Records the canvas; stop() downloads dem-run.webm. The stage draws every animation frame while a
// recording runs (a canvas stream only gets a video frame when the canvas is drawn).
export class Recorder {
  constructor(stage) {
    this.stage = stage;
    this.recorder = null;
  }

  get recording() {
    return this.recorder !== null;
  }

  start() {
    const type = webmType();
    if (!type || !this.stage.canvas.captureStream) throw new Error('this browser cannot record WebM video');
    const stream = this.stage.canvas.captureStream(30);
    const chunks = [];
    const recorder = new MediaRecorder(stream, { mimeType: type, videoBitsPerSecond: 8e6 });
    recorder.ondataavailable = (event) => { if (event.data.size) chunks.push(event.data); };
    this.stopped = new Promise((resolve) => {
      recorder.onstop = async () => {
        stream.getTracks().forEach((t) => t.stop());
        const milliseconds = performance.now() - started;
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

  // Stops and downloads; resolves with the video Blob.
  stop() {
    if (!this.recorder) return Promise.resolve(null);
    this.recorder.stop();
    this.recorder = null;
    this.stage.continuous -= 1;
    return this.stopped;
  }
}
