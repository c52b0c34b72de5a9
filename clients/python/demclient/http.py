"""HTTP requests to dem-server: one connection per request (as the dem command's client), the
bearer token on each, error answers turned into ApiError."""

from __future__ import annotations

import http.client
import json
import ssl
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Iterator, Mapping
from urllib.parse import urlsplit

from .errors import ApiError, ProtocolError

# An API answer is JSON the client holds in memory: past this it is refused, not read (the dem
# command's limit). Downloads are streamed and not bounded by it.
MAX_ANSWER_BYTES = 256 << 20


@dataclass
class Response:
    status: int
    reason: str
    headers: dict[str, str] = field(default_factory=dict)  # names in lower case
    body: bytes = b""

    def json(self) -> Any:
        try:
            return json.loads(self.body.decode("utf-8"))
        except (UnicodeDecodeError, ValueError) as e:
            raise ProtocolError(f"the server's answer ({self.status}) is not JSON: {e}") from None


class HttpTransport:
    """Where the server is and how to reach it; knows nothing of the API's resources."""

    def __init__(self, server: str, token: str | None, timeout: float, ssl_context: ssl.SSLContext | None = None) -> None:
        parts = urlsplit(server)
        if parts.scheme not in ("http", "https") or not parts.hostname:
            raise ValueError(f"the server must be an http:// or https:// URL, got {server!r}")
        if parts.path not in ("", "/") or parts.query:
            # the server's links (Location, next, artifact urls) are paths from the root
            raise ValueError(f"the server URL must have no path, got {server!r}")
        self.secure = parts.scheme == "https"
        self.host = parts.hostname
        self.port = parts.port or (443 if self.secure else 80)
        self.token = token or None
        self.timeout = timeout
        self.ssl_context = ssl_context
        self.url = f"{parts.scheme}://{parts.netloc}"

    def headers(self, extra: Mapping[str, str] | None = None) -> dict[str, str]:
        """The bearer token's header, and `extra`."""
        out = {"Authorization": f"Bearer {self.token}"} if self.token else {}
        out.update(extra or {})
        return out

    def websocket_url(self, target: str) -> str:
        return ("wss" if self.secure else "ws") + self.url[self.url.index(":") :] + target

    def _connection(self) -> http.client.HTTPConnection:
        if self.secure:
            return http.client.HTTPSConnection(self.host, self.port, timeout=self.timeout, context=self.ssl_context)
        return http.client.HTTPConnection(self.host, self.port, timeout=self.timeout)

    @contextmanager
    def open(
        self, method: str, target: str, body: bytes | None = None, headers: Mapping[str, str] | None = None
    ) -> Iterator[http.client.HTTPResponse]:
        """Sends the request and yields the answer unread, for the caller to stream; the
        connection is closed after the block. Raises ApiError for any status >= 400."""
        connection = self._connection()
        try:
            connection.request(method, target, body=body, headers=self.headers(headers))
            answer = connection.getresponse()
            if answer.status >= 400:
                headers = {k.lower(): v for k, v in answer.getheaders()}
                raise ApiError.from_response(answer.status, answer.reason, _read_limited(answer), headers)
            yield answer
        finally:
            connection.close()

    def request(
        self,
        method: str,
        target: str,
        body: bytes | None = None,
        content_type: str | None = None,
        headers: Mapping[str, str] | None = None,
    ) -> Response:
        """A whole request and answer. Raises ApiError for any status >= 400."""
        extra = {"Accept": "application/json", **(headers or {})}
        if content_type:
            extra["Content-Type"] = content_type
        with self.open(method, target, body, extra) as answer:
            return Response(
                answer.status, answer.reason, {k.lower(): v for k, v in answer.getheaders()}, _read_limited(answer)
            )

    def get_json(self, target: str) -> Any:
        return self.request("GET", target).json()

    def send_json(self, method: str, target: str, payload: Any = None, headers: Mapping[str, str] | None = None) -> Response:
        # allow_nan=False: NaN is not JSON, and the server would refuse the body as malformed
        body = None if payload is None else json.dumps(payload, allow_nan=False).encode("utf-8")
        return self.request(method, target, body, "application/json" if body is not None else None, headers)


def _read_limited(answer: http.client.HTTPResponse) -> bytes:
    length = answer.getheader("Content-Length")
    if length and length.isdigit() and int(length) > MAX_ANSWER_BYTES:
        raise ProtocolError(f"the server's answer is {length} bytes, over the client's limit of {MAX_ANSWER_BYTES}")
    body = answer.read(MAX_ANSWER_BYTES + 1)
    if len(body) > MAX_ANSWER_BYTES:
        raise ProtocolError(f"the server's answer is over the client's limit of {MAX_ANSWER_BYTES} bytes")
    return body
