// A job's output files as the panel reads them: downloaded from the server, parsed off the main
// thread, for the session (session.js) that asked; an ended session's reads are aborted.

import * as server from './server.js';
import { parseFile } from '../formats/load_files.js';
import { ACTIVE, percent } from './session.js';

export const STATS_FILES = ['Force_Displacement.dat', 'Fragments.dat', 'Bond_Breaks.dat'];
const METRES_PER = { m: 1, cm: 0.01, mm: 0.001 };

// The length unit of a job's files ("m", "cm", "mm") from its record, asked again when the record
// at hand is an old one without it; '' when the server cannot be asked.
export async function unitOfJob(job) {
  if (job.lengthUnit) return job.lengthUnit;
  try {
    return (await server.getJob(job.id)).lengthUnit || 'm';
  } catch {
    return '';
  }
}

// Downloads an output file of the session's job and parses it; onProgress(fraction, text) follows
// both halves. Rejects with an AbortError when the session ends meanwhile.
export async function downloadAndParse(session, name, size, onProgress = () => {}) {
  onProgress(0, `downloading ${name} (${(size / 1e6).toFixed(1)} MB)`);
  const blob = await server.downloadArtifactBlob(session.job.id, name, {
    signal: session.signal,
    onProgress: (got, total) => {
      const fraction = got / (total || size || got);
      onProgress(0.5 * fraction, `downloading ${name}: ${percent(fraction)}`);
    },
  });
  onProgress(0.5, `reading ${name}`);
  return parseFile(blob, (fraction) => onProgress(0.5 + 0.5 * fraction, `reading ${name}: ${percent(fraction)}`), session.signal);
}

// The job's Wall.dat as a mesh (null when it is not one). `unit`: scales it from the files' length
// unit to metres, as live frames are (a replay keeps the files' unit: no scaling).
export async function readMesh(session, unit = 'm') {
  const result = await downloadAndParse(session, 'Wall.dat', 0);
  if (!result || result.kind !== 'mesh' || !result.mesh) return null;
  const scale = METRES_PER[unit] || 1;
  if (scale !== 1) {
    const v = result.mesh.vertices;
    for (let k = 0; k < v.length; k++) v[k] *= scale;
  }
  return result.mesh;
}

// Force_Displacement.dat, Fragments.dat and Bond_Breaks.dat into `charts`, when the job has them.
// A file is downloaded again only when its size in the artifact list changed since it was read,
// and every file once more when the job has ended (`job` is its final record). One read at a time.
export async function readStatistics(session, charts, { job = null, artifacts = null } = {}) {
  session.statsInFlight += 1;
  try {
    if (!artifacts) artifacts = await server.listArtifacts(session.job.id);
    if (session.ended) return;
    const sizes = new Map(artifacts.map((a) => [a.name, a.size]));
    const final = !!job && !ACTIVE.has(job.state);
    const changed = (name) => sizes.has(name) && (final || sizes.get(name) === undefined || session.statsSizes.get(name) !== sizes.get(name));
    const get = (name) => (changed(name) ? server.downloadArtifact(session.job.id, name, { signal: session.signal }) : Promise.resolve(null));
    const [fd, fragments, breaks] = await Promise.all(STATS_FILES.map(get));
    if (session.ended) return;
    STATS_FILES.forEach((name, k) => {
      if ([fd, fragments, breaks][k] !== null) session.statsSizes.set(name, sizes.get(name));
    });
    if (fd !== null) charts.setForceDisplacement(fd);
    if (fragments !== null) charts.setFragments(fragments, { brokenBonds: !sizes.has('Bond_Breaks.dat') });
    if (breaks !== null) {
      // the cumulative count is carried to the run's end (or the newest live frame)
      let end = NaN;
      if (final && Number.isFinite(job.timeStep) && Number.isFinite(job.step)) end = job.step * job.timeStep;
      else if (session.lastFrame) end = session.lastFrame.time;
      charts.setBondBreaks(breaks, end);
    }
  } catch (e) {
    if (!session.ended) console.warn('statistics files', e);
  } finally {
    session.statsInFlight -= 1;
  }
}
