// What the particles can be coloured by: a number per particle of a frame, with its label and unit.
// `values(frame, k, context)` gives particle k's value; context.reference is the run's first frame
// (for the displacement since the start, matched by id). A quantity whose column a frame lacks
// (spin and contacts come from files only) gives NaN, drawn in the map's lowest colour.

const speed = (f, k) => Math.hypot(f.velocities[k * 3], f.velocities[k * 3 + 1], f.velocities[k * 3 + 2]);

export const QUANTITIES = {
  speed: { label: 'Speed', unit: (u) => `${u}/s`, value: speed },
  diameter: { label: 'Diameter', unit: (u) => u, value: (f, k) => 2 * f.radii[k] },
  height: { label: 'Height (z)', unit: (u) => u, value: (f, k) => f.positions[k * 3 + 2] },
  displacement: {
    label: 'Displacement from the first frame',
    // the first frame held: a job joined while running, or a live run past its memory cap, starts later
    labelFor: (context) => (context.reference ? `Displacement since step ${context.reference.step}` : 'Displacement'),
    unit: (u) => u,
    value: (f, k, context) => {
      const ref = context.reference;
      if (!ref) return NaN;
      const j = context.referenceIndex(f.ids ? f.ids[k] - 1 : k);
      if (j < 0) return NaN;
      const p = f.positions, q = ref.positions;
      return Math.hypot(p[k * 3] - q[j * 3], p[k * 3 + 1] - q[j * 3 + 1], p[k * 3 + 2] - q[j * 3 + 2]);
    },
  },
  spin: {
    label: 'Spin',
    unit: () => 'rad/s',
    value: (f, k) => (f.spins ? Math.hypot(f.spins[k * 3], f.spins[k * 3 + 1], f.spins[k * 3 + 2]) : NaN),
  },
  contacts: { label: 'Contacts', unit: () => '', value: (f, k) => (f.contacts ? f.contacts[k] : NaN) },
  fragmentSize: {
    label: 'Fragment size (particles in its part)',
    unit: () => 'particles',
    value: (f, k, context) => (f.parts[k] > 0 ? context.partSizes(f).get(f.parts[k]) : NaN), // part 0: none
  },
  // The PDEM-EGD manual's Part (section 3.2, figure 3.17): the particles that hold together in one
  // colour by how many they are, red for the large masses and green for the small ones, to judge
  // the scale of the disaster. On a log scale (one sphere to the intact block), on its own map.
  part: {
    label: 'Part: its size, green (small) to red (large)',
    unit: () => 'particles, log scale',
    value: (f, k, context) => (f.parts[k] > 0 ? context.partSizes(f).get(f.parts[k]) : NaN),
    log: true,
    map: 'partSize',
  },
};

// The largest parts of a frame: [{ part, size }], largest first, at most `count`.
export function largestParts(frame, count) {
  return [...partSizes(frame)].filter(([part]) => part > 0).map(([part, size]) => ({ part, size }))
    .sort((a, b) => b.size - a.size || a.part - b.part).slice(0, count);
}

// The particles of each part of a frame ({part: count}), computed once a frame.
export function partSizes(frame) {
  if (frame.partSizes) return frame.partSizes;
  const sizes = new Map();
  for (let k = 0; k < frame.count; k++) sizes.set(frame.parts[k], (sizes.get(frame.parts[k]) || 0) + 1);
  frame.partSizes = sizes;
  return sizes;
}

// [min, max] widened to take in `more` (either may be null).
export function widen(range, more) {
  if (!range || !more) return range || more;
  return [Math.min(range[0], more[0]), Math.max(range[1], more[1])];
}

// [min, max] of a quantity over a frame's particles (NaN values skipped); null when none.
export function frameRange(quantity, frame, context) {
  let lo = Infinity, hi = -Infinity;
  for (let k = 0; k < frame.count; k++) {
    const v = quantity.value(frame, k, context);
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  return lo <= hi ? [lo, hi] : null;
}
