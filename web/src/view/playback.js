// Playback of the run's frames: play, pause, step, and a speed in frames a second (the legacy
// "Timestep" slider set the same thing the other way round). Driven by requestAnimationFrame so
// it stops by itself when the tab is hidden.

export class Playback {
  constructor(viewer) {
    this.viewer = viewer;
    this.playing = false;
    this.framesPerSecond = 10;
    this.handle = 0;
  }

  play() {
    const run = this.viewer.run;
    if (!run || run.frames.length < 2) return;
    // from the start again when played at the last frame
    if (this.viewer.frameIndex >= run.frames.length - 1) this.viewer.showFrame(0);
    this.playing = true;
    this.last = performance.now();
    this.handle = requestAnimationFrame((t) => this.tick(t));
    this.viewer.changed();
  }

  pause() {
    if (!this.playing) return;
    this.playing = false;
    cancelAnimationFrame(this.handle);
    this.viewer.changed();
  }

  step(delta) {
    this.pause();
    this.viewer.showFrame(this.viewer.frameIndex + delta);
  }

  setSpeed(framesPerSecond) {
    if (Number.isFinite(framesPerSecond) && framesPerSecond > 0) this.framesPerSecond = framesPerSecond;
  }

  tick(now) {
    if (!this.playing) return;
    const frames = this.viewer.run.frames.length;
    const advance = Math.floor(((now - this.last) / 1000) * this.framesPerSecond);
    if (advance > 0) {
      this.last += (advance / this.framesPerSecond) * 1000;
      const next = this.viewer.frameIndex + advance;
      // A live run keeps growing: playing reaches the newest frame and then follows it.
      if (next >= frames - 1 && !this.viewer.live) {
        this.viewer.showFrame(frames - 1);
        this.pause();
        return;
      }
      this.viewer.showFrame(Math.min(next, frames - 1));
    }
    this.handle = requestAnimationFrame((t) => this.tick(t));
  }
}
