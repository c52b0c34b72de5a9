// Writes a synthetic ANIMATION_3D.dat of N spheres in a block (2 frames) for the viewer benchmark.
// usage: node make_run.mjs N OUT
import { writeFileSync } from 'node:fs';

const n = Number(process.argv[2]);
const out = process.argv[3];
const side = Math.ceil(Math.cbrt(n));
const d = 1.0;
let text = '';
for (let frame = 0; frame < 2; ++frame) {
  const lines = ['3DA:', `0 ${side} 0 ${side} 0 ${side}`, `${frame * 0.01} 0 0 0`, '0', `${frame * 1000} ${n} 0`];
  for (let i = 0; i < n; ++i) {
    const x = (i % side) + 0.5, y = (Math.floor(i / side) % side) + 0.5, z = Math.floor(i / (side * side)) + 0.5 + frame * 0.1;
    const v = ((i * 7919) % 1000) / 1000;
    lines.push(`${i + 1} ${x} ${y} ${z} ${d * (0.8 + 0.2 * v)} ${v} 0 0 0 0 0 0 0`);
  }
  text += lines.join('\n') + '\n';
}
writeFileSync(out, text);
