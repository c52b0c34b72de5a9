// Wires the side panel (index.html; ids in docs/viewer.md) to the Viewer, and keeps the read-outs
// (counts, time, step, colour bar range, slider positions) in step with what is drawn.

import { barGradient, formatValue } from './colours.js';
import { counted } from '../words.js';
import { savePicture, Recorder } from './capture.js';

const $ = (id) => document.getElementById(id);

// The particles' opacity (%) while force chains are shown, unless the user chose one.
const CHAIN_PARTICLE_OPACITY = 30;

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
  on('colour-mode', 'change', () => viewer.set({ colourMode: $('colour-mode').value }));
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
    let axis = { x: [1, 0, 0], y: [0, 1, 0], z: [0, 0, 1] }[choice];
    if (!axis) {
      const d = stage.camera.getWorldDirection(stage.camera.position.clone());
      axis = [d.x, d.y, d.z];
    }
    viewer.set({ sectionAxis: axis });
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

  // Force chains. Opaque particles hide the chains between their centres: showing the chains makes
  // the particles translucent (the legacy T/C), and hiding them makes them opaque again, until the
  // user sets the opacity.
  let opacityChosen = false;
  on('show-force-chains', 'change', () => {
    if (!opacityChosen) {
      const opacity = $('show-force-chains').checked ? CHAIN_PARTICLE_OPACITY : 100;
      $('particle-opacity').value = String(opacity);
      viewer.particles.setOpacity(opacity / 100);
    }
    viewer.set({ showChains: $('show-force-chains').checked });
    if ($('show-force-chains').checked && !viewer.chainsByStep.size) {
      viewer.message('No force chains loaded: open ForceChain_3D.dat as well (or a run written with forceChains on).');
    }
  });
  on('chain-thickness', 'input', () => viewer.set({ chainThickness: number('chain-thickness') }));
  on('chain-show-particles', 'change', () => viewer.set({ chainShowParticles: $('chain-show-particles').checked }));
  on('particle-opacity', 'input', () => {
    opacityChosen = true;
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
  on('save-picture', 'click', () => savePicture(stage).catch((e) => viewer.message(e.message, true)));
  const recorder = new Recorder(stage);
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
  bar.hidden = mode === 'part';
  bar.style.background = mode === 'constant' ? viewer.settings.constantColour : barGradient();
  bar.classList.toggle('inactive', !range && mode !== 'constant');
  $('colour-label').textContent = {
    speed: 'Speed', diameter: 'Diameter', constant: 'Constant colour', part: `Part (${viewer.bounds ? viewer.bounds.partMax : 0} parts)`,
  }[mode];
  const unit = viewer.run && viewer.run.unit === 'm' ? 'm' : 'file length unit';
  $('colour-unit').textContent = mode === 'speed' ? `${unit}/s` : mode === 'diameter' ? unit : '';
  // Play and Pause stay enabled (a click on the wrong one does nothing); they show the state.
  const playing = viewer.playback.playing;
  $('play').setAttribute('aria-pressed', String(playing));
  $('pause').setAttribute('aria-pressed', 'false');
  const chains = frame && frame.forceChains;
  $('chain-legend').hidden = !viewer.settings.showChains || !chains;
  $('chain-max').textContent = chains && chains.stats ? formatValue(chains.stats.fnMax) : '';
  $('chain-run-max').textContent = formatValue(viewer.fnMax);
  const unknown = viewer.settings.showChains && chains ? viewer.chains.unknown : 0;
  $('chain-unknown').hidden = !unknown;
  $('chain-unknown').textContent = unknown
    ? `${counted(unknown, 'chain')} of this frame not drawn: ${unknown === 1 ? 'it names' : 'they name'} particles not in the frame (the first: id ${viewer.chains.firstUnknownId})`
    : '';
  document.body.classList.toggle('live', viewer.live);
}
