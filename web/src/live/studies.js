// Parameter studies (POST /api/v1/studies, docs/api.md) in #study-select: choosing one overlays
// the time series of its runs in #charts, one line a run named by its parameter values (the
// PDEM-EGD manual's figure 4.17 compares five bond strengths so; the BallastDEM manual's
// settlement curves so). The overlay is read again every few seconds while the study runs; a file
// is downloaded again only when its size changed. Choosing a job (or "none") ends the overlay.

import * as server from './server.js';
import { Charts, parseRows } from './charts.js';
import { counted } from '../words.js';
import { errorText } from './session.js';

const REFRESH_MS = 5000;

// What is overlaid: a column (or two added) of a statistics file (docs/formats.md section 5).
const OVERLAID = [
  { id: 'study-plate-displacement', title: 'Loading plate displacement', y: 'displacement', unitKey: 'length', file: 'Force_Displacement.dat', columns: 3, value: (r) => r[1] },
  { id: 'study-plate-force', title: 'Loading plate force', y: 'force (N)', file: 'Force_Displacement.dat', columns: 3, value: (r) => r[2] },
  { id: 'study-broken-bonds', title: 'Broken bonds', y: 'broken bonds (count)', file: 'Fragments.dat', columns: 6, value: (r) => r[4] + r[5] },
  { id: 'study-fragments', title: 'Fragments', y: 'fragments (count)', file: 'Fragments.dat', columns: 6, value: (r) => r[1] },
  { id: 'study-largest-fragment', title: 'Largest fragment', y: 'particles (count)', file: 'Fragments.dat', columns: 6, value: (r) => r[2] },
];
const FILES = [...new Set(OVERLAID.map((o) => o.file))];

// A run's line name: its parameters' last path segments and values ("tensileStrength = 4e+06").
export function runName(run) {
  const parts = Object.entries(run.parameters || {}).map(([path, value]) => {
    const short = path.split(' = ').map((p) => p.split(/[./]/).filter(Boolean).pop()).join(' = ');
    return `${short} = ${typeof value === 'object' ? JSON.stringify(value) : value}`;
  });
  return parts.length ? parts.join(', ') : `run ${run.run}`;
}

export class Studies {
  // container: #charts; onChosen(): a study was chosen (the panel leaves the job it showed).
  constructor(container, onChosen) {
    this.select = document.getElementById('study-select');
    this.status = document.getElementById('study-status');
    this.details = document.getElementById('live-studies');
    this.charts = new Charts(container, OVERLAID.map((o) => ({ ...o, series: [] })));
    this.onChosen = onChosen;
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
      option.textContent = `#${s.id} ${s.name || '(no name)'}: ${counted(s.jobs.length, 'run')}${s.finished ? '' : `, ${s.summary}`}`;
      options.push(option);
    }
    this.select.replaceChildren(...options);
    this.select.value = options.some((o) => o.value === chosen) ? chosen : '';
    this.details.dataset.studies = String(studies.length);
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
  }

  async choose(id) {
    this.clear();
    if (!id) return;
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
      const runs = study.jobs.filter((run) => run.job && run.state !== 'deleted');
      for (const c of this.charts.charts.values()) {
        if (c.series.length !== runs.length) c.setSeries(runs.map(runName));
      }
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
      this.status.textContent = `${study.name || `study ${id}`}: ${study.summary}; ${drawn} of ${counted(runs.length, 'run')} with time series` +
        (drawn < runs.length ? ' (a run without Force_Displacement.dat or Fragments.dat, or not started, has none)' : '');
    } catch (e) {
      if (token === this.token) this.status.textContent = `study ${id}: ${errorText(e)}`;
    }
    if (token === this.token && !(study && study.finished)) this.timer = setTimeout(() => this.read(id, token), REFRESH_MS);
  }

  // The length unit of the study's files, from its first job's record.
  async setUnit(study) {
    const first = study.jobs.find((run) => run.job);
    let unit = '';
    try {
      if (first) unit = (await server.getJob(first.job)).lengthUnit || 'm';
    } catch {
      /* deleted: the axis says "file length unit" */
    }
    this.charts.setLengthUnit(unit);
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
