// Parameter studies (POST /api/v1/studies, docs/api.md) in #study-select: choosing one overlays
// the time series of its runs in #charts, one line a run named by its parameter values (the
// PDEM-EGD manual's figure 4.17 compares five bond strengths so; the BallastDEM manual's
// settlement curves so). The overlay is read again every few seconds while the study runs; a file
// is downloaded again only when its size changed. Choosing a job (or "none") ends the overlay.

import * as server from './server.js';
import { Charts, parseRows } from './charts.js';
import { counted } from '../words.js';
import { errorText } from './session.js';
import { unitOfJob } from './job_files.js';

const REFRESH_MS = 5000;

// What is overlaid: a column (or two added) of a statistics file (docs/formats.md section 5). The
// counts are sampled at output times: drawn as steps. Every chart has its legend, even of one run.
const OVERLAID = [
  { id: 'study-plate-displacement', title: 'Loading plate displacement', y: 'displacement', unitKey: 'length', file: 'Force_Displacement.dat', columns: 3, value: (r) => r[1] },
  { id: 'study-plate-force', title: 'Loading plate force', y: 'force (N)', file: 'Force_Displacement.dat', columns: 3, value: (r) => r[2] },
  { id: 'study-broken-bonds', title: 'Broken bonds', y: 'broken bonds (count)', file: 'Fragments.dat', columns: 6, value: (r) => r[4] + r[5], steps: true },
  { id: 'study-fragments', title: 'Fragments', y: 'fragments (count)', file: 'Fragments.dat', columns: 6, value: (r) => r[1], steps: true },
  { id: 'study-largest-fragment', title: 'Largest fragment', y: 'particles (count)', file: 'Fragments.dat', columns: 6, value: (r) => r[2], steps: true },
].map((o) => ({ ...o, legend: 'always', series: [] }));
const FILES = [...new Set(OVERLAID.map((o) => o.file))];

// A path's segments: "walls[1].load.cyclic.fMax" -> ["walls[1]", "load", "cyclic", "fMax"]; a JSON
// pointer's index joins its list: "/interactions/0/friction" -> ["interactions[0]", "friction"].
function segments(path) {
  const parts = [];
  for (const part of path.split(/[./]/).filter(Boolean)) {
    if (/^\d+$/.test(part) && parts.length) parts[parts.length - 1] += `[${part}]`;
    else parts.push(part);
  }
  return parts;
}

// Each path's shortest end that no other path ends with: ["interactions[0].friction",
// "interactions[1].friction"] stay whole, "bonds.tensileStrength" beside "walls[1].c1.z" is
// "tensileStrength".
export function shortNames(paths) {
  const parts = paths.map(segments);
  const end = (p, n) => p.slice(-n).join('.');
  return parts.map((p, i) => {
    for (let n = 1; n < p.length; n++) {
      if (parts.every((q, j) => j === i || end(q, n) !== end(p, n))) return end(p, n);
    }
    return p.join('.');
  });
}

// A value as a legend writes it: large and small numbers with an exponent (4e6), objects as JSON.
function valueText(value) {
  if (typeof value === 'number') {
    const a = Math.abs(value);
    return a !== 0 && (a >= 1e5 || a < 1e-3) ? value.toExponential().replace('e+', 'e') : String(value);
  }
  return typeof value === 'object' ? JSON.stringify(value) : String(value);
}

// Each run's line name, its parameters in the study's order ("fMax = 30"; a list of fields set
// together, "tensileStrength = shearStrength = 4e6"), and its state when it did not succeed.
export function runNames(study, { valuesOnly = false } = {}) {
  const paths = study.parameters || [];
  const fields = paths.map((p) => p.split(' = '));
  const short = shortNames(fields.flat());
  let k = 0;
  const names = fields.map((f) => f.map(() => short[k++]).join(' = '));
  return study.jobs.map((run) => {
    const values = paths.map((path, i) => (valuesOnly ? '' : `${names[i]} = `) + valueText((run.parameters || {})[path]));
    const name = values.length ? values.join(', ') : `run ${run.run}`;
    return run.state === 'succeeded' || run.state === 'running' || run.state === 'queued' ? name : `${name} (${run.state})`;
  });
}

// A study as #study-select lists it.
function optionText(study) {
  return `#${study.id} ${study.name || '(no name)'}: ${counted(study.jobs.length, 'run')}${study.finished ? '' : `, ${study.summary}`}`;
}

export class Studies {
  // container: #charts; onChosen(): a study was chosen (the panel leaves the job it showed);
  // onLeft(): the overlay was ended by choosing none (the job's charts come back).
  constructor(container, onChosen, onLeft) {
    this.select = document.getElementById('study-select');
    this.status = document.getElementById('study-status');
    this.count = document.getElementById('study-count');
    this.charts = new Charts(container, OVERLAID);
    this.container = container;
    this.legend = null; // #study-legend, at the top of #charts while a study is overlaid
    this.onChosen = onChosen;
    this.onLeft = onLeft;
    this.token = 0; // bumped by every choice: an older choice's late answers are dropped
    this.study = null; // the study overlaid
    this.sizes = new Map(); // "job/file" -> size when last read
    this.rows = new Map(); // "job/file" -> its rows
    this.select.addEventListener('change', () => this.choose(Number(this.select.value) || null));
  }

  // The server's studies into #study-select (the chosen one stays chosen).
  async refresh() {
    let studies;
    try {
      studies = await server.listStudies();
    } catch (e) {
      this.status.textContent = `Studies: ${errorText(e)}`;
      return;
    }
    const chosen = this.select.value;
    const options = [this.select.options[0]];
    for (const s of studies.slice().sort((a, b) => b.id - a.id)) {
      const option = document.createElement('option');
      option.value = String(s.id);
      option.textContent = optionText(s);
      options.push(option);
    }
    this.select.replaceChildren(...options);
    this.select.value = options.some((o) => o.value === chosen) ? chosen : '';
    // folded (the first screen keeps its room), its title saying how many there are
    this.count.textContent = studies.length ? ` (${studies.length})` : '';
    if (!studies.length && !this.study) this.status.textContent = 'No studies: submit one with `dem study --submit` or POST /api/v1/studies (docs/api.md).';
  }

  // Ends the overlay (a job was chosen): its charts go, the choice returns to none.
  clear() {
    this.token += 1;
    this.study = null;
    clearTimeout(this.timer);
    this.select.value = '';
    this.status.textContent = '';
    this.sizes.clear();
    this.rows.clear();
    for (const c of this.charts.charts.values()) {
      c.setSeries([]);
      c.update();
    }
    if (this.legend) this.legend.remove();
    this.legend = null;
  }

  // #study-legend, the first thing in #charts: which study, and every run's colour and name (a
  // chart's own legend lists a few lines of them). Printed with the charts.
  showLegend(study, runs, names) {
    if (!this.legend) {
      this.legend = document.createElement('div');
      this.legend.id = 'study-legend';
      this.legend.dataset.order = '-1';
      this.container.prepend(this.legend);
    }
    const title = document.createElement('strong');
    // the charts' legends give the values alone, in this order
    title.textContent = `Study #${study.id} ${study.name || ''}: ${(study.parameters || []).join(', ')} (the charts' legends: the values, in this order)`;
    const list = document.createElement('ol');
    const colours = this.charts.chart(OVERLAID[0].id).series.map((s) => s.colour);
    runs.forEach((run, k) => {
      const item = document.createElement('li');
      const swatch = document.createElement('span');
      swatch.className = 'swatch';
      swatch.style.background = colours[k];
      item.append(swatch, `${names[k]} · job ${run.job}`);
      list.appendChild(item);
    });
    this.legend.replaceChildren(title, list);
  }

  async choose(id) {
    this.clear();
    if (!id) {
      this.onLeft();
      return;
    }
    this.select.value = String(id);
    this.onChosen();
    const token = this.token;
    this.status.textContent = `reading study ${id}`;
    await this.read(id, token);
  }

  // Reads the study and its runs' files, draws them, and again in a while unless it has ended.
  async read(id, token) {
    let study;
    try {
      study = await server.getStudy(id);
      if (token !== this.token) return;
      if (!this.study) await this.setUnit(study);
      if (token !== this.token) return;
      this.study = study;
      const option = [...this.select.options].find((o) => o.value === String(id));
      if (option) option.textContent = optionText(study); // the list's line says what the status says
      const all = runNames(study);
      const values = runNames(study, { valuesOnly: true }); // the charts' own legends: the values alone
      const kept = study.jobs.map((run, k) => [run, all[k], values[k]]).filter(([run]) => run.job && run.state !== 'deleted');
      const runs = kept.map(([run]) => run);
      const names = kept.map(([, name]) => name);
      const labels = kept.map(([, , label]) => label);
      for (const c of this.charts.charts.values()) {
        if (c.series.length !== runs.length || c.series.some((line, k) => line.name !== names[k])) c.setSeries(names, labels);
      }
      this.showLegend(study, runs, names);
      const read = await Promise.all(runs.map((run) => this.readRun(run, token)));
      if (token !== this.token) return;
      runs.forEach((run, k) => {
        for (const c of this.charts.charts.values()) {
          const rows = this.rows.get(`${run.job}/${c.def.file}`) || [];
          c.set(k, rows.map((r) => r[0]), rows.map(c.def.value));
        }
      });
      this.charts.redraw();
      const drawn = read.filter(Boolean).length;
      const gone = study.jobs.length - runs.length;
      this.status.textContent = `${study.name || `study ${id}`}: ${study.summary}; ${drawn} of ${counted(study.jobs.length, 'run')} with time series` +
        (gone ? ` (${gone} deleted)` : '') +
        (drawn < runs.length ? '; a run without Force_Displacement.dat or Fragments.dat, or not started, has none' : '');
    } catch (e) {
      if (token === this.token) this.status.textContent = `study ${id}: ${errorText(e)}`;
    }
    if (token === this.token && !(study && study.finished)) this.timer = setTimeout(() => this.read(id, token), REFRESH_MS);
  }

  // The length unit of the study's files, from its first job's record ('' when it is deleted: the
  // axis says "file length unit").
  async setUnit(study) {
    const first = study.jobs.find((run) => run.job);
    this.charts.setLengthUnit(first ? await unitOfJob({ id: first.job }) : '');
  }

  // A run's statistics files, those whose size changed; whether it has any rows.
  async readRun(run, token) {
    let artifacts = [];
    try {
      artifacts = await server.listArtifacts(run.job);
    } catch {
      return false; // not started, or deleted meanwhile
    }
    const sizes = new Map(artifacts.map((a) => [a.name, a.size]));
    await Promise.all(FILES.map(async (file) => {
      const key = `${run.job}/${file}`;
      if (!sizes.has(file) || this.sizes.get(key) === sizes.get(file)) return;
      const text = await server.downloadArtifact(run.job, file);
      if (token !== this.token) return;
      const columns = OVERLAID.find((o) => o.file === file).columns;
      this.rows.set(key, parseRows(text, columns));
      this.sizes.set(key, sizes.get(file));
    }));
    return FILES.some((file) => (this.rows.get(`${run.job}/${file}`) || []).length > 0);
  }
}
