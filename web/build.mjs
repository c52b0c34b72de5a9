// Builds web/dist/: bundles src/main.js -> viewer.js and the parse worker -> parse_worker.js (both ES
// modules), and copies index.html and style.css. `node build.mjs --dev` keeps the code readable and
// writes source maps.

import * as esbuild from 'esbuild';
import { copyFileSync, mkdirSync, rmSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = dirname(fileURLToPath(import.meta.url));
const dist = join(root, 'dist');
const dev = process.argv.includes('--dev');

rmSync(dist, { recursive: true, force: true });
mkdirSync(dist, { recursive: true });

const common = {
  bundle: true,
  format: 'esm',
  target: ['es2020'],
  minify: !dev,
  sourcemap: dev ? 'linked' : false,
  legalComments: 'none',
  logLevel: 'warning',
};

await esbuild.build({
  ...common,
  entryPoints: { viewer: join(root, 'src/main.js'), parse_worker: join(root, 'src/formats/parse_worker.js') },
  outdir: dist,
});

for (const file of ['index.html', 'style.css']) copyFileSync(join(root, file), join(dist, file));
console.log(`built ${dist}: index.html style.css viewer.js parse_worker.js`);
