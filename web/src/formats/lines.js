// Splits text that arrives in chunks (a File read piece by piece) into numbered lines of tokens, so
// a parser never needs the whole file in memory as one string.
//
// Rules (docs/formats.md, "Readers"): tokens are separated by spaces, tabs or '\r' (commas too for
// the mesh files); blank lines are skipped but counted in line numbers; a last line without '\n' is
// never used: every writer ends its lines with '\n', so such a line was cut while being written.

export class LineSplitter {
  // onLine(tokens, lineNumber) returns false to stop reading (the parser met a problem).
  // commas: commas separate values too (mesh files). useUnfinished: a last line without '\n' is
  // read like any other (mesh files are written whole, often by hand, not followed while growing).
  constructor(onLine, { commas = false, useUnfinished = false } = {}) {
    this.onLine = onLine;
    this.useUnfinished = useUnfinished;
    this.separator = commas ? /[ \t\r\f\v,]+/ : /[ \t\r\f\v]+/;
    this.carry = '';
    this.lineNumber = 0;
    this.stopped = false;
  }

  // Feeds the next piece of text; returns false once the parser has stopped.
  push(text) {
    if (this.stopped) return false;
    let start = 0;
    let data = text;
    if (this.carry) {
      data = this.carry + text;
      this.carry = '';
    }
    for (let end = data.indexOf('\n', start); end >= 0; end = data.indexOf('\n', start)) {
      this.lineNumber += 1;
      const tokens = this.tokens(data.slice(start, end));
      start = end + 1;
      if (tokens && this.onLine(tokens, this.lineNumber) === false) {
        this.stopped = true;
        return false;
      }
    }
    this.carry = data.slice(start);
    return true;
  }

  // Ends the input. Returns { unfinishedLastLine, lastLine }: whether a last line without '\n' held
  // tokens (it is dropped), and the number of the last line read.
  end() {
    let unfinishedLastLine = false;
    if (!this.stopped && this.carry) {
      const tokens = this.tokens(this.carry);
      if (tokens) {
        this.lineNumber += 1;
        if (this.useUnfinished) this.onLine(tokens, this.lineNumber);
        else unfinishedLastLine = true;
      }
    }
    this.carry = '';
    return { unfinishedLastLine, lastLine: this.lineNumber };
  }

  tokens(line) {
    // Fast path for the engine's own files (one space between values, '\n' line ends): a plain
    // split is several times quicker than the regular expression.
    if (line.length && line.indexOf('  ') < 0 && line.indexOf('\t') < 0 && line.indexOf('\r') < 0 &&
        line.indexOf(',') < 0 && line.indexOf('\f') < 0 && line.indexOf('\v') < 0 &&
        line.charCodeAt(0) !== 32 && line.charCodeAt(line.length - 1) !== 32) {
      return line.split(' ');
    }
    const tokens = line.split(this.separator);
    // split leaves an empty token before leading and after trailing separators
    if (tokens.length && tokens[tokens.length - 1] === '') tokens.pop();
    if (tokens.length && tokens[0] === '') tokens.shift();
    return tokens.length ? tokens : null;
  }
}
