// Per-frame ranges the viewer needs (colour bar, section slider range, chain scale). Computed where
// the frame is made: in the parse worker for files, so the main thread never loops over a whole run.

export function addStats(frame) {
  if (frame.stats) return frame;
  if (frame.fn) { // a frame of force chains
    let fnMax = 0;
    for (let k = 0; k < frame.fn.length; k++) fnMax = Math.max(fnMax, Math.abs(frame.fn[k]));
    frame.stats = { fnMax };
    return frame;
  }
  const n = frame.count;
  const p = frame.positions;
  const v = frame.velocities;
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  let speedMin = Infinity, speedMax = -Infinity, dMin = Infinity, dMax = -Infinity, partMax = 0;
  for (let k = 0; k < n; k++) {
    for (let c = 0; c < 3; c++) {
      const x = p[k * 3 + c];
      if (x < min[c]) min[c] = x;
      if (x > max[c]) max[c] = x;
    }
    const s = Math.hypot(v[k * 3], v[k * 3 + 1], v[k * 3 + 2]);
    if (s < speedMin) speedMin = s;
    if (s > speedMax) speedMax = s;
    const d = 2 * frame.radii[k];
    if (d < dMin) dMin = d;
    if (d > dMax) dMax = d;
    if (frame.parts[k] > partMax) partMax = frame.parts[k];
  }
  frame.stats = n ? { min, max, speed: [speedMin, speedMax], diameter: [dMin, dMax], partMax }
    : { min: [0, 0, 0], max: [0, 0, 0], speed: [0, 0], diameter: [0, 0], partMax: 0 };
  frame.stats.repeatedId = firstRepeatedId(frame.ids, n);
  return frame;
}

// The first id the frame gives to two particles (0: none): force chains and the probe find a
// particle by its id, and can reach only one of them. Ids 1..N in order, as the engine writes them,
// need no set.
function firstRepeatedId(ids, n) {
  if (!ids) return 0;
  let ordered = true;
  for (let k = 0; k < n && ordered; k++) ordered = ids[k] === k + 1;
  if (ordered) return 0;
  const seen = new Set();
  for (let k = 0; k < n; k++) {
    if (seen.has(ids[k])) return ids[k];
    seen.add(ids[k]);
  }
  return 0;
}
