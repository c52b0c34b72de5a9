// The Web Worker that parses dropped or chosen files off the main thread, so the page keeps
// drawing while a 150 MB ANIMATION_3D.dat is read. Message in: { id, file }. Messages out:
//   { id, type: 'progress', fraction }  while reading
//   { id, type: 'done', result }        result as parse.js's ChunkedParse.finish(); the typed
//                                       arrays are transferred, not copied
//   { id, type: 'failed', error }       an unexpected exception (a bug or an unreadable file)

import { parseBlob, transferables } from './parse.js';

self.onmessage = async (event) => {
  const { id, file } = event.data;
  try {
    let last = 0;
    const result = await parseBlob(file, (fraction) => {
      if (fraction - last >= 0.01 || fraction === 1) { // at most ~100 messages a file
        last = fraction;
        self.postMessage({ id, type: 'progress', fraction });
      }
    });
    self.postMessage({ id, type: 'done', result }, transferables(result));
  } catch (error) {
    self.postMessage({ id, type: 'failed', error: String(error && error.message ? error.message : error) });
  }
};
