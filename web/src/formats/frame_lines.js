// Checks the lines of one frame against their layout and words the messages the way the engine's
// readers do (engine/legacy/legacy_formats.cpp), so that a file gets the same diagnosis in the
// browser as on the command line: "line 24: column 2 ('1.2.3') is not a number".

import { parseInteger, parseReal, quoted } from './numbers.js';

// What line a frame expects next: "particle line 12 of 400" and its layout.
export function describe(expected) {
  return expected.index ? `${expected.name} ${expected.index} of ${expected.total}` : expected.name;
}

// A problem that stops reading. truncated: the input ended inside a frame.
export class Stop {
  constructor(problem, truncated = false) {
    this.problem = problem;
    this.truncated = truncated;
  }
}

// Returns a Stop when `tokens` (a line of the frame that starts at `frameLine`) is not `expected`.
export function checkLine(tokens, lineNumber, expected, header, frameLine) {
  if (tokens.length === expected.columns) return null;
  if (tokens[0] === header) {
    return new Stop(`line ${lineNumber}: a new frame starts here, but the frame that starts at line ${frameLine} ` +
      `is incomplete: its ${describe(expected)} is missing`);
  }
  return new Stop(`line ${lineNumber}: expected ${expected.columns} values on the ${describe(expected)} ` +
    `(${expected.layout}), found ${tokens.length}`);
}

// The Stop for an input that ends while `expected` is still awaited.
export function ended(expected, frameLine, end) {
  let problem = `the file ends inside the frame that starts at line ${frameLine}: its ${describe(expected)} is missing`;
  problem += end.unfinishedLastLine
    ? `; the last line (line ${end.lastLine}) has no line end, the writer was stopped while writing it`
    : ` (the last line is line ${end.lastLine})`;
  return new Stop(problem, true);
}

// Converts a line's columns, keeping the first problem met; getters return 0 after a problem, so
// a caller converts a whole line and checks `problem` once.
export class Values {
  constructor(tokens, lineNumber) {
    this.tokens = tokens;
    this.lineNumber = lineNumber;
    this.problem = null;
  }

  real(column) {
    const value = parseReal(this.tokens[column]);
    return value === value ? value : this.fail(column, 'is not a number');
  }

  integer(column) {
    const value = parseInteger(this.tokens[column]);
    if (value !== value) return this.fail(column, 'is not an integer');
    if (value < -2147483648 || value > 2147483647) return this.fail(column, 'is out of the range of an int');
    return value;
  }

  // A step number: any whole number (the engine keeps 64 bits; JS numbers are exact to 2^53).
  step(column) {
    const value = parseInteger(this.tokens[column]);
    return value === value ? value : this.fail(column, 'is not an integer');
  }

  count(column) {
    const value = this.integer(column);
    return value < 0 ? this.fail(column, 'is a negative count') : value;
  }

  // A 1-based index into a list of `size` items (0 when none is known).
  id(column) {
    const value = this.integer(column);
    return value < 1 && !this.problem ? this.fail(column, 'is not a 1-based id') : value;
  }

  word(column, word) {
    if (this.tokens[column] !== word && !this.problem) {
      this.problem = `line ${this.lineNumber}: column ${column + 1} is ${quoted(this.tokens[column])}, expected '${word}'`;
    }
  }

  fail(column, what) {
    if (!this.problem) {
      this.problem = `line ${this.lineNumber}: column ${column + 1} (${quoted(this.tokens[column])}) ${what}`;
    }
    return 0;
  }
}
