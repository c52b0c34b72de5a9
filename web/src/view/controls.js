// Wires the side panel (index.html; ids in docs/viewer.md) to the Viewer, and keeps the read-outs
// (counts, time, step, colour bar range, slider positions) in step with what is drawn.

import { barGradient, formatValue, COLOUR_MAPS, onMap, cssColour, logPosition } from './colours.js';
import { counted } from '../words.js';
import { QUANTITIES, largestParts } from './quantities.js';
import { savePicture, Recorder } from './capture.js';
import { wirePrint, timeStamp } from './print.js';

// Part mode lists this many of the frame's largest parts.
const PARTS_LISTED = 5;

const $ = (id) => document.getElementById(id);

function formatTime(t) {
  return Number.isFinite(t) ? String(Number(t.toPrecision(6))) : '-';
}

export function wireControls(viewer) {
  const stage = viewer.stage;
  const on = (id, event, handler) => $(id).addEventListener(event, handler);
  const number = (id) => Number($(id).value);

  // Display
  on('background-colour', 'input', () => stage.setBackground($('background-colour').value));
  stage.setBackground($('background-colour').value);
  on('colour-mode', 'change', () => {
    const s = viewer.settings;
    s.colourMode = $('colour-mode').value;
    if (s.colourRangeMode === 'manual') {
      // a hand-set range belongs to the quantity it was set for: start the new one at its run's range
      s.colourRangeManual = [...(viewer.colourRange('run') || [0, 1])];
      fillRangeInputs(viewer, true);
    }
    viewer.set({});
  });
  on('colour-map', 'change', () => viewer.set({ colourMap: $('colour-map').value }));
  on('colour-range', 'change', () => {
    const mode = $('colour-range').value;
    if (mode === 'manual') {
      // start from the range in use, so that the picture does not jump
      const current = viewer.colourRange() || [0, 1];
      viewer.settings.colourRangeManual = [...current];
      fillRangeInputs(viewer, true);
    }
    $('colour-range-inputs').hidden = mode !== 'manual';
    viewer.set({ colourRangeMode: mode });
  });
  const manualRange = () => {
    const lo = number('colour-range-min'), hi = number('colour-range-max');
    const valid = Number.isFinite(lo) && Number.isFinite(hi) && hi > lo && $('colour-range-min').value !== '' && $('colour-range-max').value !== '';
    for (const id of ['colour-range-min', 'colour-range-max']) $(id).setCustomValidity(valid ? '' : 'the range needs From < to');
    if (valid) viewer.set({ colourRangeManual: [lo, hi] });
    else viewer.message(`Colour range not changed: it needs From < to (got ${$('colour-range-min').value || 'nothing'} and ${$('colour-range-max').value || 'nothing'})`, true);
  };
  on('colour-range-min', 'change', manualRange);
  on('colour-range-max', 'change', manualRange);
  on('constant-colour', 'input', () => viewer.set({ constantColour: $('constant-colour').value }));
  viewer.settings.constantColour = $('constant-colour').value;
  $('colour-bar').style.background = barGradient();

  // Light onto an axis
  for (const axis of ['x', 'y', 'z']) {
    on(`light-${axis}`, 'click', () => {
      stage.placeLight(axis);
      for (const a of ['x', 'y', 'z']) $(`light-${a}`).setAttribute('aria-pressed', String(a === axis));
    });
  }

  // Section: along an axis, or along the camera's direction when chosen (a plane through the view)
  on('section-axis', 'change', () => {
    const choice = $('section-axis').value;
    viewer.set({ sectionAxis: { x: [1, 0, 0], y: [0, 1, 0], z: [0, 0, 1] }[choice] || stage.viewDirection() });
  });
  // the two sliders never cross (Front stays left of Rear)
  on('section-front', 'input', () => {
    if (number('section-front') > number('section-rear')) $('section-front').value = $('section-rear').value;
    viewer.set({ sectionFront: number('section-front') });
  });
  on('section-rear', 'input', () => {
    if (number('section-rear') < number('section-front')) $('section-rear').value = $('section-front').value;
    viewer.set({ sectionRear: number('section-rear') });
  });

  // Force chains (the particles turn translucent while chains are drawn: Viewer.redraw)
  on('show-force-chains', 'change', () => {
    viewer.set({ showChains: $('show-force-chains').checked });
    const frames = viewer.run ? viewer.run.frames : [];
    if ($('show-force-chains').checked && !viewer.live && !frames.some((f) => f.forceChains)) {
      viewer.message('No force chains loaded: open ForceChain_3D.dat as well (or a run written with forceChains on).');
    }
  });
  on('chain-thickness', 'input', () => viewer.set({ chainThickness: number('chain-thickness') }));
  on('chain-show-particles', 'change', () => viewer.set({ chainShowParticles: $('chain-show-particles').checked }));
  on('particle-opacity', 'input', () => {
    viewer.settings.opacityChosen = true;
    viewer.particles.setOpacity(number('particle-opacity') / 100);
  });

  // Boundary
  on('show-boundary', 'change', () => viewer.boundary.setVisible($('show-boundary').checked));
  on('boundary-colour', 'input', () => viewer.boundary.setColour($('boundary-colour').value));
  on('boundary-opacity', 'input', () => viewer.boundary.setOpacity(number('boundary-opacity') / 100));
  viewer.boundary.setColour($('boundary-colour').value);
  viewer.boundary.setOpacity(number('boundary-opacity') / 100);

  // Playback
  on('play', 'click', () => viewer.playback.play());
  on('pause', 'click', () => viewer.playback.pause());
  on('step-back', 'click', () => viewer.playback.step(-1));
  on('step-forward', 'click', () => viewer.playback.step(1));
  on('speed', 'input', () => viewer.playback.setSpeed(number('speed')));
  viewer.playback.setSpeed(number('speed'));
  on('time-slider', 'input', () => {
    viewer.playback.pause();
    viewer.showFrame(number('time-slider'));
  });

  // Pictures and video
  const legend = (g, w, h) => drawLegend(viewer, g, w, h);
  on('save-picture', 'click', () => savePicture(stage, 'dem-view.png', legend).catch((e) => viewer.message(e.message, true)));
  wirePrint(stage, legend, () => pictureCaption(viewer));
  const recorder = new Recorder(stage, (e) => viewer.message(e.message, true));
  on('record', 'click', () => {
    if (recorder.recording) {
      recorder.stop();
    } else {
      try {
        recorder.start();
      } catch (e) {
        viewer.message(e.message, true);
      }
    }
    $('record').textContent = recorder.recording ? 'Stop recording' : 'Record video';
    $('record').classList.toggle('recording', recorder.recording);
    $('record').setAttribute('aria-pressed', String(recorder.recording));
  });
  viewer.recorder = recorder;

  // Help
  on('help-button', 'click', () => {
    $('help-panel').hidden = !$('help-panel').hidden;
    $('help-button').setAttribute('aria-expanded', String(!$('help-panel').hidden));
  });
  const closeHelp = () => {
    $('help-panel').hidden = true;
    $('help-button').setAttribute('aria-expanded', 'false');
  };
  on('help-close', 'click', closeHelp);
  document.addEventListener('keydown', (event) => {
    if (event.key === 'Escape' && !$('help-panel').hidden) closeHelp();
  });

  viewer.onChange(refresh);
  refresh(viewer);
}

// The read-outs after a change.
function refresh(viewer) {
  const frame = viewer.currentFrame();
  const frames = viewer.run ? viewer.run.frames.length : 0;
  $('particle-count').textContent = String(frame ? frame.count : 0);
  $('frame-index').textContent = String(frame ? viewer.frameIndex + 1 : 0);
  $('frame-count').textContent = String(frames);
  $('time').textContent = frame ? formatTime(frame.time) : '-';
  $('step').textContent = frame ? String(frame.step) : '-';
  $('visible-count').textContent = String(frame ? viewer.drawnCount : 0);
  const slider = $('time-slider');
  slider.max = String(Math.max(frames - 1, 0));
  slider.value = String(Math.max(viewer.frameIndex, 0));

  const range = viewer.colourRange();
  const mode = viewer.settings.colourMode;
  $('colour-min').textContent = range ? formatValue(range[0]) : '';
  $('colour-max').textContent = range ? formatValue(range[1]) : '';
  // no scale to read in Part and Constant modes: the constant colour alone, or no bar
  const bar = $('colour-bar');
  bar.hidden = mode === 'parts';
  bar.style.background = mode === 'constant' ? viewer.settings.constantColour : barGradient(viewer.colourMapName());
  // Part: the largest parts of the frame, with their colours
  const legend = $('part-legend');
  legend.hidden = mode !== 'part' || !frame;
  if (!legend.hidden) {
    const [lo, hi] = range || [1, 1];
    legend.innerHTML = largestParts(frame, PARTS_LISTED).map(({ part, size }) => {
      const css = cssColour(onMap(viewer.colourMapName(), logPosition(size, lo, hi), [0, 0, 0]));
      return `<li><span class="swatch" style="background:${css}"></span>part ${part}: ${counted(size, 'particle')}</li>`;
    }).join('');
  }
  bar.classList.toggle('inactive', !range && mode !== 'constant');
  const { label, unit } = colourLegend(viewer);
  $('colour-label').textContent = label;
  $('colour-unit').textContent = unit;
  // Play and Pause stay enabled (a click on the wrong one does nothing); they show the state.
  const playing = viewer.playback.playing;
  $('play').setAttribute('aria-pressed', String(playing));
  $('pause').setAttribute('aria-pressed', 'false');
  const shown = frame && viewer.chainsShown(frame);
  const chains = shown && shown.chains;
  $('chain-legend').hidden = !viewer.settings.showChains || !chains;
  $('chain-max').textContent = chains ? formatValue(viewer.chains.fnMax) : '';
  $('chain-step').textContent = shown && shown.step !== frame.step ? `; the chains drawn are the latest received, from step ${shown.step}` : '';
  if (!viewer.settings.opacityChosen) $('particle-opacity').value = String(Math.round(viewer.particles.opacity * 100));
  $('chain-run-max').textContent = formatValue(viewer.fnMax);
  const unknown = viewer.settings.showChains && chains ? viewer.chains.unknown : 0;
  $('chain-unknown').hidden = !unknown;
  $('chain-unknown').textContent = unknown
    ? `${counted(unknown, 'chain')} of this frame not drawn: ${unknown === 1 ? 'it names' : 'they name'} particles not in the frame (the first: id ${viewer.chains.firstUnknownId})`
    : '';
  document.body.classList.toggle('live', viewer.live);
  document.body.classList.toggle('has-run', Boolean(viewer.run && (viewer.run.frames.length || viewer.run.mesh)));
}

// The colour bar's label and unit for the current mode (also drawn in saved pictures).
export function colourLegend(viewer) {
  const mode = viewer.settings.colourMode;
  const quantity = QUANTITIES[mode];
  if (quantity) {
    const length = viewer.lengthUnitName() || 'file length unit';
    const label = quantity.labelFor ? quantity.labelFor(viewer.colourContext()) : quantity.label;
    return { label, unit: quantity.unit(length) };
  }
  if (mode === 'parts') return { label: `Parts, a colour each (${counted(viewer.bounds ? viewer.bounds.partMax : 0, 'part')})`, unit: '' };
  return { label: 'Constant colour', unit: '' };
}

// Puts the range in use into the From and to fields (force: even when the user typed there).
function fillRangeInputs(viewer, force) {
  let [lo, hi] = viewer.colourRange() || viewer.settings.colourRangeManual;
  if (!(hi > lo)) {
    // every value the same (or none): a range round it, since From < to
    hi = lo + (Math.abs(lo) || 1);
    viewer.settings.colourRangeManual = [lo, hi];
  }
  if (force || $('colour-range-min').value === '') $('colour-range-min').value = String(Number(lo.toPrecision(6)));
  if (force || $('colour-range-max').value === '') $('colour-range-max').value = String(Number(hi.toPrecision(6)));
}

// What a saved or printed picture shows, one line: source, time, step, particles ('' with no frame).
function pictureCaption(viewer) {
  const frame = viewer.currentFrame();
  if (!frame) return '';
  const source = viewer.run && viewer.run.source ? `${viewer.run.source} · ` : '';
  return `${source}t = ${formatTime(frame.time)} s · step ${frame.step} · ${counted(frame.count, 'particle')}`;
}

// The legend of a saved picture, drawn over it: the colour bar with its quantity, unit and range
// (or the Part mode's note) at the lower left, what is shown (source, time, step) at the top left,
// and when the picture was made at the top right (the axes indicator has the lower right).
function drawLegend(viewer, g, width, height) {
  const scale = Math.max(1, width / 1200);
  g.save();
  g.font = `${Math.round(13 * scale)}px sans-serif`;
  g.textBaseline = 'top';
  g.fillStyle = '#1d2733';
  const backing = (x, y, w, h) => {
    g.save();
    g.fillStyle = 'rgba(255, 255, 255, 0.85)';
    g.fillRect(x, y, w, h);
    g.restore();
  };
  const caption = pictureCaption(viewer);
  if (caption) {
    backing(4 * scale, 4 * scale, g.measureText(caption).width + 12 * scale, 22 * scale);
    g.fillText(caption, 10 * scale, 8 * scale);
  }
  const stamp = timeStamp();
  const stampWidth = g.measureText(stamp).width;
  backing(width - stampWidth - 16 * scale, 4 * scale, stampWidth + 12 * scale, 22 * scale);
  g.fillText(stamp, width - stampWidth - 10 * scale, 8 * scale);
  const { label, unit } = colourLegend(viewer);
  const range = viewer.colourRange();
  const x = 10 * scale, barW = 220 * scale, barH = 14 * scale, y = height - 52 * scale;
  const title = unit ? `${label} (${unit})` : label;
  backing(x - 6 * scale, y - 22 * scale, Math.max(barW, g.measureText(title).width) + 12 * scale, 56 * scale);
  g.fillText(title, x, y - 18 * scale);
  if (range) {
    const gradient = g.createLinearGradient(x, 0, x + barW, 0);
    for (const [t, c] of COLOUR_MAPS[viewer.colourMapName()]) gradient.addColorStop(t, cssColour(c));
    g.fillStyle = gradient;
    g.fillRect(x, y, barW, barH);
    g.strokeStyle = '#5b6775';
    g.strokeRect(x, y, barW, barH);
    g.fillStyle = '#1d2733';
    g.fillText(formatValue(range[0]), x, y + barH + 3 * scale);
    g.textAlign = 'right';
    g.fillText(formatValue(range[1]), x + barW, y + barH + 3 * scale);
  }
  g.restore();
}
