// Typed arrays filled from counts read in a file. A count is not trusted for memory (a corrupt
// "2000000000" must not reserve gigabytes before a single line backs it), so arrays start at most
// 2^20 items long and double as lines actually arrive.

const FIRST_CAPACITY = 1 << 20;

export function allocate(Type, count, width) {
  return new Type(Math.min(count, FIRST_CAPACITY) * width);
}

// Returns `array`, or a copy twice as long when `needed` values do not fit.
export function ensure(array, needed) {
  if (needed <= array.length) return array;
  const grown = new array.constructor(Math.max(needed, array.length * 2));
  grown.set(array);
  return grown;
}
