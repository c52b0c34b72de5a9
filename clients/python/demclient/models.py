"""The server's records as typed objects: a job, an artifact, a study. Each keeps the JSON it came
from in `raw`, so a field a newer server adds is still there to read."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

FINAL_STATES = frozenset({"succeeded", "failed", "cancelled"})


@dataclass
class Job:
    """A job as GET /api/v1/jobs/{id} answers it (docs/api.md, "The job object")."""

    id: int
    name: str
    state: str
    tags: list[str] = field(default_factory=list)
    progress: float = 0.0
    step: int = 0
    total_steps: int = 0
    time_step: float | None = None
    particles: int = 0
    length_unit: str = "m"
    created_at: str | None = None
    started_at: str | None = None
    finished_at: str | None = None
    steps_per_second: float | None = None
    seconds_left: float | None = None
    stage: str | None = None
    error: str | None = None
    idempotency_key: str | None = None
    resumable: bool = False
    checkpoint_step: int | None = None
    run_seconds: float | None = None
    stream_seconds: float | None = None
    results: dict[str, Any] | None = None
    links: dict[str, str] = field(default_factory=dict)
    replayed: bool = False  # a submission the server matched by its Idempotency-Key: nothing new queued
    raw: dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def finished(self) -> bool:
        """Whether nothing more will happen to the job (succeeded, failed or cancelled)."""
        return self.state in FINAL_STATES

    @classmethod
    def from_json(cls, d: dict[str, Any], replayed: bool = False) -> Job:
        return cls(
            id=int(d["id"]),
            name=str(d.get("name", "")),
            state=str(d.get("state", "")),
            tags=[str(t) for t in d.get("tags", [])],
            progress=float(d.get("progress", 0.0)),
            step=int(d.get("step", 0)),
            total_steps=int(d.get("totalSteps", 0)),
            time_step=d.get("timeStep"),
            particles=int(d.get("particles", 0)),
            length_unit=str(d.get("lengthUnit", "m")),
            created_at=d.get("createdAt"),
            started_at=d.get("startedAt"),
            finished_at=d.get("finishedAt"),
            steps_per_second=d.get("stepsPerSecond"),
            seconds_left=d.get("secondsLeft"),
            stage=d.get("stage"),
            error=d.get("error"),
            idempotency_key=d.get("idempotencyKey"),
            resumable=bool(d.get("resumable", False)),
            checkpoint_step=d.get("checkpointStep"),
            run_seconds=d.get("runSeconds"),
            stream_seconds=d.get("streamSeconds"),
            results=d.get("results"),
            links=dict(d.get("links", {})),
            replayed=replayed,
            raw=d,
        )


@dataclass
class Artifact:
    """One of a job's output files, with its size when it was listed."""

    name: str
    size: int
    url: str

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> Artifact:
        return cls(str(d["name"]), int(d.get("size", 0)), str(d.get("url", "")))


@dataclass
class StudyRun:
    """One run of a study: its number from 1, its job, its parameter values and the job's state."""

    run: int
    job: int | None
    parameters: dict[str, Any]
    state: str
    progress: float = 0.0
    error: str | None = None

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> StudyRun:
        job = d.get("job")
        return cls(
            run=int(d.get("run", 0)),
            job=int(job) if job is not None else None,
            parameters=dict(d.get("parameters", {})),
            state=str(d.get("state", "")),
            progress=float(d.get("progress", 0.0)),
            error=d.get("error"),
        )


@dataclass
class Study:
    """A parameter study as GET /api/v1/studies/{id} answers it (docs/api.md, "Studies")."""

    id: int
    name: str
    finished: bool
    progress: float = 0.0
    summary: str = ""
    combine: str = "grid"
    parameters: list[Any] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=dict)
    jobs: list[StudyRun] = field(default_factory=list)
    created_at: str | None = None
    results: dict[str, str] = field(default_factory=dict)  # the table's and figure's paths
    replayed: bool = False
    raw: dict[str, Any] = field(default_factory=dict, repr=False)

    @classmethod
    def from_json(cls, d: dict[str, Any], replayed: bool = False) -> Study:
        return cls(
            id=int(d["id"]),
            name=str(d.get("name", "")),
            finished=bool(d.get("finished", False)),
            progress=float(d.get("progress", 0.0)),
            summary=str(d.get("summary", "")),
            combine=str(d.get("combine", "grid")),
            parameters=list(d.get("parameters", [])),
            counts={str(k): int(v) for k, v in d.get("counts", {}).items()},
            jobs=[StudyRun.from_json(j) for j in d.get("jobs", [])],
            created_at=d.get("createdAt"),
            results=dict(d.get("results", {})),
            replayed=replayed,
            raw=d,
        )
