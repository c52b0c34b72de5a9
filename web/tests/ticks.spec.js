// The charts' axes are labelled at round numbers (src/live/ticks.js): steps of 1, 2 or 5 times a
// power of ten, the axis widened to the ticks around the data. No browser.
import { test, expect } from '@playwright/test';
import { niceTicks, decadeTicks, tickLabels } from '../src/live/ticks.js';

const round = (v, step) => Math.abs(v / step - Math.round(v / step)) < 1e-6;

test('ticks are round and cover the data', () => {
  const cases = [[0.0137, 0.9862, 5], [0, 0.3, 5], [-2.3e-6, 7.9e-6, 4], [51840, 51862, 5], [1.5e3, 5.184e4, 6],
                 [0.2, 0.2, 5], [-1, -1, 3], [3, 1, 5], [0, 1e-12, 5], [123456789, 123456790, 5]];
  for (const [min, max, target] of cases) {
    const a = niceTicks(min, max, target);
    const what = `niceTicks(${min}, ${max}, ${target}) = ${JSON.stringify(a)}`;
    const mantissa = a.step / 10 ** Math.floor(Math.log10(a.step) + 1e-12);
    expect([1, 2, 5].some((m) => Math.abs(mantissa - m) < 1e-9), `${what}: a step of 1, 2 or 5 x 10^k`).toBe(true);
    const slack = a.step * 1e-3;
    expect(a.min <= Math.min(min, max) + slack && a.max >= Math.max(min, max) - slack, `${what}: covers the data`).toBe(true);
    expect(a.ticks.length >= 2 && a.ticks.length <= 2 * target + 2, `${what}: about ${target} intervals`).toBe(true);
    for (const t of a.ticks) expect(round(t, a.step), `${what}: ${t} is a multiple of the step`).toBe(true);
    expect(a.ticks[0]).toBe(a.min);
    expect(a.ticks[a.ticks.length - 1]).toBe(a.max);
  }
  expect(niceTicks(0.0137, 0.9862, 5).ticks).toEqual([0, 0.2, 0.4, 0.6, 0.8, 1]);
  expect(niceTicks(0, 0.3, 3).ticks).toEqual([0, 0.1, 0.2, 0.3]);
  expect(niceTicks(0, 0.200007, 3).ticks, 'a last frame just past a round time').toEqual([0, 0.1, 0.2]);
});

test('a log axis is labelled at whole decades', () => {
  expect(decadeTicks(0.03, 400).ticks).toEqual([0.01, 0.1, 1, 10, 100, 1000]);
  expect(decadeTicks(5, 5).ticks).toEqual([1, 10]);
  const wide = decadeTicks(1e-12, 1e6);
  expect(wide.ticks.length).toBeLessThanOrEqual(8);
  expect(wide.min).toBe(1e-12);
});

test('an axis is labelled in one format, without trailing zeros', () => {
  // a log axis over 1e-5 .. 10 had "1.00e-5", "1.00e-4", "0.001", "0.01", "0.1", "1", "10"
  expect(tickLabels(decadeTicks(2e-5, 8).ticks, true)).toEqual(['1e-5', '1e-4', '1e-3', '1e-2', '1e-1', '1e0', '1e1']);
  expect(tickLabels(decadeTicks(0.03, 400).ticks, true)).toEqual(['0.01', '0.1', '1', '10', '100', '1000']);
  expect(tickLabels([0, 2e5, 4e5, 6e5], false)).toEqual(['0', '2e5', '4e5', '6e5']);
  expect(tickLabels([0, 0.5, 1, 1.5], false)).toEqual(['0', '0.5', '1', '1.5']);
  expect(tickLabels([0, 2.5e-4, 5e-4], false)).toEqual(['0', '2.5e-4', '5e-4']);
  expect(tickLabels([51840, 51850, 51860], false)).toEqual(['51840', '51850', '51860']);
});
