"""A minimal protobuf wire-format reader, by field number, for the few messages the client decodes.

Only what proto/dem.proto's Frame needs: varints, 64- and 32-bit fixed values and length-delimited
fields (bytes, strings, nested messages, packed repeated scalars). A schema is a table from field
number to FieldSpec, written by hand from the .proto; tests/test_frames.py checks it against the
.proto so that the two cannot drift apart silently.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from typing import Any, Iterator, Mapping

from .errors import ProtocolError

VARINT, FIXED64, LENGTH_DELIMITED, START_GROUP, END_GROUP, FIXED32 = 0, 1, 2, 3, 4, 5

# The wire type each scalar type is written with (protobuf encoding guide).
SCALAR_WIRE_TYPES: dict[str, int] = {
    "int32": VARINT, "int64": VARINT, "uint32": VARINT, "uint64": VARINT, "bool": VARINT,
    "sint32": VARINT, "sint64": VARINT, "enum": VARINT,
    "double": FIXED64, "fixed64": FIXED64, "sfixed64": FIXED64,
    "float": FIXED32, "fixed32": FIXED32, "sfixed32": FIXED32,
    "bytes": LENGTH_DELIMITED, "string": LENGTH_DELIMITED,
}  # fmt: skip


@dataclass(frozen=True)
class FieldSpec:
    """One field of a message: its name in the .proto, its type (a scalar type or a message name
    in the schema registry), and whether it is repeated."""

    name: str
    type: str
    repeated: bool = False


Schema = Mapping[int, FieldSpec]


def read_varint(data: memoryview, pos: int) -> tuple[int, int]:
    """The varint at `pos` and the position after it."""
    result = 0
    shift = 0
    while True:
        if pos >= len(data):
            raise ProtocolError("protobuf: a varint runs past the end of the message")
        byte = data[pos]
        pos += 1
        result |= (byte & 0x7F) << shift
        if not byte & 0x80:
            return result, pos
        shift += 7
        if shift >= 70:  # ten bytes hold any 64-bit value; more is garbage, not a bigger number
            raise ProtocolError("protobuf: a varint longer than ten bytes")


def iter_fields(data: memoryview) -> Iterator[tuple[int, int, int | memoryview]]:
    """(field number, wire type, value) for each field in order: an int for varints and fixed
    values, a view of the payload for length-delimited fields."""
    pos = 0
    end = len(data)
    while pos < end:
        key, pos = read_varint(data, pos)
        number, wire = key >> 3, key & 7
        if number == 0:
            raise ProtocolError("protobuf: field number 0")
        value: int | memoryview
        if wire == VARINT:
            value, pos = read_varint(data, pos)
        elif wire == FIXED64:
            if pos + 8 > end:
                raise ProtocolError(f"protobuf: field {number} runs past the end of the message")
            value = int.from_bytes(data[pos : pos + 8], "little")
            pos += 8
        elif wire == FIXED32:
            if pos + 4 > end:
                raise ProtocolError(f"protobuf: field {number} runs past the end of the message")
            value = int.from_bytes(data[pos : pos + 4], "little")
            pos += 4
        elif wire == LENGTH_DELIMITED:
            length, pos = read_varint(data, pos)
            if pos + length > end:
                raise ProtocolError(f"protobuf: field {number} runs past the end of the message")
            value = data[pos : pos + length]
            pos += length
        else:  # groups are deprecated and never in dem.proto
            raise ProtocolError(f"protobuf: field {number} has wire type {wire}, which this reader does not take")
        yield number, wire, value


def _signed(value: int, bits: int) -> int:
    return value - (1 << bits) if value >= 1 << (bits - 1) else value


def _scalar(kind: str, wire: int, value: int | memoryview) -> Any:
    """A scalar field's value from its wire form."""
    if isinstance(value, memoryview):
        if kind == "bytes":
            return value.tobytes()
        if kind == "string":
            try:
                return str(value, "utf-8")
            except UnicodeDecodeError as e:
                raise ProtocolError(f"protobuf: a string field is not UTF-8: {e}") from None
        raise AssertionError(kind)
    if kind in ("int64", "int32", "enum"):
        # int32 and enums are sign-extended to 64 bits on the wire, so both read as int64
        return _signed(value & 0xFFFFFFFFFFFFFFFF, 64)
    if kind == "uint32":
        return value & 0xFFFFFFFF
    if kind == "uint64":
        return value & 0xFFFFFFFFFFFFFFFF
    if kind == "bool":
        return value != 0
    if kind in ("sint32", "sint64"):
        return (value >> 1) ^ -(value & 1)  # zigzag
    if kind == "double":
        return struct.unpack("<d", value.to_bytes(8, "little"))[0]
    if kind == "float":
        return struct.unpack("<f", value.to_bytes(4, "little"))[0]
    if kind in ("fixed64", "fixed32"):
        return value
    if kind == "sfixed64":
        return _signed(value, 64)
    if kind == "sfixed32":
        return _signed(value, 32)
    raise AssertionError(kind)


def _packed(kind: str, payload: memoryview) -> list[Any]:
    """The values of a packed repeated scalar field."""
    wire = SCALAR_WIRE_TYPES[kind]
    values: list[Any] = []
    pos = 0
    if wire == VARINT:
        while pos < len(payload):
            raw, pos = read_varint(payload, pos)
            values.append(_scalar(kind, wire, raw))
        return values
    size = 8 if wire == FIXED64 else 4
    if len(payload) % size:
        raise ProtocolError(f"protobuf: a packed {kind} field of {len(payload)} bytes")
    for pos in range(0, len(payload), size):
        values.append(_scalar(kind, wire, int.from_bytes(payload[pos : pos + size], "little")))
    return values


def decode_message(data: bytes | memoryview, schema: Schema, registry: Mapping[str, Schema]) -> dict[str, Any]:
    """The fields of one message by name, with protobuf's merge rules: a singular field given
    several times keeps its last value, nested messages merge, repeated fields append. That is also
    how concatenated messages read as one (the server sends a frame in up to three pieces).
    Unknown fields are skipped, so a newer server's additions do not break an older client."""
    out: dict[str, Any] = {}
    for number, wire, value in iter_fields(memoryview(data)):
        spec = schema.get(number)
        if spec is None:
            continue
        nested = registry.get(spec.type)
        if nested is not None:
            if not isinstance(value, memoryview):
                raise ProtocolError(f"protobuf: field {spec.name} should be a message, got wire type {wire}")
            message = decode_message(value, nested, registry)
            if spec.repeated:
                out.setdefault(spec.name, []).append(message)
            else:
                out[spec.name] = {**out.get(spec.name, {}), **message}  # shallow merge: enough for dem.proto
            continue
        expected = SCALAR_WIRE_TYPES[spec.type]
        if spec.repeated and expected != LENGTH_DELIMITED and isinstance(value, memoryview):
            out.setdefault(spec.name, []).extend(_packed(spec.type, value))  # packed, proto3's default
            continue
        if wire != expected:
            raise ProtocolError(f"protobuf: field {spec.name} ({spec.type}) came with wire type {wire}")
        decoded = _scalar(spec.type, wire, value)
        if spec.repeated:
            out.setdefault(spec.name, []).append(decoded)
        else:
            out[spec.name] = decoded
    return out
