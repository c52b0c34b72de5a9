// Time-series charts of a job drawn on 2D canvases (no chart library), in #charts:
//   kinetic-energy   kinetic energy (J) over time: live frames' scalars, or ANIMATION_3D.dat's
//   plate-force      loading-plate force (N) over time: Force_Displacement.dat
//   plate-displacement  loading-plate displacement (file length unit) over time: Force_Displacement.dat
//   broken-bonds     broken bonds (cumulative; tension, shear) over time: Bond_Breaks.dat (or Fragments.dat)
//   largest-fragment particles in the largest fragment over time: Fragments.dat
//   fragments        number of fragments over time: Fragments.dat
// A chart is in #charts (a div.chart holding its canvas) only while it has data. Each canvas carries data-chart (its id) and data-points (the
// number of points of its first series). Click a chart to switch its y axis between linear and
// logarithmic (positive values only).

import { niceTicks, decadeTicks, tickLabels } from './ticks.js';
import { download } from '../view/capture.js';

// A live series keeps at most this many points: when full, every other point is dropped.
const LIVE_POINTS = 10000;

// Tableau's ten: distinct for the runs of a study overlaid, the first five for a job's series.
const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f', '#bcbd22', '#17becf'];

const DEFINITIONS = [
  { id: 'kinetic-energy', title: 'Kinetic energy', y: 'kinetic energy (J)', series: ['kinetic energy'] },
  { id: 'plate-force', title: 'Loading plate force', y: 'force (N)', series: ['force'] },
  { id: 'plate-displacement', title: 'Loading plate displacement', y: 'displacement', unitKey: 'length', series: ['displacement'] },
  { id: 'broken-bonds', title: 'Broken bonds', y: 'broken bonds (count)', series: ['total', 'tension', 'shear'], steps: true },
  { id: 'largest-fragment', title: 'Largest fragment', y: 'particles (count)', series: ['largest fragment'], steps: true },
  { id: 'fragments', title: 'Fragments', y: 'fragments (count)', series: ['fragments'], steps: true },
];

// Parses the rows of a statistics file (docs/formats.md section 5): whitespace-separated reals, one
// row per line; blank lines skipped; a row with another column count (a cut last line) ends the read.
export function parseRows(text, columns) {
  const rows = [];
  const lines = text.split('\n');
  // A last line without its line end may have been cut while being written: not used.
  const complete = text.endsWith('\n') ? lines.length : lines.length - 1;
  for (let k = 0; k < complete; k++) {
    const tokens = lines[k].trim().split(/\s+/).filter(Boolean);
    if (!tokens.length) continue;
    if (tokens.length !== columns) break;
    const row = tokens.map(Number);
    if (row.some((v) => !Number.isFinite(v))) break;
    rows.push(row);
  }
  return rows;
}

// The canvas's CSS height with a legend of one line (style.css has the same).
const BASE_HEIGHT = 150;
// On screen a legend takes at most this many lines (a study of many runs: the panel lists them all).
const SCREEN_LEGEND_LINES = 3;
// A saved chart (PNG) is drawn at this many pixels a CSS pixel: sharp in a report.
const EXPORT_RATIO = 3;

// `text` cut with an ellipsis to fit `width` pixels.
function fitted(g, text, width) {
  if (g.measureText(text).width <= width) return text;
  let lo = 0, hi = text.length;
  while (lo < hi) {
    const mid = Math.ceil((lo + hi) / 2);
    if (g.measureText(`${text.slice(0, mid)}…`).width <= width) lo = mid;
    else hi = mid - 1;
  }
  return `${text.slice(0, lo)}…`;
}

// The series' names in lines no wider than `width` (a name too long for one is cut), at most
// `maxLines`: the last then ends with how many more there are. [{ entries: [{ text, colour }], width }].
function legendLines(g, series, width, maxLines = Infinity) {
  const lines = [];
  let placed = 0;
  for (const s of series) {
    const text = fitted(g, s.label || s.name, width);
    const w = g.measureText(text).width;
    const line = lines[lines.length - 1];
    if (line && line.width + 12 + w <= width) {
      line.entries.push({ text, colour: s.colour });
      line.width += 12 + w;
    } else if (lines.length < maxLines) {
      lines.push({ entries: [{ text, colour: s.colour }], width: w });
    } else {
      break;
    }
    placed += 1;
  }
  if (placed < series.length) {
    const line = lines[lines.length - 1];
    const note = () => `+${series.length - placed} more`;
    while (line.entries.length > 1 && line.width + 12 + g.measureText(note()).width > width) {
      const dropped = line.entries.pop();
      line.width -= 12 + g.measureText(dropped.text).width;
      placed -= 1;
    }
    const text = note();
    const noteWidth = g.measureText(text).width;
    if (line.width + 12 + noteWidth > width) {
      // one name on the line, too long beside the note: cut it shorter
      const last = line.entries[line.entries.length - 1];
      line.width -= g.measureText(last.text).width;
      last.text = fitted(g, last.text.replace(/…$/, ''), Math.max(0, width - line.width - 12 - noteWidth));
      line.width += g.measureText(last.text).width;
    }
    line.entries.push({ text, colour: null });
    line.width += 12 + noteWidth;
  }
  return lines;
}

// Tableau's ten for up to ten series; past ten, hues a golden angle apart (no two runs alike).
function seriesColour(k, count) {
  if (count <= COLOURS.length) return COLOURS[k];
  return `hsl(${Math.round((k * 137.508) % 360)}, 70%, 42%)`;
}

export class Chart {
  constructor(container, def, order) {
    this.container = container;
    this.order = order;
    this.def = def;
    this.setSeries(def.series);
    this.log = false;
    this.unit = '';
    this.cursor = NaN;
    this.element = document.createElement('div');
    this.element.className = 'chart';
    this.element.dataset.chart = def.id;
    this.canvas = document.createElement('canvas');
    this.canvas.dataset.chart = def.id;
    this.canvas.dataset.points = '0';
    this.canvas.title = `${def.title}: click to switch the y axis between linear and logarithmic`;
    this.canvas.addEventListener('click', () => {
      this.log = !this.log;
      this.draw();
    });
    this.element.appendChild(this.canvas);
    // export: the picture as PNG, the numbers as CSV (one row a point: series, time, value)
    const exports = document.createElement('div');
    exports.className = 'chart-export';
    for (const [kind, title] of [['PNG', 'save this chart as a picture'], ['CSV', 'save this chart\'s numbers']]) {
      const button = document.createElement('button');
      button.type = 'button';
      button.textContent = kind;
      button.title = title;
      button.dataset.export = kind.toLowerCase();
      button.addEventListener('click', (event) => {
        event.stopPropagation();
        if (kind === 'PNG') this.picture().toBlob((blob) => blob && download(blob, `${def.id}.png`), 'image/png');
        else download(new Blob([this.csv()], { type: 'text/csv' }), `${def.id}.csv`);
      });
      exports.appendChild(button);
    }
    this.element.appendChild(exports);
    this.element.dataset.order = String(order);
    // Attached to the container only while it has data (#charts stays :empty without any).
  }

  // The series by name, each empty (a study's runs).
  // `labels` (optional): shorter names for the legend drawn in the chart (a study's values alone).
  setSeries(names, labels = names) {
    this.series = names.map((name, k) => ({ name, label: labels[k], colour: seriesColour(k, names.length), x: [], y: [] }));
  }

  points() {
    return this.series.length ? this.series[0].x.length : 0;
  }

  // The chart's numbers: a header naming the columns and units, then a row a point, in full precision.
  csv() {
    const quote = (text) => `"${text.replace(/"/g, '""')}"`; // RFC 4180
    const rows = [`series,time (s),${quote(this.yLabel())}`];
    for (const s of this.series) {
      for (let k = 0; k < s.x.length; k++) rows.push(`${quote(s.name)},${s.x[k]},${s.y[k]}`);
    }
    return `${rows.join('\r\n')}\r\n`;
  }

  hasData() {
    return this.series.some((s) => s.x.length > 0);
  }

  clear() {
    for (const s of this.series) {
      s.x = [];
      s.y = [];
    }
    this.update();
  }

  set(seriesIndex, x, y) {
    const s = this.series[seriesIndex];
    s.x = Array.from(x);
    s.y = Array.from(y);
    this.update();
  }

  add(seriesIndex, x, y) {
    const s = this.series[seriesIndex];
    if (!Number.isFinite(x) || !Number.isFinite(y)) return;
    // Live frames may repeat or go back (a reconnect, a resumed job): keep x increasing.
    while (s.x.length && s.x[s.x.length - 1] >= x) {
      s.x.pop();
      s.y.pop();
    }
    if (s.x.length >= LIVE_POINTS) {
      // halve the resolution rather than grow forever (a long job followed for hours)
      s.x = s.x.filter((_, k) => k % 2 === 0);
      s.y = s.y.filter((_, k) => k % 2 === 0);
    }
    s.x.push(x);
    s.y.push(y);
    this.update();
  }

  update() {
    this.canvas.dataset.points = String(this.points());
    const show = this.hasData();
    if (show && !this.element.isConnected) {
      const after = Array.from(this.container.children).find((el) => Number(el.dataset.order) > this.order);
      this.container.insertBefore(this.element, after || null);
    } else if (!show && this.element.parentNode) {
      this.element.remove();
    }
  }

  // Draws on the page's canvas, at the screen's pixel ratio; a legend of many series is cut to a
  // few lines, and the canvas grows to the lines it has.
  draw() {
    if (!this.element.isConnected) return;
    const canvas = this.canvas;
    const ratio = (typeof window !== 'undefined' && window.devicePixelRatio) || 1;
    const lines = this.render(canvas, ratio, canvas.clientWidth || 320, canvas.clientHeight || BASE_HEIGHT, SCREEN_LEGEND_LINES);
    const wanted = `${BASE_HEIGHT + 13 * Math.max(0, lines - 1)}px`;
    if (canvas.style.height !== wanted) canvas.style.height = wanted; // the next drawing has its size
  }

  // The chart as a picture to save: EXPORT_RATIO pixels a CSS pixel, the whole legend.
  picture() {
    const canvas = document.createElement('canvas');
    canvas.style.color = getComputedStyle(this.canvas).color;
    const width = this.canvas.clientWidth || 320;
    const probe = this.render(canvas, 1, width, BASE_HEIGHT, Infinity); // how many legend lines
    this.render(canvas, EXPORT_RATIO, width, BASE_HEIGHT + 13 * Math.max(0, probe - 1), Infinity, this.canvas);
    return canvas;
  }

  // Draws the chart on `canvas` at `cssWidth` x `cssHeight` CSS pixels, `ratio` pixels each, with at
  // most `maxLegendLines` of legend. Returns the number of legend lines below the title (1 when the
  // legend sits beside it or there is none). `inkFrom`: the element whose CSS colour is the ink.
  render(canvas, ratio, cssWidth, cssHeight, maxLegendLines, inkFrom = canvas) {
    const width = Math.round(cssWidth * ratio);
    const height = Math.round(cssHeight * ratio);
    if (canvas.width !== width) canvas.width = width;
    if (canvas.height !== height) canvas.height = height;
    const g = canvas.getContext('2d');
    if (!g) return 1;
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, cssWidth, cssHeight);
    const style = typeof getComputedStyle === 'function' && inkFrom.isConnected ? getComputedStyle(inkFrom) : null;
    const ink = (style && style.color) || '#222';
    g.fillStyle = ink;
    g.strokeStyle = ink;
    g.font = '11px sans-serif';

    const title = `${this.def.title}${this.log ? ' (log scale)' : ''}`;
    const shown = this.series.filter((s) => s.x.length);
    const left = 64;
    const right = 12;
    // The legend (more than one series with data, or a study's one) goes right of the title when it
    // fits there, else on lines of its own below it.
    const wantsLegend = shown.length > 1 || (this.def.legend === 'always' && shown.length === 1);
    const legend = wantsLegend ? legendLines(g, shown, cssWidth - left - right, maxLegendLines) : [];
    const legendBeside = legend.length === 1 && g.measureText(title).width + 16 + legend[0].width <= cssWidth - left - right;
    const top = legend.length && !legendBeside ? 18 + 13 * legend.length : 20;
    const bottom = 32;
    const plotW = Math.max(10, cssWidth - left - right);
    const plotH = Math.max(10, cssHeight - top - bottom);
    const legendLinesBelow = legendBeside ? 1 : Math.max(1, legend.length);

    // Ranges over every series.
    const useLog = this.log;
    let xMin = Infinity, xMax = -Infinity, yMin = Infinity, yMax = -Infinity;
    for (const s of this.series) {
      for (let k = 0; k < s.x.length; k++) {
        // the time axis is the same on a log scale: it lines up with the charts beside it
        if (s.x[k] < xMin) xMin = s.x[k];
        if (s.x[k] > xMax) xMax = s.x[k];
        const y = s.y[k];
        if (useLog && !(y > 0)) continue;
        if (y < yMin) yMin = y;
        if (y > yMax) yMax = y;
      }
    }
    g.textAlign = 'left';
    g.textBaseline = 'top';
    g.fillText(title, left, 3);
    if (!(xMin <= xMax) || !(yMin <= yMax)) {
      g.fillText(useLog ? 'no positive values' : 'no data', left + 4, top + plotH / 2);
      return legendLinesBelow;
    }
    // Round ticks, the axes widened to them (ticks.js).
    const xAxis = niceTicks(xMin, xMax, Math.max(2, Math.floor(plotW / 70)));
    xMin = xAxis.min;
    xMax = xAxis.max;
    let ty = (v) => v;
    let yAxis;
    if (useLog) {
      ty = Math.log10;
      yAxis = decadeTicks(yMin, yMax);
    } else {
      yAxis = niceTicks(yMin, yMax, Math.max(2, Math.floor(plotH / 30)));
    }
    yMin = yAxis.min;
    yMax = yAxis.max;
    this.axes = { x: xAxis.ticks, y: yAxis.ticks }; // what the last picture labelled (for tests)
    const ly0 = ty(yMin), ly1 = ty(yMax);
    const px = (x) => left + ((x - xMin) / (xMax - xMin)) * plotW;
    const py = (y) => top + plotH - ((ty(y) - ly0) / (ly1 - ly0)) * plotH;

    // Axes.
    g.lineWidth = 1;
    g.globalAlpha = 0.8;
    g.beginPath();
    g.moveTo(left, top);
    g.lineTo(left, top + plotH);
    g.lineTo(left + plotW, top + plotH);
    g.stroke();
    // Ticks at round values.
    g.beginPath();
    for (const t of xAxis.ticks) {
      g.moveTo(px(t), top + plotH);
      g.lineTo(px(t), top + plotH + 4);
    }
    for (const t of yAxis.ticks) {
      g.moveTo(left - 4, py(t));
      g.lineTo(left, py(t));
    }
    g.stroke();
    g.globalAlpha = 1;
    g.textBaseline = 'top';
    g.textAlign = 'center';
    const xLabels = tickLabels(xAxis.ticks);
    // a label at the right end is kept inside the picture
    xAxis.ticks.forEach((t, k) => g.fillText(xLabels[k], Math.min(px(t), cssWidth - 1 - g.measureText(xLabels[k]).width / 2), top + plotH + 5));
    g.textAlign = 'right';
    g.textBaseline = 'middle';
    const yLabels = tickLabels(yAxis.ticks, useLog);
    yAxis.ticks.forEach((t, k) => g.fillText(yLabels[k], left - 6, py(t)));
    // Axis labels.
    g.textAlign = 'center';
    g.textBaseline = 'bottom';
    g.fillText('time (s)', left + plotW / 2, cssHeight - 1);
    g.save();
    // centred on the plot while it fits there, else on the whole height, cut to it at most
    const yLabel = fitted(g, this.yLabel(), cssHeight - 4);
    const half = g.measureText(yLabel).width / 2;
    g.translate(12, Math.max(half + 2, Math.min(cssHeight - half - 2, top + plotH / 2)));
    g.rotate(-Math.PI / 2);
    g.textBaseline = 'middle';
    g.fillText(yLabel, 0, 0);
    g.restore();

    // Lines: at most two points (min and max) per pixel column.
    g.lineWidth = 1.5;
    for (const s of this.series) {
      if (!s.x.length) continue;
      g.strokeStyle = s.colour;
      g.fillStyle = s.colour;
      g.beginPath();
      let started = false;
      // a column's first point, its extremes, then its last: the line enters and leaves the
      // column where the data does (a count's jump is a step, not a slope from the left)
      let column = NaN, first = 0, lo = 0, hi = 0, last = 0;
      const flush = () => {
        if (Number.isNaN(column)) return;
        if (!started) {
          g.moveTo(column, first);
          started = true;
        } else g.lineTo(column, first);
        if (lo !== first) g.lineTo(column, lo);
        if (hi !== lo) g.lineTo(column, hi);
        if (last !== hi) g.lineTo(column, last);
      };
      const point = (x, y) => {
        const cx = Math.round(px(x) * 2) / 2;
        const cy = py(y);
        if (cx !== column) {
          flush();
          column = cx;
          first = lo = hi = last = cy;
        } else {
          lo = Math.min(lo, cy);
          hi = Math.max(hi, cy);
          last = cy;
        }
      };
      let previous = NaN;
      for (let k = 0; k < s.x.length; k++) {
        const y = s.y[k];
        if (useLog && !(y > 0)) continue;
        // a count sampled at times (Fragments.dat) holds its value until the next sample: a step
        if (this.def.steps && Number.isFinite(previous)) point(s.x[k], previous);
        point(s.x[k], y);
        previous = y;
      }
      flush();
      g.stroke();
      if (s.x.length === 1) {
        g.beginPath();
        g.arc(px(s.x[0]), py(s.y[0]), 2.5, 0, 2 * Math.PI);
        g.fill();
      }
    }
    // The time of the frame shown in the view.
    const cursor = this.cursor;
    if (Number.isFinite(cursor) && cursor >= xMin && cursor <= xMax) {
      g.save();
      g.strokeStyle = ink;
      g.globalAlpha = 0.5;
      g.lineWidth = 1;
      g.setLineDash([3, 3]);
      g.beginPath();
      g.moveTo(px(cursor), top);
      g.lineTo(px(cursor), top + plotH);
      g.stroke();
      g.restore();
    }

    // The legend, each line right-aligned; "+N more" in the ink.
    g.textAlign = 'right';
    g.textBaseline = 'top';
    legend.forEach((line, row) => {
      const y = legendBeside ? 3 : 16 + 13 * row;
      let x = left + plotW;
      for (let k = line.entries.length - 1; k >= 0; k--) {
        const entry = line.entries[k];
        g.fillStyle = entry.colour || ink;
        g.fillText(entry.text, x, y);
        x -= g.measureText(entry.text).width + 12;
      }
    });
    return legendLinesBelow;
  }

  yLabel() {
    return this.unit ? `${this.def.y} (${this.unit})` : this.def.y;
  }
}

// A set of charts in one container: a job's (the methods below), or a study's (studies.js). All
// methods are safe to call when #charts is missing (they do nothing).
export class Charts {
  // definitions: the charts ({ id, title, y, unitKey, series }), a job's by default.
  constructor(container, definitions = DEFINITIONS) {
    this.container = container || null;
    this.charts = new Map();
    this.pending = false;
    if (!this.container) return;
    definitions.forEach((def, k) => this.charts.set(def.id, new Chart(this.container, def, k)));
    if (typeof ResizeObserver === 'function') {
      this.resize = new ResizeObserver(() => this.redraw());
      this.resize.observe(this.container);
    } else if (typeof window !== 'undefined') {
      window.addEventListener('resize', () => this.redraw());
    }
  }

  chart(id) {
    return this.charts.get(id) || null;
  }

  hasData() {
    return [...this.charts.values()].some((c) => c.hasData());
  }

  // Forget every series (a new job).
  clear() {
    for (const c of this.charts.values()) c.clear();
    this.redraw();
  }

  // The length unit of the files ("m", "cm", "mm"; "" when unknown) for the lengths' axes.
  setLengthUnit(unit) {
    for (const c of this.charts.values()) if (c.def.unitKey === 'length') c.unit = unit || 'file length unit';
    this.redraw();
  }

  // The time (s) of the frame shown in the view: a dashed line on every chart (NaN: none).
  setCursor(time) {
    const t = Number.isFinite(time) ? time : NaN;
    let changed = false;
    for (const c of this.charts.values()) {
      if (!(c.cursor === t || (Number.isNaN(c.cursor) && Number.isNaN(t)))) changed = true;
      c.cursor = t;
    }
    if (changed) this.redraw();
  }

  // Live: one frame's kinetic energy.
  addFrame(frame) {
    const c = this.chart('kinetic-energy');
    if (!c || !frame || !frame.scalars) return;
    c.add(0, frame.time, frame.scalars.kineticEnergy);
    this.redraw();
  }

  // A finished job: the kinetic energy of ANIMATION_3D.dat's frames (their scalars), replacing the
  // live points.
  setAnimationFrames(frames) {
    const c = this.chart('kinetic-energy');
    if (!c || !frames) return;
    const x = [], y = [];
    for (const f of frames) {
      const s = f.scalars;
      if (!s) continue;
      x.push(Number.isFinite(s.time) ? s.time : f.time);
      y.push(s.kineticEnergy);
    }
    c.set(0, x, y);
    this.redraw();
  }

  // Force_Displacement.dat: time, displacement (length unit), force (N).
  setForceDisplacement(text) {
    const rows = parseRows(text, 3);
    const force = this.chart('plate-force');
    const disp = this.chart('plate-displacement');
    if (force) force.set(0, rows.map((r) => r[0]), rows.map((r) => r[2]));
    if (disp) disp.set(0, rows.map((r) => r[0]), rows.map((r) => r[1]));
    this.redraw();
    return rows.length;
  }

  // Fragments.dat: time, fragments, particles in the largest, intact bonds, broken in tension, in
  // shear. Gives the largest fragment (and the fragment count), and the broken bonds when
  // `brokenBonds` (used when there is no Bond_Breaks.dat).
  setFragments(text, { brokenBonds = true } = {}) {
    const rows = parseRows(text, 6);
    const t = rows.map((r) => r[0]);
    const largest = this.chart('largest-fragment');
    if (largest) largest.set(0, t, rows.map((r) => r[2]));
    const count = this.chart('fragments');
    if (count) count.set(0, t, rows.map((r) => r[1]));
    const broken = this.chart('broken-bonds');
    if (broken && brokenBonds) {
      broken.set(0, t, rows.map((r) => r[4] + r[5]));
      broken.set(1, t, rows.map((r) => r[4]));
      broken.set(2, t, rows.map((r) => r[5]));
    }
    this.redraw();
    return rows.length;
  }

  // Bond_Breaks.dat: one row per broken bond: time, i, j, mode (1 tension, 2 shear). Drawn as the
  // cumulative count over time. `endTime`: carries the last count to that time (the run's end).
  setBondBreaks(text, endTime) {
    const rows = parseRows(text, 4).sort((a, b) => a[0] - b[0]);
    const broken = this.chart('broken-bonds');
    if (!broken) return rows.length;
    const series = [[[], []], [[], []], [[], []]]; // total, tension, shear: [x, y]
    const counts = [0, 0, 0];
    const push = (k, t) => {
      series[k][0].push(t);
      series[k][1].push(counts[k]);
    };
    if (rows.length) for (let k = 0; k < 3; k++) push(k, Math.min(0, rows[0][0]));
    // a staircase: the count before each break, then after it, at its time
    for (const r of rows) {
      const mode = r[3] === 2 ? 2 : 1;
      push(0, r[0]);
      push(mode, r[0]);
      counts[0] += 1;
      counts[mode] += 1;
      push(0, r[0]);
      push(mode, r[0]);
    }
    if (rows.length && Number.isFinite(endTime) && endTime > rows[rows.length - 1][0]) for (let k = 0; k < 3; k++) push(k, endTime);
    for (let k = 0; k < 3; k++) broken.set(k, series[k][0], series[k][1]);
    this.redraw();
    return rows.length;
  }

  // Draws at the next animation frame (many updates a frame cost one drawing).
  redraw() {
    if (!this.container || this.pending) return;
    this.pending = true;
    const run = () => {
      this.pending = false;
      for (const c of this.charts.values()) c.draw();
    };
    if (typeof requestAnimationFrame === 'function' && !(typeof document !== 'undefined' && document.hidden)) requestAnimationFrame(run);
    else setTimeout(run, 50);
  }
}
