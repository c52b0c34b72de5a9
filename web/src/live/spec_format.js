// JSON text of a job spec for the #case-spec editor: indented like JSON.stringify(spec, null, 2), but
// objects and arrays of plain values ({"x": 0.1, "y": 0.2}) stay on one line, and long runs of
// them (mesh vertices and triangles) are packed several to a line, so an inline mesh does not make
// the text thousands of lines long. JSON.parse gives back the same value.

const WIDTH = 100;

function isPlain(v) {
  return v === null || typeof v !== 'object';
}

// One line for an object or array whose members are all plain values; null when it has others.
function oneLine(value) {
  if (isPlain(value)) return JSON.stringify(value);
  if (Array.isArray(value)) {
    if (!value.every(isPlain)) return null;
    return `[${value.map((v) => JSON.stringify(v)).join(', ')}]`;
  }
  const entries = Object.entries(value).filter(([, v]) => v !== undefined);
  if (!entries.every(([, v]) => isPlain(v))) return null;
  return `{${entries.map(([k, v]) => `${JSON.stringify(k)}: ${JSON.stringify(v)}`).join(', ')}}`;
}

export function formatSpec(value, indent = '') {
  const line = oneLine(value);
  if (line !== null && line.length + indent.length <= WIDTH) return line;
  const inner = `${indent}  `;
  if (Array.isArray(value)) {
    if (!value.length) return '[]';
    const lines = value.map((v) => oneLine(v));
    if (lines.every((l) => l !== null && l.length + inner.length <= WIDTH)) {
      // Pack the items, several to a line.
      const rows = [];
      let row = '';
      for (const l of lines) {
        if (row && inner.length + row.length + 2 + l.length > WIDTH) {
          rows.push(row);
          row = '';
        }
        row = row ? `${row}, ${l}` : l;
      }
      if (row) rows.push(row);
      return `[\n${rows.map((r) => inner + r).join(',\n')}\n${indent}]`;
    }
    return `[\n${value.map((v) => inner + formatSpec(v, inner)).join(',\n')}\n${indent}]`;
  }
  const entries = Object.entries(value).filter(([, v]) => v !== undefined);
  if (!entries.length) return '{}';
  return `{\n${entries.map(([k, v]) => `${inner}${JSON.stringify(k)}: ${formatSpec(v, inner)}`).join(',\n')}\n${indent}}`;
}
