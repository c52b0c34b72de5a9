"""The client of dem-server's REST API (docs/api.md): jobs, their results and files, their live
frames, and parameter studies."""

from __future__ import annotations

import json
import os
import re
import ssl
import time
from pathlib import Path
from typing import Any, Callable, Iterable, Iterator, Union
from urllib.parse import quote, urlencode

from .download import download as _download
from .errors import ProtocolError
from .http import HttpTransport, Response
from .inline import inline_files, resolve_file
from .live import FrameStream
from .models import Artifact, Job, Study
from .websocket import WebSocket

API = "/api/v1"
DEFAULT_SERVER = "http://127.0.0.1:8080"

SpecSource = Union[dict[str, Any], str, "os.PathLike[str]"]

# the server's rule for artifact names (docs/api.md, "Output files")
_ARTIFACT_NAME = re.compile(r"[A-Za-z0-9_\-][A-Za-z0-9._\-]*")


def _job_id(id: int | Job) -> int:
    value = id.id if isinstance(id, Job) else id
    # a bool is an int to Python, but never a job id; a negative one has no path either
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise ValueError(f"a job or study id is a whole number >= 0, got {value!r}")
    return value


def _read_json_file(path: str | os.PathLike[str]) -> Any:
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def _as_object(value: Any, what: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise ProtocolError(f"{what}: expected a JSON object, got {type(value).__name__}")
    return value


def _csv(value: str | Iterable[str] | None) -> str | None:
    if value is None:
        return None
    return value if isinstance(value, str) else ",".join(value)


class Client:
    """A dem-server, at `server` (default: $DEM_SERVER, else http://127.0.0.1:8080) with the bearer
    `token` (default: $DEM_SERVER_TOKEN). `timeout` bounds each network wait, in seconds.

    Errors: a refused request raises ApiError (status, detail, problems); an answer that is not
    what the API promises, ProtocolError; a server that cannot be reached, OSError (TimeoutError
    when it does not answer in time)."""

    def __init__(
        self,
        server: str | None = None,
        token: str | None = None,
        timeout: float = 300.0,
        ssl_context: ssl.SSLContext | None = None,
    ) -> None:
        server = server or os.environ.get("DEM_SERVER") or DEFAULT_SERVER
        token = token if token is not None else os.environ.get("DEM_SERVER_TOKEN")
        self._http = HttpTransport(server.rstrip("/"), token, timeout, ssl_context)
        self._ssl_context = ssl_context

    @property
    def server(self) -> str:
        return self._http.url

    @property
    def timeout(self) -> float:
        return self._http.timeout

    def health(self) -> dict[str, Any]:
        return _as_object(self._http.get_json(f"{API}/health"), "health")

    # -- jobs ------------------------------------------------------------------------------------

    def submit(self, spec: SpecSource, idempotency_key: str | None = None, base_dir: str | None = None) -> Job:
        """Queues a job. `spec` is a dict or the path of a JSON spec file; the mesh and clump
        template files it names are inlined first, read relative to the spec file's folder (for a
        dict, `base_dir`, else the working folder). With `idempotency_key`, a retried submission of
        the same spec gives the job it made (`Job.replayed`) instead of a new one."""
        if isinstance(spec, dict):
            body, folder = spec, base_dir or ""
        elif not isinstance(spec, (str, os.PathLike)):  # an int would be opened as a file descriptor
            raise TypeError(f"spec: a dict or the path of a JSON file, not {type(spec).__name__}")
        else:
            body = _as_object(_read_json_file(spec), os.fspath(spec))
            folder = base_dir if base_dir is not None else os.path.dirname(os.fspath(spec))
        headers = {"Idempotency-Key": idempotency_key} if idempotency_key else {}
        response = self._http.send_json("POST", f"{API}/jobs", inline_files(body, folder), headers)
        return Job.from_json(_as_object(response.json(), "job"), _replayed(response))

    def job(self, id: int | Job) -> Job:
        return Job.from_json(_as_object(self._http.get_json(f"{API}/jobs/{_job_id(id)}"), "job"))

    def jobs(
        self,
        state: str | Iterable[str] | None = None,
        name: str | None = None,
        tag: str | Iterable[str] | None = None,
        page_size: int = 100,
    ) -> Iterator[Job]:
        """Every job that passes the filters, oldest first, fetched a page at a time by following
        the list's `next` links (so jobs added meanwhile come at the end and none repeats).
        `state`: any of these states; `tag`: every one of these tags; `name`: the whole name."""
        if not 1 <= page_size <= 1000:  # checked here, not when the first page is fetched
            raise ValueError(f"page_size must be 1 to 1000, got {page_size}")
        query = {"limit": str(page_size), "state": _csv(state), "name": name, "tag": _csv(tag)}
        # quote: a space as %20 (the server reads "+" as a space too, as form encoding has it)
        present = {k: v for k, v in query.items() if v is not None}
        return self._pages(f"{API}/jobs?" + urlencode(present, quote_via=quote))

    def _pages(self, first: str) -> Iterator[Job]:
        target: str | None = first
        read: set[str] = set()  # a next link back to a page read would list its jobs for ever
        while target:
            if target in read:
                raise ProtocolError(f"job list: the next page is a page already read: {target!r}")
            read.add(target)
            page = _as_object(self._http.get_json(target), "job list")
            for job in page.get("jobs", []):
                yield Job.from_json(job)
            following = page.get("next")
            if following is not None and (not isinstance(following, str) or not following.startswith("/")):
                raise ProtocolError(f"job list: a next link that is not a path: {following!r}")
            target = following

    def cancel(self, id: int | Job) -> Job:
        """Cancels a queued, running or interrupted job (a running one stops within a step)."""
        response = self._http.request("POST", f"{API}/jobs/{_job_id(id)}/cancel")
        return Job.from_json(_as_object(response.json(), "job"))

    def resume(self, id: int | Job) -> Job:
        """Queues an interrupted job again; it continues from its checkpoint."""
        response = self._http.request("POST", f"{API}/jobs/{_job_id(id)}/resume")
        return Job.from_json(_as_object(response.json(), "job"))

    def delete(self, id: int | Job) -> None:
        """Removes a job that is not running, and its files."""
        self._http.request("DELETE", f"{API}/jobs/{_job_id(id)}")

    def wait(
        self,
        id: int | Job,
        progress: Callable[[Job], None] | None = None,
        poll: float = 0.5,
        timeout: float | None = None,
    ) -> Job:
        """Polls the job every `poll` seconds until it has succeeded, failed or been cancelled, and
        returns it; `progress` is called with the job at each poll. An interrupted job is waited
        for too (it ends once someone resumes it). Raises TimeoutError after `timeout` seconds."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            job = self.job(id)
            if progress is not None:
                progress(job)
            if job.finished:
                return job
            if deadline is not None and time.monotonic() >= deadline:
                raise TimeoutError(f"job {job.id} is still {job.state} after {timeout} s")
            time.sleep(poll)

    def results(self, id: int | Job) -> dict[str, Any]:
        """What the run found (its results.json); ApiError 404 before the job has ended."""
        return _as_object(self._http.get_json(f"{API}/jobs/{_job_id(id)}/results"), "results")

    def artifacts(self, id: int | Job) -> list[Artifact]:
        """The job's output files, sorted by name, with their sizes now."""
        listing = _as_object(self._http.get_json(f"{API}/jobs/{_job_id(id)}/artifacts"), "artifacts")
        return [Artifact.from_json(a) for a in listing.get("artifacts", [])]

    def download(self, id: int | Job, name: str, path: str | os.PathLike[str]) -> Path:
        """Streams the artifact `name` to `path` (a file, or a folder to put it in) and returns the
        file's path. A download cut short leaves PATH.part, which the next call continues from
        with a Range request."""
        if not _ARTIFACT_NAME.fullmatch(name):
            raise ValueError(f"not an artifact name (letters, digits, . _ -, not starting with .): {name!r}")
        dest = Path(path)
        if os.fspath(path).endswith(("/", os.sep)) or dest.is_dir():  # a folder: made if missing
            dest.mkdir(parents=True, exist_ok=True)
            dest = dest / name
        else:
            dest.parent.mkdir(parents=True, exist_ok=True)
        return _download(self._http, f"{API}/jobs/{_job_id(id)}/artifacts/{quote(name)}", dest)

    def frames(self, id: int | Job, force_chains: bool = False, idle_timeout: float | None = None) -> FrameStream:
        """The job's live frames over its WebSocket, until the job ends (see FrameStream). A
        queued job's stream waits for it to start; a finished job's ends at once. `idle_timeout`
        bounds the wait for each frame (None: as long as it takes; the stream pings the server
        every 30 s of silence so that the connection is not dropped as idle)."""
        target = f"{API}/jobs/{_job_id(id)}/frames" + ("?forceChains=1" if force_chains else "")
        ws = WebSocket.connect(
            self._http.websocket_url(target), self._http.headers(), self.timeout, ssl_context=self._ssl_context
        )
        ws.timeout = idle_timeout
        return FrameStream(ws)

    # -- studies ---------------------------------------------------------------------------------

    def submit_study(
        self, study: SpecSource, idempotency_key: str | None = None, base_dir: str | None = None
    ) -> Study:
        """Starts a parameter study: a dict or the path of a study file. A `base` that names a spec
        file is read relative to the study file's folder and sent inline, its own files inlined
        relative to its folder (as `dem study --submit` does)."""
        if isinstance(study, dict):
            body, folder = dict(study), base_dir or ""
        else:
            body = dict(_as_object(_read_json_file(study), os.fspath(study)))
            folder = base_dir if base_dir is not None else os.path.dirname(os.fspath(study))
        base = body.get("base")
        if isinstance(base, str):
            base_path = resolve_file(base, folder)
            base = _as_object(_read_json_file(base_path), base_path)
            folder = os.path.dirname(base_path)
        if isinstance(base, dict):
            body["base"] = inline_files(base, folder)
        headers = {"Idempotency-Key": idempotency_key} if idempotency_key else {}
        response = self._http.send_json("POST", f"{API}/studies", body, headers)
        return Study.from_json(_as_object(response.json(), "study"), _replayed(response))

    def study(self, id: int | Study) -> Study:
        return Study.from_json(_as_object(self._http.get_json(f"{API}/studies/{_study_id(id)}"), "study"))

    def studies(self) -> list[Study]:
        listing = _as_object(self._http.get_json(f"{API}/studies"), "study list")
        return [Study.from_json(s) for s in listing.get("studies", [])]

    def study_results(self, id: int | Study) -> dict[str, Any]:
        """The study's table: `rows`, one per run (`run`, `job`, `parameters`, `state`, `error`,
        `results`, null until that job ends)."""
        return _as_object(self._http.get_json(f"{API}/studies/{_study_id(id)}/results.json"), "study table")

    def cancel_study(self, id: int | Study) -> Study:
        response = self._http.request("POST", f"{API}/studies/{_study_id(id)}/cancel")
        return Study.from_json(_as_object(response.json(), "study"))

    def resume_study(self, id: int | Study) -> Study:
        response = self._http.request("POST", f"{API}/studies/{_study_id(id)}/resume")
        return Study.from_json(_as_object(response.json(), "study"))

    def wait_study(
        self,
        id: int | Study,
        progress: Callable[[Study], None] | None = None,
        poll: float = 0.5,
        timeout: float | None = None,
    ) -> Study:
        """Polls the study until every job of it has ended, and returns it."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            study = self.study(id)
            if progress is not None:
                progress(study)
            if study.finished:
                return study
            if deadline is not None and time.monotonic() >= deadline:
                raise TimeoutError(f"study {study.id} is not finished after {timeout} s: {study.summary}")
            time.sleep(poll)


def _study_id(id: int | Study) -> int:
    return _job_id(id.id if isinstance(id, Study) else id)


def _replayed(response: Response) -> bool:
    return response.headers.get("idempotent-replayed", "").lower() == "true"
