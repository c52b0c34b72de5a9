"""A minimal blocking WebSocket client (RFC 6455) on a plain socket: the handshake, masked sends,
fragmented and control frames, and the closing handshake. No extensions, no subprotocols: the
server's frames WebSocket uses neither."""

from __future__ import annotations

import base64
import hashlib
import os
import socket
import ssl
import struct
import time
from dataclasses import dataclass
from typing import Mapping, NoReturn
from urllib.parse import urlsplit

from .errors import ApiError, ProtocolError

_GUID = "258EAFA5-E914-47DA-95CA-C5AB0DC85B11"  # RFC 6455 section 1.3

CONTINUATION, TEXT, BINARY, CLOSE, PING, PONG = 0x0, 0x1, 0x2, 0x8, 0x9, 0xA
_DATA_OPCODES = (CONTINUATION, TEXT, BINARY)
_CONTROL_OPCODES = (CLOSE, PING, PONG)

# close codes (RFC 6455 section 7.4.1)
NORMAL_CLOSURE, PROTOCOL_ERROR, INVALID_DATA, MESSAGE_TOO_BIG = 1000, 1002, 1007, 1009
NO_STATUS = 1005  # what a close frame without a code reports; never sent


@dataclass
class Message:
    """One whole data message: `data` is str for a text message, bytes for a binary one."""

    data: str | bytes

    @property
    def is_binary(self) -> bool:
        return isinstance(self.data, bytes)


def mask(payload: bytes, key: bytes) -> bytes:
    """XORs the payload with the repeated 4-byte key (RFC 6455 5.3); its own inverse."""
    if not payload:
        return b""
    # one big-integer XOR instead of a Python loop per byte: megabytes stay fast
    repeated = (key * (len(payload) // 4 + 1))[: len(payload)]
    return (int.from_bytes(payload, "little") ^ int.from_bytes(repeated, "little")).to_bytes(len(payload), "little")


def encode_frame(opcode: int, payload: bytes, fin: bool = True, key: bytes | None = None) -> bytes:
    """A client frame (masked, as RFC 6455 5.1 requires of every client frame)."""
    key = os.urandom(4) if key is None else key
    head = bytearray([(0x80 if fin else 0) | opcode])
    n = len(payload)
    if n < 126:
        head.append(0x80 | n)
    elif n < 1 << 16:
        head.append(0x80 | 126)
        head += struct.pack("!H", n)
    else:
        head.append(0x80 | 127)
        head += struct.pack("!Q", n)
    return bytes(head) + key + mask(payload, key)


def accept_key(key: str) -> str:
    """The Sec-WebSocket-Accept a server must answer to `key`."""
    return base64.b64encode(hashlib.sha1((key + _GUID).encode("ascii")).digest()).decode("ascii")


class WebSocket:
    """A connected client WebSocket. recv() gives whole messages and answers pings; it returns
    None once the server has closed, with `close_code` and `close_reason` set."""

    def __init__(self, sock: socket.socket, buffered: bytes = b"", max_message: int = 256 << 20) -> None:
        self._sock = sock
        self._buffer = bytearray(buffered)
        self.max_message = max_message
        self.timeout: float | None = None  # for a whole message; None: wait as long as it takes
        self.keepalive: float | None = 30.0  # send a ping after this many silent seconds
        self.close_code: int | None = None
        self.close_reason = ""
        self._close_sent = False
        self._closed = False
        self._last_sent = time.monotonic()
        self._fragments: list[bytes] = []
        self._fragment_opcode: int | None = None
        self._fragment_size = 0

    # -- opening ---------------------------------------------------------------------------------

    @classmethod
    def connect(
        cls,
        url: str,
        headers: Mapping[str, str] | None = None,
        timeout: float | None = 30.0,
        max_message: int = 256 << 20,
        ssl_context: ssl.SSLContext | None = None,
    ) -> WebSocket:
        """Opens `url` (ws:// or wss://). A server that answers the handshake with anything but
        101 raises ApiError from its answer (a 404 problem detail for an unknown job, say)."""
        parts = urlsplit(url)
        if parts.scheme not in ("ws", "wss") or not parts.hostname:
            raise ValueError(f"not a ws:// or wss:// URL: {url}")
        secure = parts.scheme == "wss"
        port = parts.port or (443 if secure else 80)
        target = (parts.path or "/") + (f"?{parts.query}" if parts.query else "")
        sock = socket.create_connection((parts.hostname, port), timeout=timeout)
        try:
            if secure:
                context = ssl_context or ssl.create_default_context()
                sock = context.wrap_socket(sock, server_hostname=parts.hostname)
            key = base64.b64encode(os.urandom(16)).decode("ascii")
            host = parts.hostname if ":" not in parts.hostname else f"[{parts.hostname}]"
            if parts.port:
                host += f":{parts.port}"
            lines = [
                f"GET {target} HTTP/1.1",
                f"Host: {host}",
                "Upgrade: websocket",
                "Connection: Upgrade",
                f"Sec-WebSocket-Key: {key}",
                "Sec-WebSocket-Version: 13",
            ]
            for name, value in (headers or {}).items():
                if any(c in f"{name}{value}" for c in "\r\n\0"):  # would smuggle in headers of its own
                    raise ValueError(f"a header with a line break: {name!r}")
                lines.append(f"{name}: {value}")
            sock.sendall(("\r\n".join(lines) + "\r\n\r\n").encode("latin-1"))
            status, reason, answer, rest = _read_handshake(sock)
            if status != 101:
                raise ApiError.from_response(status, reason, _read_body(sock, answer, rest), answer)
            if answer.get("upgrade", "").lower() != "websocket" or "upgrade" not in answer.get("connection", "").lower():
                raise ProtocolError("WebSocket handshake: the answer does not upgrade the connection to websocket")
            if answer.get("sec-websocket-accept") != accept_key(key):
                raise ProtocolError("WebSocket handshake: wrong Sec-WebSocket-Accept")
            if answer.get("sec-websocket-extensions"):  # we offered none, so none may be used
                raise ProtocolError("WebSocket handshake: the server chose extensions the client did not offer")
            ws = cls(sock, rest, max_message)
            ws.timeout = timeout
            return ws
        except BaseException:
            sock.close()
            raise

    # -- sending ---------------------------------------------------------------------------------

    def _send_frame(self, opcode: int, payload: bytes, fin: bool = True) -> None:
        self._sock.settimeout(30.0)  # a send to a stuck peer must not hang forever
        self._sock.sendall(encode_frame(opcode, payload, fin))
        self._last_sent = time.monotonic()

    def send_text(self, text: str) -> None:
        self._send_frame(TEXT, text.encode("utf-8"))

    def send_binary(self, data: bytes) -> None:
        self._send_frame(BINARY, data)

    def ping(self, payload: bytes = b"") -> None:
        self._send_frame(PING, payload[:125])

    # -- receiving -------------------------------------------------------------------------------

    def _parse_frame(self) -> tuple[bool, int, bytes] | None:
        """The first whole frame in the buffer (fin, opcode, payload), consumed; None until one has
        arrived. Parsing only whole frames lets a read that times out mid-frame be resumed."""
        buf = self._buffer
        if len(buf) < 2:
            return None
        b0, b1 = buf[0], buf[1]
        fin, rsv, opcode = bool(b0 & 0x80), b0 & 0x70, b0 & 0x0F
        if rsv:
            self._fail(PROTOCOL_ERROR, "a frame with reserved bits set (no extension was agreed)")
        if opcode not in _DATA_OPCODES + _CONTROL_OPCODES:
            self._fail(PROTOCOL_ERROR, f"a frame with the reserved opcode {opcode:#x}")
        if b1 & 0x80:
            self._fail(PROTOCOL_ERROR, "a masked frame from the server (RFC 6455 5.1)")
        length, pos = b1 & 0x7F, 2
        if length == 126:
            if len(buf) < 4:
                return None
            length, pos = struct.unpack_from("!H", buf, 2)[0], 4
        elif length == 127:
            if len(buf) < 10:
                return None
            length, pos = struct.unpack_from("!Q", buf, 2)[0], 10
            if length >> 63:
                self._fail(PROTOCOL_ERROR, "a frame length with its top bit set")
        if opcode in _CONTROL_OPCODES and (not fin or length > 125):
            self._fail(PROTOCOL_ERROR, "a fragmented or oversized control frame")
        if opcode in _DATA_OPCODES and self._fragment_size + length > self.max_message:
            self._fail(MESSAGE_TOO_BIG, f"a message over {self.max_message} bytes")
        if len(buf) < pos + length:
            return None
        payload = bytes(buf[pos : pos + length])
        del buf[: pos + length]
        return fin, opcode, payload

    def _next_frame(self) -> tuple[bool, int, bytes]:
        while True:
            frame = self._parse_frame()
            if frame is not None:
                return frame
            chunk = self._sock.recv(1 << 18)
            if not chunk:
                self._closed = True
                self._sock.close()
                if self.close_code is None:
                    self.close_code = 1006  # abnormal closure: the connection dropped without a close frame
                raise ConnectionError("the server closed the connection without a WebSocket close frame")
            self._buffer += chunk

    def recv(self) -> Message | None:
        """The next whole message, or None once the connection is closed. Raises TimeoutError
        when `timeout` seconds pass without a whole message."""
        if self._closed:
            return None
        deadline = None if self.timeout is None else time.monotonic() + self.timeout
        while True:
            now = time.monotonic()
            wait = None if deadline is None else max(deadline - now, 0.0)
            if self.keepalive is not None and not self._close_sent:
                until_ping = max(self._last_sent + self.keepalive - now, 0.01)
                wait = until_ping if wait is None else min(wait, until_ping)
            self._sock.settimeout(wait)
            try:
                fin, opcode, payload = self._next_frame()
            except TimeoutError:
                now = time.monotonic()
                if deadline is not None and now >= deadline:
                    raise TimeoutError(f"no WebSocket message in {self.timeout} s") from None
                # A viewer of a queued job hears nothing for as long as the queue takes; a ping
                # now and then keeps proxies and NAT tables from dropping the quiet connection.
                if self.keepalive is not None and not self._close_sent and now - self._last_sent >= self.keepalive:
                    self.ping(b"keepalive")
                continue
            message = self._on_frame(fin, opcode, payload)
            if message is not None or self._closed:
                return message

    def _on_frame(self, fin: bool, opcode: int, payload: bytes) -> Message | None:
        if opcode == PING:
            if not self._close_sent:
                self._send_frame(PONG, payload)
            return None
        if opcode == PONG:
            return None
        if opcode == CLOSE:
            self._on_close(payload)
            return None
        if opcode == CONTINUATION:
            if self._fragment_opcode is None:
                self._fail(PROTOCOL_ERROR, "a continuation frame with no message to continue")
        else:
            if self._fragment_opcode is not None:
                self._fail(PROTOCOL_ERROR, "a new message before the previous one's last fragment")
            self._fragment_opcode = opcode
        self._fragments.append(payload)
        self._fragment_size += len(payload)
        if not fin:
            return None
        data, kind = b"".join(self._fragments), self._fragment_opcode
        self._fragments, self._fragment_opcode, self._fragment_size = [], None, 0
        if self._close_sent:  # closing: what was still on its way is dropped
            return None
        if kind == TEXT:
            try:
                return Message(data.decode("utf-8"))
            except UnicodeDecodeError:
                self._fail(INVALID_DATA, "a text message that is not UTF-8")
        return Message(data)

    def _on_close(self, payload: bytes) -> None:
        if len(payload) == 1:
            self._fail(PROTOCOL_ERROR, "a close frame with a one-byte payload")
        code = struct.unpack("!H", payload[:2])[0] if payload else NO_STATUS
        try:
            reason = payload[2:].decode("utf-8")
        except UnicodeDecodeError:
            self._fail(INVALID_DATA, "a close reason that is not UTF-8")
        self.close_code, self.close_reason = code, reason
        if not self._close_sent:  # answer with the same code (RFC 6455 5.5.1)
            try:
                self._send_frame(CLOSE, payload[:2])
            except OSError:
                pass
            self._close_sent = True
        self._shutdown()

    def _fail(self, code: int, why: str) -> NoReturn:
        """Fails the connection (RFC 6455 7.1.7): a close frame if it can still go out, then the
        socket is closed and ProtocolError raised."""
        if not self._close_sent and not self._closed:
            try:
                self._send_frame(CLOSE, struct.pack("!H", code))
            except OSError:
                pass
            self._close_sent = True
        self.close_code, self.close_reason = code, why
        self._shutdown()
        raise ProtocolError(f"WebSocket: {why}")

    def _shutdown(self) -> None:
        self._closed = True
        try:
            self._sock.close()
        except OSError:
            pass

    # -- closing ---------------------------------------------------------------------------------

    @property
    def closed(self) -> bool:
        return self._closed

    def close(self, code: int = NORMAL_CLOSURE, reason: str = "", wait: float = 2.0) -> None:
        """Starts the closing handshake and waits up to `wait` seconds for the server's close
        frame, dropping any data still on its way; then closes the socket."""
        if self._closed:
            return
        try:
            if not self._close_sent:
                self._send_frame(CLOSE, struct.pack("!H", code) + reason.encode("utf-8")[:123])
                self._close_sent = True
            deadline = time.monotonic() + wait
            while not self._closed:
                left = deadline - time.monotonic()
                if left <= 0:
                    break
                self._sock.settimeout(left)
                fin, opcode, payload = self._next_frame()
                self._on_frame(fin, opcode, payload)
        except (OSError, ProtocolError):
            pass  # closing anyway: a peer that misbehaves now changes nothing
        finally:
            self._shutdown()

    def __enter__(self) -> WebSocket:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _read_handshake(sock: socket.socket) -> tuple[int, str, dict[str, str], bytes]:
    """Reads the handshake answer's head: status, reason, headers (lower-case names), and the
    bytes that came after it (the first frames, or an error body)."""
    data = b""
    while b"\r\n\r\n" not in data:
        if len(data) > 64 << 10:
            raise ProtocolError("WebSocket handshake: an answer head over 64 KB")
        chunk = sock.recv(4096)
        if not chunk:
            raise ProtocolError("WebSocket handshake: the server closed the connection before answering")
        data += chunk
    head, rest = data.split(b"\r\n\r\n", 1)
    lines = head.decode("latin-1").split("\r\n")
    status_line = lines[0].split(" ", 2)
    if len(status_line) < 2 or not status_line[0].startswith("HTTP/") or not status_line[1].isdigit():
        raise ProtocolError(f"WebSocket handshake: not an HTTP answer: {lines[0][:100]!r}")
    headers: dict[str, str] = {}
    for line in lines[1:]:
        name, _, value = line.partition(":")
        headers[name.strip().lower()] = value.strip()
    return int(status_line[1]), status_line[2] if len(status_line) > 2 else "", headers, rest


def _read_body(sock: socket.socket, headers: Mapping[str, str], rest: bytes, limit: int = 1 << 20) -> bytes:
    """The body of a refused handshake, as far as Content-Length says (or until the server closes)."""
    length = headers.get("content-length", "")
    want = int(length) if length.isdigit() else limit
    body = rest
    try:
        while len(body) < min(want, limit):
            chunk = sock.recv(min(want, limit) - len(body))
            if not chunk:
                break
            body += chunk
    except OSError:
        pass  # what arrived is enough to tell the error
    return body[:want]
