"""Streaming an artifact to a file, resumable: the bytes go to DEST.part and DEST.part is renamed
to DEST once whole, so DEST is never half a file. A DEST.part left by a download cut short is
continued with a Range request; the ETag of the version it holds (in DEST.part.etag) goes along as
If-Range, so that a file that changed since (a running job's) is fetched whole again instead of
being spliced from two versions."""

from __future__ import annotations

import os
import re
from pathlib import Path

from .errors import ApiError, ProtocolError
from .http import HttpTransport

_CHUNK = 1 << 16
_CONTENT_RANGE = re.compile(r"bytes (\d+)-(\d+)/(\d+)")


def _remove(path: Path) -> None:
    try:
        path.unlink()
    except FileNotFoundError:
        pass


def download(transport: HttpTransport, target: str, dest: Path) -> Path:
    part = dest.with_name(dest.name + ".part")
    etag_file = dest.with_name(dest.name + ".part.etag")
    have = part.stat().st_size if part.exists() else 0
    headers: dict[str, str] = {}
    if have:
        headers["Range"] = f"bytes={have}-"
        if etag_file.exists():
            headers["If-Range"] = etag_file.read_text(encoding="ascii").strip()
    try:
        with transport.open("GET", target, headers=headers) as answer:
            if answer.status == 206:
                m = _CONTENT_RANGE.fullmatch(answer.getheader("Content-Range", ""))
                if not m or int(m.group(1)) != have:
                    raise ProtocolError(f"{target}: asked for bytes from {have}, got {answer.getheader('Content-Range')!r}")
                mode = "ab"
            elif answer.status == 200:  # the whole file: no range asked, or the file changed since
                mode, have = "wb", 0
            else:
                raise ProtocolError(f"{target}: unexpected answer {answer.status} to a download")
            etag = answer.getheader("ETag")
            if etag:
                etag_file.write_text(etag, encoding="ascii")
            else:
                _remove(etag_file)
            expected = answer.getheader("Content-Length")
            received = 0
            with open(part, mode) as out:
                while chunk := answer.read(_CHUNK):
                    out.write(chunk)
                    received += len(chunk)
            if expected is not None and expected.isdigit() and received != int(expected):
                raise ProtocolError(f"{target}: got {received} of {expected} bytes; call download again to continue")
    except ApiError as e:
        # 416: the part already holds the whole file (Content-Range: bytes */SIZE)
        whole = re.fullmatch(r"bytes \*/(\d+)", e.headers.get("content-range", ""))
        if e.status != 416 or not whole:
            raise
        if int(whole.group(1)) != have:  # the part is longer than the file is now: start again
            _remove(part)
            _remove(etag_file)
            return download(transport, target, dest)
    os.replace(part, dest)
    _remove(etag_file)
    return dest
