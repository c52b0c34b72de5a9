// Global setup of the browser tests: legacy files written by the real engine, a malformed one,
// and the real dem-server on a free loopback port serving web/dist. The returned function is the
// teardown: it stops the server with SIGTERM and removes the temporary folder.
//
// Environment: DEM_BUILD_DIR (build/ of the source tree by default), DEM_WEB_DIR (web/dist by
// default), DEM_KEEP_FIXTURES=1 keeps the temporary folder (fixtures, server data and log).
//
// What the tests get (environment variables, inherited by the test workers):
//   DEM_SERVER_URL      http://127.0.0.1:PORT (no trailing slash)
//   DEM_FIXTURES        the folder holding offline/ANIMATION_3D.dat, offline/ForceChain_3D.dat,
//                       malformed/ANIMATION_3D.dat (no complete frame), truncated/ANIMATION_3D.dat
//                       (cut inside frame 7: 6 complete frames), planar/ANIMATION_2D.dat (a 2D run)
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const webDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const rootDir = path.resolve(webDir, '..');

// The fixture run: the demo case shrunk to ~300 spheres of two sizes (so "Diameter" colouring has
// something to show), 0.3 s, a frame every 0.02 s (17 frames), force chains on, lengths in mm.
function fixtureSpec() {
  const spec = JSON.parse(fs.readFileSync(path.join(rootDir, 'cases/demo/spec.json'), 'utf8'));
  const lattice = spec.lattices[0];
  spec.name = 'viewer test fixture';
  spec.lattices = [
    { ...lattice, max: { ...lattice.max, z: 0.18 }, radius: 0.012 },
    { ...lattice, min: { ...lattice.min, z: 0.2 }, radius: 0.016 },
  ];
  spec.time = { duration: 0.3 };
  spec.outputs = { interval: 0.02, forceChains: true, lengthUnit: 'mm' };
  return spec;
}

// A 2D run: discs of two sizes falling onto a sloping plate in a box of two planes, 0.2 s, a frame every 0.02 s.
function planarSpec() {
  return {
    name: 'viewer test fixture, 2D',
    dimension: 2,
    discThickness: 0.01,
    materials: [
      { name: 'glass', density: 2500, youngsModulus: 1e8, poissonRatio: 0.25 },
      { name: 'steel', rigid: true },
    ],
    interactions: [
      { a: 'glass', b: 'glass', restitution: 0.5, friction: 0.5 },
      { a: 'glass', b: 'steel', restitution: 0.5, friction: 0.5 },
    ],
    contact: { normal: 'HERTZ' },
    lattices: [
      { kind: 'HEX', min: { x: 0.005, z: 0.05 }, max: { x: 0.095, z: 0.1 }, radius: 0.004, spacing: 1.1, material: 'glass' },
      { kind: 'HEX', min: { x: 0.005, z: 0.11 }, max: { x: 0.095, z: 0.15 }, radius: 0.006, spacing: 1.1, material: 'glass' },
    ],
    walls: [
      { name: 'slope', material: 'steel', plate: { c1: { x: 0, y: -0.05, z: 0.03 }, c2: { x: 0.1, y: -0.05, z: 0 },
        c3: { x: 0.1, y: 0.05, z: 0 }, c4: { x: 0, y: 0.05, z: 0.03 } } },
      { name: 'left', material: 'steel', plane: { normal: { x: 1 } } },
      { name: 'right', material: 'steel', plane: { point: { x: 0.1 }, normal: { x: -1 } } },
    ],
    gravity: { z: -9.81 },
    time: { duration: 0.2 },
    outputs: { interval: 0.02 },
  };
}

// A malformed ANIMATION_3D.dat: the first frame with a garbled particle line, then cut in the
// middle of a line. No frame in it is complete, so there is nothing to show but an error.
function malformedAnimation(goodText) {
  const lines = goodText.split('\n');
  // header, box, scalars, NT, "step NP NW", NW plate lines, then particles
  const nt = Number(lines[3].trim());
  const [, np, nw] = lines[4].trim().split(/\s+/).map(Number);
  const firstParticle = 5 + nw + nt;
  const out = lines.slice(0, firstParticle + Math.min(np, 20));
  const cols = out[firstParticle + 2].split(' ');
  cols[1] = '1.2.3e';            // not a number
  cols.push('garbage', '###');  // and too many values
  out[firstParticle + 2] = cols.join(' ');
  const text = out.join('\n');
  return text.slice(0, text.length - 17);  // ends inside a line, with no line end
}

// ANIMATION_3D.dat of a writer killed in the middle of frame 7: 6 complete frames, then half a frame
// ending inside a line.
export const TRUNCATED_FRAMES = 6;
function truncatedAnimation(goodText) {
  const starts = [...goodText.matchAll(/^3DA:$/gm)].map((m) => m.index);
  const cut = starts[TRUNCATED_FRAMES] + Math.floor((starts[TRUNCATED_FRAMES + 1] - starts[TRUNCATED_FRAMES]) / 2);
  return goodText.slice(0, goodText[cut - 1] === '\n' ? cut + 5 : cut);
}

export function waitForListening(server, timeoutMs) {
  return new Promise((resolve, reject) => {
    let seen = '';
    const timer = setTimeout(() => {
      reject(new Error(`dem-server did not say where it listens within ${timeoutMs} ms; it printed:\n${seen}`));
    }, timeoutMs);
    const onData = (chunk) => {
      seen += chunk.toString();
      const m = seen.match(/listening on (http:\/\/127\.0\.0\.1:\d+)\//);
      if (m) {
        clearTimeout(timer);
        resolve(m[1]);
      }
    };
    server.stdout.on('data', onData);
    server.stderr.on('data', (chunk) => { seen += chunk.toString(); });
    server.on('exit', (code, signal) => {
      clearTimeout(timer);
      reject(new Error(`dem-server exited (code ${code}, signal ${signal}) before listening:\n${seen}`));
    });
  });
}

export default async function globalSetup() {
  const buildDir = path.resolve(process.env.DEM_BUILD_DIR || path.join(rootDir, 'build'));
  const dem = path.join(buildDir, 'dem');
  const demServer = path.join(buildDir, 'dem-server');
  const dist = path.resolve(process.env.DEM_WEB_DIR || path.join(webDir, 'dist'));
  for (const [file, hint] of [[dem, 'scripts/build'], [demServer, 'scripts/build'],
                              [path.join(dist, 'index.html'), 'npm run build in web/ (scripts/build does it)']]) {
    if (!fs.existsSync(file)) throw new Error(`${file} is missing: run ${hint}`);
  }

  const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'dem-web-tests-'));
  const offline = path.join(tmp, 'offline');
  const malformed = path.join(tmp, 'malformed');
  fs.mkdirSync(malformed, { recursive: true });
  const specFile = path.join(tmp, 'spec.json');
  fs.writeFileSync(specFile, JSON.stringify(fixtureSpec(), null, 1));
  const run = spawnSync(dem, ['run', specFile, '--out', offline, '--quiet'], {
    encoding: 'utf8', timeout: 120_000, env: { ...process.env, OMP_NUM_THREADS: '1' },
  });
  if (run.status !== 0) {
    throw new Error(`dem run of the fixture spec failed (status ${run.status}):\n${run.stdout}\n${run.stderr}`);
  }
  for (const name of ['ANIMATION_3D.dat', 'ForceChain_3D.dat']) {
    if (!fs.existsSync(path.join(offline, name))) throw new Error(`dem run wrote no ${name} in ${offline}`);
  }
  const goodText = fs.readFileSync(path.join(offline, 'ANIMATION_3D.dat'), 'utf8');
  fs.writeFileSync(path.join(malformed, 'ANIMATION_3D.dat'), malformedAnimation(goodText));
  fs.mkdirSync(path.join(tmp, 'truncated'));
  fs.writeFileSync(path.join(tmp, 'truncated', 'ANIMATION_3D.dat'), truncatedAnimation(goodText));
  const planarFile = path.join(tmp, 'planar.json');
  fs.writeFileSync(planarFile, JSON.stringify(planarSpec(), null, 1));
  const planar = spawnSync(dem, ['run', planarFile, '--out', path.join(tmp, 'planar'), '--quiet'], {
    encoding: 'utf8', timeout: 120_000, env: { ...process.env, OMP_NUM_THREADS: '1' },
  });
  if (planar.status !== 0 || !fs.existsSync(path.join(tmp, 'planar', 'ANIMATION_2D.dat'))) {
    throw new Error(`dem run of the 2D fixture spec failed (status ${planar.status}):\n${planar.stdout}\n${planar.stderr}`);
  }

  const server = spawn(demServer, ['--port', '0', '--data', path.join(tmp, 'server'), '--web', dist,
                                   '--cases', path.join(rootDir, 'cases')],
                       { stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, OMP_WAIT_POLICY: 'PASSIVE' } });
  const log = fs.createWriteStream(path.join(tmp, 'dem-server.log'));
  server.stdout.pipe(log);
  server.stderr.pipe(log);
  let url;
  try {
    url = await waitForListening(server, 30_000);
  } catch (e) {
    server.kill('SIGKILL');
    throw e;
  }
  process.env.DEM_SERVER_URL = url;
  process.env.DEM_FIXTURES = tmp;

  return async function globalTeardown() {
    if (server.exitCode === null && server.signalCode === null) {
      const exited = new Promise((resolve) => server.once('exit', resolve));
      server.kill('SIGTERM');
      const timer = setTimeout(() => server.kill('SIGKILL'), 20_000);
      await exited;
      clearTimeout(timer);
    }
    if (process.env.DEM_KEEP_FIXTURES) {
      console.log(`fixtures and the server's data kept in ${tmp}`);
    } else {
      fs.rmSync(tmp, { recursive: true, force: true });
    }
  };
}
