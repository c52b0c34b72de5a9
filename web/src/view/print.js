// Printing (the manuals' "print"): before the browser prints, the view goes into #print-sheet as a
// picture with its legend (composePicture), under a caption naming what is shown and when it was
// printed. The print stylesheet (style.css, @media print) shows that sheet and the charts alone.

import { composePicture } from './capture.js';

// "2026-12-06 14:05", local time.
export function timeStamp(date = new Date()) {
  const two = (n) => String(n).padStart(2, '0');
  return `${date.getFullYear()}-${two(date.getMonth() + 1)}-${two(date.getDate())} ${two(date.getHours())}:${two(date.getMinutes())}`;
}

// caption(): what is shown, one line (the saved picture's caption).
export function wirePrint(stage, decorate, caption) {
  const fill = () => {
    const shown = caption();
    const sheet = document.getElementById('print-sheet');
    // nothing shown: no empty frame on the page (a study's charts print alone)
    sheet.classList.toggle('empty', !shown);
    if (!shown) return;
    document.getElementById('print-picture').src = composePicture(stage, decorate).toDataURL('image/png');
    document.getElementById('print-caption').textContent = `${shown} · printed ${timeStamp()}`;
  };
  window.addEventListener('beforeprint', fill);
  document.getElementById('print').addEventListener('click', () => {
    fill();
    window.print();
  });
}
