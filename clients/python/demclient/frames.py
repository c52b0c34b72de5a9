"""Live frames of a job (proto/dem.proto, messages Frame and WallShape), as plain Python objects."""

from __future__ import annotations

import struct
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from .errors import ProtocolError
from .protowire import FieldSpec, Schema, decode_message

# Field numbers and types as in proto/dem.proto; tests/test_frames.py reads the .proto and fails
# when they differ, so a renumbered or retyped field is caught before it decodes into nonsense.
FRAME_FIELDS: Schema = {
    1: FieldSpec("job", "int64"),
    2: FieldSpec("step", "int64"),
    3: FieldSpec("total_steps", "int64"),
    4: FieldSpec("time", "double"),
    5: FieldSpec("particle_count", "uint32"),
    6: FieldSpec("positions", "bytes"),
    7: FieldSpec("velocities", "bytes"),
    8: FieldSpec("radii", "bytes"),
    9: FieldSpec("fragments", "bytes"),
    10: FieldSpec("force_chains", "bytes"),
    11: FieldSpec("walls", "WallShape", repeated=True),
    12: FieldSpec("kinetic_energy", "double"),
    13: FieldSpec("clump_positions", "bytes"),
    14: FieldSpec("clump_orientations", "bytes"),
    15: FieldSpec("stage", "string"),
    16: FieldSpec("absent_walls", "uint32", repeated=True),
    17: FieldSpec("planar", "bool"),
}

WALL_SHAPE_FIELDS: Schema = {
    1: FieldSpec("wall", "uint32"),
    2: FieldSpec("triangles", "bytes"),
}

SCHEMAS: dict[str, Schema] = {"Frame": FRAME_FIELDS, "WallShape": WALL_SHAPE_FIELDS}

Vec3 = tuple[float, float, float]
Quaternion = tuple[float, float, float, float]  # w, x, y, z
Triangle = tuple[Vec3, Vec3, Vec3]


class ForceChain(NamedTuple):
    """A contact's force: particles i and j (0-based ids), normal and tangential force, N."""

    i: int
    j: int
    fn: float
    ft: float


@dataclass
class WallShape:
    """A plate's or moving mesh's triangles in this frame; `wall` indexes the spec's walls (then
    the stages' addWalls)."""

    wall: int
    triangles: list[Triangle] = field(default_factory=list)


@dataclass
class Frame:
    """One live frame. Arrays are one entry per particle in particle-id order (the spec's order).

    `radii` are the last radii the stream was sent: the server sends them in a viewer's first
    frame and then only when they change (growth), and FrameDecoder carries them over;
    `radii_sent` says whether this frame brought them. `force_chains` are empty unless asked for,
    and even then come only with the steps of the job's file frames.
    """

    job: int = 0
    step: int = 0
    total_steps: int = 0
    time: float = 0.0
    particle_count: int = 0
    positions: list[Vec3] = field(default_factory=list)
    velocities: list[Vec3] = field(default_factory=list)
    radii: list[float] = field(default_factory=list)
    radii_sent: bool = False
    fragments: list[int] = field(default_factory=list)
    force_chains: list[ForceChain] = field(default_factory=list)
    walls: list[WallShape] = field(default_factory=list)
    kinetic_energy: float = 0.0
    clump_positions: list[Vec3] = field(default_factory=list)
    clump_orientations: list[Quaternion] = field(default_factory=list)
    stage: str = ""
    absent_walls: list[int] = field(default_factory=list)
    planar: bool = False


def _records(data: bytes, fmt: str, what: str) -> list[Any]:
    """Little-endian fixed-size records, each a tuple (or a plain value for one-item records)."""
    layout = struct.Struct("<" + fmt)
    if len(data) % layout.size:
        raise ProtocolError(f"frame: {what} holds {len(data)} bytes, not a whole number of {layout.size}-byte records")
    if len(fmt) == 1:
        return list(struct.unpack(f"<{len(data) // layout.size}{fmt}", data))
    return list(layout.iter_unpack(data))


def _per_particle(values: list[Any], count: int, what: str) -> list[Any]:
    if values and len(values) != count:
        raise ProtocolError(f"frame: {len(values)} {what} for {count} particles")
    return values


def decode_frame(data: bytes) -> Frame:
    """Decodes one Frame message as it stands (radii only if it carries them)."""
    raw = decode_message(data, FRAME_FIELDS, SCHEMAS)
    count = int(raw.get("particle_count", 0))
    radii = raw.get("radii")
    walls = []
    for wall in raw.get("walls", []):
        corners: list[Vec3] = _records(wall.get("triangles", b""), "3f", "a wall's triangles")
        if len(corners) % 3:
            raise ProtocolError(f"frame: wall {wall.get('wall', 0)} has {len(corners)} corners, not whole triangles")
        walls.append(
            WallShape(int(wall.get("wall", 0)), [(corners[k], corners[k + 1], corners[k + 2]) for k in range(0, len(corners), 3)])
        )
    return Frame(
        job=int(raw.get("job", 0)),
        step=int(raw.get("step", 0)),
        total_steps=int(raw.get("total_steps", 0)),
        time=float(raw.get("time", 0.0)),
        particle_count=count,
        positions=_per_particle(_records(raw.get("positions", b""), "3f", "positions"), count, "positions"),
        velocities=_per_particle(_records(raw.get("velocities", b""), "3f", "velocities"), count, "velocities"),
        radii=_per_particle(_records(radii, "f", "radii"), count, "radii") if radii is not None else [],
        radii_sent=radii is not None,
        fragments=_per_particle(_records(raw.get("fragments", b""), "i", "fragments"), count, "fragments"),
        force_chains=[ForceChain(*r) for r in _records(raw.get("force_chains", b""), "iiff", "force chains")],
        walls=walls,
        kinetic_energy=float(raw.get("kinetic_energy", 0.0)),
        clump_positions=_records(raw.get("clump_positions", b""), "3f", "clump positions"),
        clump_orientations=_records(raw.get("clump_orientations", b""), "4f", "clump orientations"),
        stage=str(raw.get("stage", "")),
        absent_walls=[int(w) for w in raw.get("absent_walls", [])],
        planar=bool(raw.get("planar", False)),
    )


class FrameDecoder:
    """Decodes a stream's frames in order, carrying the radii over the frames that leave them out."""

    def __init__(self) -> None:
        self._radii: list[float] = []

    def decode(self, data: bytes) -> Frame:
        frame = decode_frame(data)
        if frame.radii_sent:
            self._radii = frame.radii
        else:
            frame.radii = list(self._radii)
        return frame
