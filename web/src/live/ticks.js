// Round tick values for a chart axis: steps of 1, 2 or 5 times a power of ten, and the axis widened
// to the ticks just outside the data, so that both ends are labelled with round numbers (0, 0.5, 1
// rather than 0.0137 and 0.9862).

// niceTicks(min, max, target): { min, max, step, ticks } with about `target` intervals; min < max,
// within a thousandth of a step of the data's ends or outside them.
export function niceTicks(min, max, target = 5) {
  if (!(Number.isFinite(min) && Number.isFinite(max))) return { min, max, step: NaN, ticks: [] };
  if (min > max) [min, max] = [max, min];
  if (min === max) {
    const pad = Math.abs(min) * 0.1 || 1;
    min -= pad;
    max += pad;
  }
  const rough = (max - min) / Math.max(1, target);
  const power = 10 ** Math.floor(Math.log10(rough));
  const step = [1, 2, 5, 10].map((m) => m * power).find((s) => s >= rough * (1 - 1e-9));
  // data past a tick by a thousandth of a step (a last frame at 0.200007 s) does not widen the axis
  const lo = Math.floor(min / step + 1e-3) * step;
  const hi = Math.ceil(max / step - 1e-3) * step;
  const ticks = [];
  for (let k = 0; lo + k * step <= hi + step * 1e-9; k++) ticks.push(clean(lo + k * step, step));
  return { min: ticks[0], max: ticks[ticks.length - 1], step, ticks };
}

// Powers of ten for a log axis over [min, max] (both > 0), widened to whole decades.
export function decadeTicks(min, max) {
  const lo = Math.floor(Math.log10(min) + 1e-9);
  const hi = Math.max(lo + 1, Math.ceil(Math.log10(max) - 1e-9));
  const every = Math.max(1, Math.ceil((hi - lo) / 6)); // at most about six labels
  const ticks = [];
  for (let e = lo; e <= hi; e += every) ticks.push(10 ** e);
  return { min: 10 ** lo, max: 10 ** hi, ticks };
}

// v rounded to the step's decimals: 0.30000000000000004 -> 0.3, -0 -> 0.
function clean(v, step) {
  const decimals = Math.max(0, -Math.floor(Math.log10(step)) + 1);
  const r = Number(v.toFixed(Math.min(decimals, 20)));
  return r === 0 ? 0 : r;
}

// One number as a label: short, an exponent for very large or small magnitudes, no trailing zeros
// ("2.5e-4", "4e5", "0.5", "51840").
function label(v) {
  if (!Number.isFinite(v)) return '';
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e5 || a < 1e-3) return exponential(v);
  return Number(v.toPrecision(a >= 1000 ? 5 : 3)).toString();
}

function exponential(v) {
  return v.toExponential(2).replace(/\.?0+e/, 'e').replace('e+', 'e');
}

// The labels of an axis's ticks, all in one format: on a log axis that reaches an exponent, every
// decade as one (1e-5 ... 1e1, not 1e-4 beside 0.001).
export function tickLabels(ticks, log = false) {
  const labels = ticks.map(label);
  if (log && labels.some((l) => l.includes('e'))) return ticks.map(exponential);
  return labels;
}
