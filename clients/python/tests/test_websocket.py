"""The WebSocket client against a scripted server on a loopback socket: the handshake, masking,
fragmented and control frames, closing, and the errors RFC 6455 asks a client to fail on."""

from __future__ import annotations

import json
import socket
import struct
import threading
import unittest
from typing import Callable, Generic, TypeVar

from demclient.errors import ApiError, ProtocolError
from demclient.websocket import BINARY, CLOSE, CONTINUATION, PING, PONG, TEXT, WebSocket, accept_key, encode_frame, mask


def server_frame(opcode: int, payload: bytes, fin: bool = True, rsv: int = 0, masked: bool = False) -> bytes:
    """A frame as a server writes it (unmasked unless asked, to test the client's refusal)."""
    head = bytearray([(0x80 if fin else 0) | rsv | opcode])
    n = len(payload)
    flag = 0x80 if masked else 0
    if n < 126:
        head.append(flag | n)
    elif n < 1 << 16:
        head += bytes([flag | 126]) + struct.pack("!H", n)
    else:
        head += bytes([flag | 127]) + struct.pack("!Q", n)
    if masked:
        return bytes(head) + b"abcd" + mask(payload, b"abcd")
    return bytes(head) + payload


def read_exact(conn: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = conn.recv(n - len(data))
        if not chunk:
            raise ConnectionError("the client closed the connection")
        data += chunk
    return data


def read_client_frame(conn: socket.socket) -> tuple[bool, int, bytes]:
    """A client frame, unmasked; fails the test's server when it is not masked."""
    b0, b1 = read_exact(conn, 2)
    n = b1 & 0x7F
    if n == 126:
        n = struct.unpack("!H", read_exact(conn, 2))[0]
    elif n == 127:
        n = struct.unpack("!Q", read_exact(conn, 8))[0]
    if not b1 & 0x80:
        raise AssertionError("a client frame that is not masked")
    key = read_exact(conn, 4)
    return bool(b0 & 0x80), b0 & 0x0F, mask(read_exact(conn, n), key)


T = TypeVar("T")


class ScriptedServer(Generic[T]):
    """Accepts one connection, answers its handshake (or not), then runs `script` on it in a
    thread; what the script returns or raises is kept for the test to check."""

    def __init__(self, script: Callable[[socket.socket], T], answer: bytes | None = None) -> None:
        self.listener = socket.create_server(("127.0.0.1", 0))
        self.port = self.listener.getsockname()[1]
        self.script = script
        self.answer = answer
        self.request = b""
        self.result: T | None = None
        self.error: BaseException | None = None
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    @property
    def url(self) -> str:
        return f"ws://127.0.0.1:{self.port}/api/v1/jobs/1/frames"

    def _run(self) -> None:
        try:
            conn, _ = self.listener.accept()
            with conn:
                conn.settimeout(10)
                while b"\r\n\r\n" not in self.request:
                    self.request += conn.recv(4096)
                if self.answer is not None:
                    conn.sendall(self.answer)
                    return
                key = next(
                    line.split(b":", 1)[1].strip().decode()
                    for line in self.request.split(b"\r\n")
                    if line.lower().startswith(b"sec-websocket-key:")
                )
                conn.sendall(
                    b"HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                    + f"Sec-WebSocket-Accept: {accept_key(key)}\r\n\r\n".encode()
                )
                self.result = self.script(conn)
        except BaseException as e:  # kept for the test: a thread's exception is otherwise lost
            self.error = e
        finally:
            self.listener.close()

    def join(self) -> T:
        self.thread.join(10)
        if self.error:
            raise self.error
        if self.thread.is_alive():
            raise AssertionError("the scripted server is still running")
        return self.result  # type: ignore[return-value]  # None only for scripts that return None


class WebSocketTest(unittest.TestCase):
    def test_rfc_examples(self) -> None:
        # RFC 6455 1.3 (the accept key) and 5.7 (a masked "Hello")
        self.assertEqual(accept_key("dGhlIHNhbXBsZSBub25jZQ=="), "s3pPLMBiTxaQ9kYGzzhZRbK+xOo=")
        self.assertEqual(
            encode_frame(TEXT, b"Hello", key=bytes.fromhex("37fa213d")), bytes.fromhex("818537fa213d7f9f4d5158")
        )
        self.assertEqual(mask(mask(b"any bytes at all", b"wxyz"), b"wxyz"), b"any bytes at all")

    def test_fragments_pings_and_the_closing_handshake(self) -> None:
        big = bytes(range(256)) * 300  # 76,800 bytes: a 64-bit length in the last fragment
        middle = b"m" * 200  # a 16-bit length

        def script(conn: socket.socket) -> list[tuple[bool, int, bytes]]:
            conn.sendall(
                server_frame(BINARY, b"head", fin=False)
                + server_frame(PING, b"are you there")  # control frames may come between fragments
                + server_frame(CONTINUATION, middle, fin=False)
                + server_frame(CONTINUATION, big)
                + server_frame(TEXT, "déjà".encode())
                + server_frame(CLOSE, struct.pack("!H", 1000) + b"job succeeded")
            )
            return [read_client_frame(conn), read_client_frame(conn)]

        server = ScriptedServer(script)
        ws = WebSocket.connect(server.url, {"Authorization": "Bearer t0ken"}, timeout=10)
        first = ws.recv()
        second = ws.recv()
        self.assertIsNone(ws.recv())
        self.assertEqual(first.data if first else None, b"head" + middle + big)
        self.assertEqual(second.data if second else None, "déjà")
        self.assertEqual((ws.close_code, ws.close_reason, ws.closed), (1000, "job succeeded", True))
        pong, close = server.join()
        self.assertEqual(pong, (True, PONG, b"are you there"))
        self.assertEqual(close, (True, CLOSE, struct.pack("!H", 1000)))  # the code echoed
        request = server.request.decode()
        self.assertIn("GET /api/v1/jobs/1/frames HTTP/1.1\r\n", request)
        self.assertIn("Authorization: Bearer t0ken\r\n", request)
        self.assertIn("Sec-WebSocket-Version: 13\r\n", request)

    def test_the_client_closes_and_sends_text(self) -> None:
        def script(conn: socket.socket) -> list[tuple[bool, int, bytes]]:
            got = [read_client_frame(conn), read_client_frame(conn)]
            conn.sendall(server_frame(BINARY, b"late") + server_frame(CLOSE, got[1][2]))
            return got

        server = ScriptedServer(script)
        ws = WebSocket.connect(server.url, timeout=10)
        ws.send_text(json.dumps({"forceChains": True}))
        ws.close(1000, "bye")
        self.assertTrue(ws.closed)
        self.assertIsNone(ws.recv())
        text, close = server.join()
        self.assertEqual(text, (True, TEXT, b'{"forceChains": true}'))
        self.assertEqual(close, (True, CLOSE, struct.pack("!H", 1000) + b"bye"))
        self.assertEqual(ws.close_code, 1000)

    def test_a_silent_server_gets_pings_and_the_wait_ends(self) -> None:
        def script(conn: socket.socket) -> list[int]:
            opcodes = [read_client_frame(conn)[1]]
            while opcodes[-1] != CLOSE:  # silent until the client gives up and closes
                opcodes.append(read_client_frame(conn)[1])
            return opcodes

        server = ScriptedServer(script)
        ws = WebSocket.connect(server.url, timeout=10)
        ws.keepalive = 0.05
        ws.timeout = 0.5
        with self.assertRaises(TimeoutError):
            ws.recv()
        ws.close(wait=0)
        opcodes = server.join()
        self.assertGreaterEqual(opcodes.count(PING), 2)
        self.assertEqual(opcodes[-1], CLOSE)

    def test_a_refused_handshake_raises_the_servers_problem(self) -> None:
        body = json.dumps({"status": 404, "title": "Not Found", "detail": "no job 1", "error": "no job 1"}).encode()
        answer = (
            b"HTTP/1.1 404 Not Found\r\nContent-Type: application/problem+json\r\n"
            + f"Content-Length: {len(body)}\r\n\r\n".encode()
            + body
        )
        server = ScriptedServer(lambda conn: None, answer=answer)
        with self.assertRaises(ApiError) as caught:
            WebSocket.connect(server.url, timeout=10)
        self.assertEqual((caught.exception.status, caught.exception.detail), (404, "no job 1"))
        server.join()

    def test_a_wrong_accept_key_is_refused(self) -> None:
        answer = b"HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Accept: x\r\n\r\n"
        server = ScriptedServer(lambda conn: None, answer=answer)
        with self.assertRaises(ProtocolError):
            WebSocket.connect(server.url, timeout=10)
        server.join()

    def test_frames_a_client_must_fail_on(self) -> None:
        cases = {
            "masked by the server": server_frame(BINARY, b"x", masked=True),
            "reserved bits": server_frame(BINARY, b"x", rsv=0x40),
            "reserved opcode": server_frame(0x3, b"x"),
            "continuation of nothing": server_frame(CONTINUATION, b"x"),
            "fragmented ping": server_frame(PING, b"x", fin=False),
            "new message inside a fragmented one": server_frame(BINARY, b"a", fin=False) + server_frame(TEXT, b"b"),
            "text that is not UTF-8": server_frame(TEXT, b"\xff\xfe"),
            "one-byte close": server_frame(CLOSE, b"\x03"),
        }
        for what, data in cases.items():
            with self.subTest(what):

                def script(conn: socket.socket, data: bytes = data) -> tuple[bool, int, bytes]:
                    conn.sendall(data)
                    return read_client_frame(conn)

                server = ScriptedServer(script)
                ws = WebSocket.connect(server.url, timeout=10)
                with self.assertRaises(ProtocolError):
                    ws.recv()
                self.assertTrue(ws.closed)
                fin, opcode, payload = server.join()
                self.assertEqual(opcode, CLOSE)  # the client said why before it closed
                self.assertIn(struct.unpack("!H", payload[:2])[0], (1002, 1007))

    def test_a_message_over_the_limit_is_refused(self) -> None:
        def script(conn: socket.socket) -> tuple[bool, int, bytes]:
            conn.sendall(server_frame(BINARY, b"x" * 2000))
            return read_client_frame(conn)

        server = ScriptedServer(script)
        ws = WebSocket.connect(server.url, timeout=10, max_message=1000)
        with self.assertRaises(ProtocolError):
            ws.recv()
        self.assertEqual(server.join(), (True, CLOSE, struct.pack("!H", 1009)))

    def test_a_dropped_connection_is_an_error_not_an_end(self) -> None:
        server = ScriptedServer(lambda conn: conn.sendall(server_frame(BINARY, b"x", fin=False)))
        ws = WebSocket.connect(server.url, timeout=10)
        with self.assertRaises(ConnectionError):
            ws.recv()
        self.assertEqual(ws.close_code, 1006)
        server.join()


if __name__ == "__main__":
    unittest.main()
