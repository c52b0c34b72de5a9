// Colour maps. The legacy colour bar runs from dark blue (small) to red (large) through cyan, green
// and yellow (manuals, figure 3.9); the same stops draw the bar on the page and colour the spheres
// and force chains, so the bar always tells the truth.

const STOPS = [
  [0.0, [0.0, 0.0, 0.56]],
  [0.125, [0.0, 0.0, 1.0]],
  [0.375, [0.0, 1.0, 1.0]],
  [0.5, [0.0, 1.0, 0.0]],
  [0.625, [1.0, 1.0, 0.0]],
  [0.875, [1.0, 0.0, 0.0]],
  [1.0, [0.5, 0.0, 0.0]],
];

// Writes the colour of t in [0, 1] into out[offset..offset+2] (linear interpolation of the stops).
export function blueToRed(t, out, offset = 0) {
  const x = t > 0 ? (t < 1 ? t : 1) : 0; // also maps NaN to 0
  let k = 1;
  while (k < STOPS.length - 1 && STOPS[k][0] < x) k++;
  const [t0, c0] = STOPS[k - 1];
  const [t1, c1] = STOPS[k];
  const f = (x - t0) / (t1 - t0);
  out[offset] = c0[0] + (c1[0] - c0[0]) * f;
  out[offset + 1] = c0[1] + (c1[1] - c0[1]) * f;
  out[offset + 2] = c0[2] + (c1[2] - c0[2]) * f;
  return out;
}

// The CSS gradient of the bar.
export function barGradient() {
  return `linear-gradient(to right, ${STOPS.map(([t, c]) =>
    `rgb(${c.map((v) => Math.round(v * 255)).join(',')}) ${t * 100}%`).join(', ')})`;
}

// Distinct colours for "Part" (the cluster a particle belongs to: a block of a landslide, a
// fragment of a crushed stone). Golden-angle hues keep neighbouring part numbers apart; part 0
// (no part written) is grey.
export function partColour(part, out, offset = 0) {
  if (part <= 0) {
    out[offset] = out[offset + 1] = out[offset + 2] = 0.6;
    return out;
  }
  const h = ((part * 0.618033988749895) % 1) * 6;
  const s = 0.75;
  const v = 0.9;
  const i = Math.floor(h);
  const f = h - i;
  const p = v * (1 - s), q = v * (1 - s * f), u = v * (1 - s * (1 - f));
  const rgb = [[v, u, p], [q, v, p], [p, v, u], [p, q, v], [u, p, v], [v, p, q]][i % 6];
  out[offset] = rgb[0];
  out[offset + 1] = rgb[1];
  out[offset + 2] = rgb[2];
  return out;
}

// '#rrggbb' to [r, g, b] in [0, 1].
export function hexToRgb(hex) {
  const n = parseInt(hex.slice(1), 16);
  return [((n >> 16) & 255) / 255, ((n >> 8) & 255) / 255, (n & 255) / 255];
}

// Numbers on the colour bar: 4 significant digits, no trailing zeros.
export function formatValue(value) {
  if (!Number.isFinite(value)) return '';
  return String(Number(value.toPrecision(4)));
}

// The renderer works in linear light and converts to sRGB on output, while the stops above are
// sRGB (what the page's bar shows): colours handed to the GPU are converted first.
export function srgbToLinear(c) {
  return c < 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4);
}

// 256 linear colours of the blue-to-red map: per-particle colouring is a table look-up.
const LUT_SIZE = 256;
const LUT = (() => {
  const lut = new Float32Array(LUT_SIZE * 3);
  for (let k = 0; k < LUT_SIZE; k++) {
    blueToRed(k / (LUT_SIZE - 1), lut, k * 3);
    for (let c = 0; c < 3; c++) lut[k * 3 + c] = srgbToLinear(lut[k * 3 + c]);
  }
  return lut;
})();

// Linear colour of t in [0, 1] from the table into out[offset..].
export function mapLinear(t, out, offset) {
  const k = t > 0 ? (t < 1 ? Math.round(t * (LUT_SIZE - 1)) * 3 : (LUT_SIZE - 1) * 3) : 0;
  out[offset] = LUT[k];
  out[offset + 1] = LUT[k + 1];
  out[offset + 2] = LUT[k + 2];
}

// Linear RGB for each particle of `frame` (3 floats each) in colour mode
//   'speed' | 'diameter' (blue-to-red over range [lo, hi]), 'constant' (rgb), 'part'.
export function particleColours(frame, mode, range, rgb, out) {
  const n = frame.count;
  const [lo, hi] = range;
  const scale = hi > lo ? 1 / (hi - lo) : 0;
  if (mode === 'speed') {
    const v = frame.velocities;
    for (let k = 0; k < n; k++) {
      const s = Math.sqrt(v[k * 3] * v[k * 3] + v[k * 3 + 1] * v[k * 3 + 1] + v[k * 3 + 2] * v[k * 3 + 2]);
      mapLinear((s - lo) * scale, out, k * 3);
    }
  } else if (mode === 'diameter') {
    for (let k = 0; k < n; k++) mapLinear((2 * frame.radii[k] - lo) * scale, out, k * 3);
  } else if (mode === 'part') {
    const cache = new Map(); // few parts, many particles
    for (let k = 0; k < n; k++) {
      const part = frame.parts[k];
      let c = cache.get(part);
      if (!c) {
        c = partColour(part, [0, 0, 0]).map(srgbToLinear);
        cache.set(part, c);
      }
      out[k * 3] = c[0];
      out[k * 3 + 1] = c[1];
      out[k * 3 + 2] = c[2];
    }
  } else {
    const c = rgb.map(srgbToLinear);
    for (let k = 0; k < n; k++) {
      out[k * 3] = c[0];
      out[k * 3 + 1] = c[1];
      out[k * 3 + 2] = c[2];
    }
  }
  return out;
}
