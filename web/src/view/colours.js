// Colour maps. The legacy colour bar runs from dark blue (small) to red (large) through cyan, green
// and yellow (manuals, figure 3.9); viridis (matplotlib's default, perceptually uniform and
// readable in grey and by colour-blind readers) and a grey ramp are the others. The same stops draw
// the bar on the page and colour the spheres, so the bar always tells the truth. Force chains keep
// the legacy map (their legend names its blue and red).

const LEGACY = [
  [0.0, [0.0, 0.0, 0.56]],
  [0.125, [0.0, 0.0, 1.0]],
  [0.375, [0.0, 1.0, 1.0]],
  [0.5, [0.0, 1.0, 0.0]],
  [0.625, [1.0, 1.0, 0.0]],
  [0.875, [1.0, 0.0, 0.0]],
  [1.0, [0.5, 0.0, 0.0]],
];
// viridis at ninths (van der Walt and Smith, matplotlib 2.0): #440154 ... #fde725
const VIRIDIS = ['#440154', '#472d7b', '#3b528b', '#2c728e', '#21918c', '#28ae80', '#5ec962', '#addc30', '#fde725']
  .map((hex, k, all) => [k / (all.length - 1), hexToRgb(hex)]);
const GREY = [[0, [0.08, 0.08, 0.08]], [1, [0.92, 0.92, 0.92]]];
// the manual's Part: green for few particles, red for many
const PART_SIZE = [[0, [0.13, 0.63, 0.17]], [0.5, [0.95, 0.8, 0.1]], [1, [0.84, 0.1, 0.1]]];

export const COLOUR_MAPS = { legacy: LEGACY, viridis: VIRIDIS, grey: GREY, partSize: PART_SIZE };
const stopsOf = (map) => COLOUR_MAPS[map] || LEGACY;

// An sRGB colour [r, g, b] in [0, 1] as CSS.
export function cssColour(c) {
  return `rgb(${c.map((v) => Math.round(v * 255)).join(',')})`;
}

// Where v stands in [lo, hi] on a log scale, 0 to 1 (1 when the range is a single value).
export function logPosition(v, lo, hi) {
  const l0 = Math.log(Math.max(lo, 1e-300)), l1 = Math.log(Math.max(hi, 1e-300));
  return l1 > l0 ? (Math.log(v) - l0) / (l1 - l0) : 1;
}

// The colour of t in [0, 1] on `stops` into out[offset..offset+2] (linear between the stops).
function onStops(stops, t, out, offset) {
  const x = t > 0 ? (t < 1 ? t : 1) : 0; // also maps NaN to 0
  let k = 1;
  while (k < stops.length - 1 && stops[k][0] < x) k++;
  const [t0, c0] = stops[k - 1];
  const [t1, c1] = stops[k];
  const f = (x - t0) / (t1 - t0);
  out[offset] = c0[0] + (c1[0] - c0[0]) * f;
  out[offset + 1] = c0[1] + (c1[1] - c0[1]) * f;
  out[offset + 2] = c0[2] + (c1[2] - c0[2]) * f;
  return out;
}

// Writes map `map`'s colour (sRGB) of t in [0, 1] into out[offset..offset+2].
export function onMap(map, t, out, offset = 0) {
  return onStops(stopsOf(map), t, out, offset);
}

// The CSS gradient of the bar for a map (the legacy one by default).
export function barGradient(map = 'legacy') {
  return `linear-gradient(to right, ${stopsOf(map).map(([t, c]) => `${cssColour(c)} ${t * 100}%`).join(', ')})`;
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

// 256 linear colours of each map: per-particle colouring is a table look-up.
const LUT_SIZE = 256;
const LUTS = new Map();
function lutOf(map) {
  if (!LUTS.has(map)) {
    const stops = stopsOf(map);
    const lut = new Float32Array(LUT_SIZE * 3);
    for (let k = 0; k < LUT_SIZE; k++) {
      onStops(stops, k / (LUT_SIZE - 1), lut, k * 3);
      for (let c = 0; c < 3; c++) lut[k * 3 + c] = srgbToLinear(lut[k * 3 + c]);
    }
    LUTS.set(map, lut);
  }
  return LUTS.get(map);
}

// Linear colour of t in [0, 1] on a map's table (the legacy map by default) into out[offset..].
export function mapLinear(t, out, offset, lut = lutOf('legacy')) {
  const k = t > 0 ? (t < 1 ? Math.round(t * (LUT_SIZE - 1)) * 3 : (LUT_SIZE - 1) * 3) : 0;
  out[offset] = lut[k];
  out[offset + 1] = lut[k + 1];
  out[offset + 2] = lut[k + 2];
}

// Linear RGB for each particle of `frame` (3 floats each): by a quantity (quantities.js; `quantity`
// with its `context`) on colour map `map` over range [lo, hi], or in mode 'constant' (rgb) or 'parts'.
export function particleColours(frame, mode, range, rgb, out, { quantity = null, context = null, map = 'legacy' } = {}) {
  const n = frame.count;
  const [lo, hi] = range;
  const scale = hi > lo ? 1 / (hi - lo) : 0;
  if (quantity && quantity.log) {
    const lut = lutOf(map);
    for (let k = 0; k < n; k++) {
      const v = quantity.value(frame, k, context);
      if (!(v > 0)) {
        out[k * 3] = out[k * 3 + 1] = out[k * 3 + 2] = srgbToLinear(0.6); // no part written: grey
        continue;
      }
      mapLinear(logPosition(v, lo, hi), out, k * 3, lut);
    }
  } else if (quantity) {
    const lut = lutOf(map);
    for (let k = 0; k < n; k++) mapLinear((quantity.value(frame, k, context) - lo) * scale, out, k * 3, lut);
  } else if (mode === 'parts') {
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
