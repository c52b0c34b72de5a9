// The live frames' decoder against the schema: every field of proto/dem.proto's Frame and WallShape
// is in its table with its number (the table once drifted: clump positions and orientations were
// sent and skipped), and the fields the viewer does not draw yet are decoded all the same. No browser.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { test, expect } from '@playwright/test';
import { FRAME_FIELDS, WALL_SHAPE_FIELDS, decodeFrameMessage } from '../src/live/frame_decode.js';

const here = path.dirname(fileURLToPath(import.meta.url));
const proto = fs.readFileSync(path.join(here, '..', '..', 'proto', 'dem.proto'), 'utf8');

// A message's fields as {name: number}, from its text in the .proto (comments dropped).
function fieldsOf(message) {
  const start = proto.indexOf(`message ${message} {`);
  expect(start, `message ${message} in dem.proto`).toBeGreaterThanOrEqual(0);
  const body = proto.slice(start, proto.indexOf('\n}', start)).replace(/\/\/[^\n]*/g, '');
  const fields = {};
  for (const m of body.matchAll(/^\s*(?:repeated\s+|optional\s+)?[\w.]+\s+(\w+)\s*=\s*(\d+)\s*;/gm)) fields[m[1]] = Number(m[2]);
  return fields;
}

test('the decoder knows every field of Frame and WallShape by its number in dem.proto', () => {
  const frame = fieldsOf('Frame');
  expect(Object.keys(frame).length).toBeGreaterThanOrEqual(17);
  expect({ ...FRAME_FIELDS }).toEqual(frame);
  expect({ ...WALL_SHAPE_FIELDS }).toEqual(fieldsOf('WallShape'));
});

// Protobuf's wire format, by hand: a varint, a tag, a length-delimited field.
function varint(n) {
  const out = [];
  do {
    let b = n % 128;
    n = Math.floor(n / 128);
    if (n > 0) b += 128;
    out.push(b);
  } while (n > 0);
  return out;
}
const lenField = (field, bytes) => [...varint(field * 8 + 2), ...varint(bytes.length), ...bytes];
const floats = (values) => [...new Uint8Array(new Float32Array(values).buffer)];

test('clump positions and orientations and the absent walls are decoded, packed or not', () => {
  const message = new Uint8Array([
    ...varint(FRAME_FIELDS.step * 8), ...varint(300),
    ...lenField(FRAME_FIELDS.clump_positions, floats([1, 2, 3, 4, 5, 6])),
    ...lenField(FRAME_FIELDS.clump_orientations, floats([1, 0, 0, 0, 0.5, 0.5, 0.5, 0.5])),
    ...lenField(FRAME_FIELDS.absent_walls, [...varint(2), ...varint(300)]),  // packed
    ...varint(FRAME_FIELDS.absent_walls * 8), ...varint(7),                  // and one more, unpacked
  ]);
  const raw = decodeFrameMessage(message);
  expect(raw.step).toBe(300);
  expect([...raw.clumpPositions]).toEqual([1, 2, 3, 4, 5, 6]);
  expect([...raw.clumpOrientations]).toEqual([1, 0, 0, 0, 0.5, 0.5, 0.5, 0.5]);
  expect(raw.absentWalls).toEqual([2, 300, 7]);
  for (const f of [FRAME_FIELDS.clump_positions, FRAME_FIELDS.clump_orientations, FRAME_FIELDS.absent_walls])
    expect(raw.present.has(f), `field ${f} present`).toBe(true);
});
