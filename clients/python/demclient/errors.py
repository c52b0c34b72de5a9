"""The errors the client raises: the server's refusals, and answers it cannot make sense of."""

from __future__ import annotations

import json
from typing import Any


class DemError(Exception):
    """Base of every error this package raises, so one ``except`` can catch them all."""


class ApiError(DemError):
    """The server refused a request: its RFC 9457 problem detail, as fields.

    ``detail`` is what went wrong, ``problems`` the ``"field.path: message"`` lines of an invalid
    spec or study (empty otherwise), ``body`` the decoded problem object (``{}`` when the answer
    was not JSON, as with a WebSocket handshake Beast itself refuses), ``headers`` the answer's.
    """

    def __init__(
        self,
        status: int,
        detail: str,
        problems: list[str] | None = None,
        body: dict[str, Any] | None = None,
        headers: dict[str, str] | None = None,
    ) -> None:
        self.status = status
        self.detail = detail
        self.problems: list[str] = list(problems or [])
        self.body: dict[str, Any] = dict(body or {})
        self.headers: dict[str, str] = dict(headers or {})  # lower-case names: Retry-After, Content-Range, ...
        text = f"{status}: {detail}"
        if self.problems:
            text += "\n  " + "\n  ".join(self.problems)
        super().__init__(text)

    @property
    def title(self) -> str:
        return str(self.body.get("title", ""))

    @property
    def instance(self) -> str:
        return str(self.body.get("instance", ""))

    @classmethod
    def from_response(cls, status: int, reason: str, payload: bytes, headers: dict[str, str] | None = None) -> ApiError:
        """Builds the error from an answer's status and body, whatever form the body has."""
        body: dict[str, Any] = {}
        try:
            decoded = json.loads(payload.decode("utf-8"))
            if isinstance(decoded, dict):
                body = decoded
        except (UnicodeDecodeError, ValueError):
            pass
        # `detail` is RFC 9457's; `error` is what servers before it answered (docs/api.md, Errors)
        detail = body.get("detail") or body.get("error")
        if not isinstance(detail, str) or not detail:
            text = payload.decode("utf-8", "replace").strip()
            detail = text[:500] if text else reason or "HTTP error"
        raw_problems = body.get("problems")
        problems = [str(p) for p in raw_problems] if isinstance(raw_problems, list) else []
        return cls(status, detail, problems, body, headers)


class ProtocolError(DemError):
    """The server's answer is not what the API promises (not JSON, a broken WebSocket frame, ...)."""


class SpecFileError(DemError):
    """A file a spec names (a mesh, a clump template) could not be read for inlining.

    ``problems`` are ``"field.path.file: reason"`` lines, as ``dem submit`` prints them.
    """

    def __init__(self, problems: list[str]) -> None:
        self.problems = list(problems)
        super().__init__("cannot inline the spec's files:\n  " + "\n  ".join(self.problems))
