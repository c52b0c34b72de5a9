"""A job's live frames over its WebSocket, as an iterator of decoded Frames."""

from __future__ import annotations

import json
from typing import Iterator

from .frames import Frame, FrameDecoder
from .websocket import WebSocket


class FrameStream:
    """Iterates over a job's live frames until the server closes the socket (the job ended, was
    deleted, or the server stops); `close_code` and `close_reason` then say why (1000,
    "job succeeded"). Use it in a ``with`` block, or call close(), to leave early."""

    def __init__(self, socket: WebSocket) -> None:
        self._ws = socket
        self._decoder = FrameDecoder()

    @property
    def close_code(self) -> int | None:
        return self._ws.close_code

    @property
    def close_reason(self) -> str:
        return self._ws.close_reason

    def set_force_chains(self, enabled: bool) -> None:
        """Asks for force chains in later frames, or stops them (the server's text message)."""
        self._ws.send_text(json.dumps({"forceChains": enabled}))

    def __iter__(self) -> Iterator[Frame]:
        return self

    def __next__(self) -> Frame:
        while True:
            message = self._ws.recv()
            if message is None:
                raise StopIteration
            if isinstance(message.data, bytes):  # the server sends no text; ignore any
                return self._decoder.decode(message.data)

    def close(self) -> None:
        self._ws.close()

    def __enter__(self) -> FrameStream:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
