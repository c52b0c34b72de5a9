// Numbers as the legacy Fortran programs wrote them (docs/formats.md, "Rules common to every file").
// Mirrors engine/legacy/fortran_real.cpp so that the browser accepts and rejects exactly what the
// engine's readers do: 7.5e+002, 1.0E9, 1.0D9, 1.0d-3, .5, 5., +3, and 1.0-100 (Fortran drops the
// exponent letter before a three-digit exponent). NaN means "not a number" (callers test v !== v).

// The whole grammar: [sign] digits [. [digits]] | [sign] . digits, then (e|E|d|D)[sign]digits or sign digits.
const REAL = /^[+-]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][+-]?\d+|[+-]\d+)?$/;
// A mantissa of zeros only: the one case where a result of 0 is not an underflow.
const ZERO = /^[+-]?[0.]+(?:[eEdD+-].*)?$/;
const MAX_TOKEN = 128; // as the engine: far longer than any program prints

export function parseReal(token) {
  if (token.length > MAX_TOKEN || !REAL.test(token)) return NaN;
  let value = Number(token); // covers the C forms; NaN for the two Fortran-only forms
  if (value !== value) value = Number(token.replace(/[dD]/, 'e').replace(/([\d.])([+-]\d+)$/, '$1e$2'));
  // Out of the range of a double (1e400, or 1e-400 flushed to 0): rejected, as std::from_chars does.
  if (!Number.isFinite(value)) return NaN;
  if (value === 0 && !ZERO.test(token)) return NaN;
  return value;
}

// Integer columns (ids, steps, counts): old programs sometimes wrote them as reals ("3.0", "1.35E4").
export function parseInteger(token) {
  const value = parseReal(token);
  return Number.isSafeInteger(value) ? value : NaN;
}

// Token quoted for a message; keeps messages readable when a line holds binary junk.
export function quoted(token) {
  return token.length <= 40 ? `'${token}'` : `'${token.slice(0, 40)}...'`;
}
