"""The Frame decoder: its field table against proto/dem.proto, and decoding hand-made messages."""

from __future__ import annotations

import re
import struct
import unittest

from demclient.errors import ProtocolError
from demclient.frames import FRAME_FIELDS, WALL_SHAPE_FIELDS, FrameDecoder, decode_frame
from demclient.protowire import FieldSpec, Schema

from .support import SOURCE_DIR


def proto_message_fields(text: str, message: str) -> dict[int, FieldSpec]:
    """The fields of a top-level message of a .proto file: number -> (name, type, repeated).
    Only the message's own fields: those of messages or enums nested in it are skipped."""
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    start = re.search(rf"\bmessage\s+{message}\s*\{{", text)
    if not start:
        raise AssertionError(f"no message {message} in the .proto")
    depth, pos, body = 1, start.end(), []
    while depth:
        ch = text[pos]
        depth += {"{": 1, "}": -1}.get(ch, 0)
        body.append(ch if depth == 1 else (" " if ch not in "{}" else ch))  # blank nested bodies
        pos += 1
    fields: dict[int, FieldSpec] = {}
    for statement in re.split(r"[;{}]", "".join(body)):
        m = re.fullmatch(r"\s*(repeated\s+|optional\s+)?([\w.]+)\s+(\w+)\s*=\s*(\d+)\s*(\[[^\]]*\])?\s*", statement)
        if m:
            fields[int(m.group(4))] = FieldSpec(m.group(3), m.group(2), (m.group(1) or "").strip() == "repeated")
    return fields


class ProtoTableTest(unittest.TestCase):
    """The decoder's tables are written by hand; these fail when proto/dem.proto moves on."""

    def setUp(self) -> None:
        self.proto = (SOURCE_DIR / "proto" / "dem.proto").read_text(encoding="utf-8")

    def check(self, message: str, table: Schema) -> None:
        in_proto = proto_message_fields(self.proto, message)
        self.assertTrue(in_proto, f"no fields found in message {message}")
        self.assertEqual(dict(table), in_proto, f"demclient/frames.py's table of {message} differs from proto/dem.proto")

    def test_frame_fields_match_the_proto(self) -> None:
        self.check("Frame", FRAME_FIELDS)

    def test_wall_shape_fields_match_the_proto(self) -> None:
        self.check("WallShape", WALL_SHAPE_FIELDS)

    def test_the_proto_reader_sees_nested_definitions_apart(self) -> None:
        text = """message Outer { // a comment = 9;
          message Inner { int32 hidden = 5; }
          enum Kind { A = 0; B = 1; }
          repeated Inner items = 1;
          optional double x = 2 [json_name = "ex"];
        }"""
        self.assertEqual(
            proto_message_fields(text, "Outer"),
            {1: FieldSpec("items", "Inner", True), 2: FieldSpec("x", "double")},
        )


# -- a small protobuf writer, to make frames as the server does -----------------------------------


def varint(n: int) -> bytes:
    n &= (1 << 64) - 1
    out = bytearray()
    while True:
        out.append((n & 0x7F) | (0x80 if n > 0x7F else 0))
        n >>= 7
        if not n:
            return bytes(out)


def field_varint(number: int, value: int) -> bytes:
    return varint(number << 3) + varint(value)


def field_bytes(number: int, payload: bytes) -> bytes:
    return varint(number << 3 | 2) + varint(len(payload)) + payload


def field_double(number: int, value: float) -> bytes:
    return varint(number << 3 | 1) + struct.pack("<d", value)


def floats(*values: float) -> bytes:
    return struct.pack(f"<{len(values)}f", *values)


class DecodeFrameTest(unittest.TestCase):
    def base(self) -> bytes:
        """Everything but radii and force chains, for two particles, as the server's first piece."""
        wall = field_varint(1, 3) + field_bytes(2, floats(*range(18)))
        return (
            field_varint(1, 7)
            + field_varint(2, 120)
            + field_varint(3, 400)
            + field_double(4, 0.25)
            + field_varint(5, 2)
            + field_bytes(6, floats(1, 2, 3, 4, 5, 6))
            + field_bytes(7, floats(0.5, 0, 0, 0, 0, -1))
            + field_bytes(9, struct.pack("<2i", 1, 2))
            + field_bytes(11, wall)
            + field_double(12, 1.5)
            + field_bytes(13, floats(0, 0, 1))
            + field_bytes(14, floats(1, 0, 0, 0))
            + field_bytes(15, b"settle")
            + field_bytes(16, varint(2) + varint(300))  # packed, proto3's way
            + field_varint(17, 1)
        )

    def test_every_field(self) -> None:
        f = decode_frame(self.base())
        self.assertEqual((f.job, f.step, f.total_steps, f.time, f.particle_count), (7, 120, 400, 0.25, 2))
        self.assertEqual(f.positions, [(1.0, 2.0, 3.0), (4.0, 5.0, 6.0)])
        self.assertEqual(f.velocities, [(0.5, 0.0, 0.0), (0.0, 0.0, -1.0)])
        self.assertEqual(f.fragments, [1, 2])
        self.assertEqual(len(f.walls), 1)
        self.assertEqual(f.walls[0].wall, 3)
        self.assertEqual(f.walls[0].triangles[1], ((9.0, 10.0, 11.0), (12.0, 13.0, 14.0), (15.0, 16.0, 17.0)))
        self.assertEqual(f.kinetic_energy, 1.5)
        self.assertEqual(f.clump_positions, [(0.0, 0.0, 1.0)])
        self.assertEqual(f.clump_orientations, [(1.0, 0.0, 0.0, 0.0)])
        self.assertEqual(f.stage, "settle")
        self.assertEqual(f.absent_walls, [2, 300])
        self.assertTrue(f.planar)
        self.assertFalse(f.radii_sent)
        self.assertEqual((f.radii, f.force_chains), ([], []))

    def test_pieces_concatenated_read_as_one_frame(self) -> None:
        # the server sends base, radii and force chains as three messages in one WebSocket message
        radii = field_bytes(8, floats(0.01, 0.02))
        chains = field_bytes(10, struct.pack("<iiff", 0, 1, 2.5, 0.5))
        f = decode_frame(self.base() + radii + chains)
        self.assertTrue(f.radii_sent)
        self.assertEqual(len(f.radii), 2)
        self.assertAlmostEqual(f.radii[1], 0.02, places=7)
        self.assertEqual(f.force_chains, [(0, 1, 2.5, 0.5)])
        self.assertEqual(f.force_chains[0].fn, 2.5)

    def test_later_values_win_and_repeated_fields_append(self) -> None:
        f = decode_frame(field_varint(2, 1) + field_varint(16, 4) + field_varint(2, 9) + field_varint(16, 5))
        self.assertEqual(f.step, 9)
        self.assertEqual(f.absent_walls, [4, 5])  # unpacked repeated values are read too

    def test_unknown_fields_are_skipped(self) -> None:
        future = field_varint(99, 5) + field_bytes(100, b"xyz") + varint(101 << 3 | 5) + b"\0\0\0\0"
        self.assertEqual(decode_frame(future + field_varint(2, 3)).step, 3)

    def test_negative_int64(self) -> None:
        self.assertEqual(decode_frame(field_varint(2, -5)).step, -5)

    def test_an_empty_message_is_a_default_frame(self) -> None:
        f = decode_frame(b"")
        self.assertEqual((f.step, f.particle_count, f.positions, f.stage, f.planar), (0, 0, [], "", False))

    def test_malformed_messages_raise(self) -> None:
        cases = {
            "truncated length": field_bytes(6, floats(1, 2, 3))[:-2],
            "truncated varint": varint(2 << 3) + b"\x80",
            "wrong wire type": field_bytes(2, b"ab"),
            "positions not whole records": field_varint(5, 1) + field_bytes(6, b"\0" * 10),
            "positions for another count": field_varint(5, 2) + field_bytes(6, floats(1, 2, 3)),
            "a group": varint(6 << 3 | 3),
            "field number 0": varint(0) + varint(1),
        }
        for what, data in cases.items():
            with self.subTest(what), self.assertRaises(ProtocolError):
                decode_frame(data)


class FrameDecoderTest(unittest.TestCase):
    def test_radii_carry_over_until_they_change(self) -> None:
        decoder = FrameDecoder()
        count = field_varint(5, 2)
        first = decoder.decode(count + field_varint(2, 1) + field_bytes(8, floats(1, 2)))
        second = decoder.decode(count + field_varint(2, 2))
        third = decoder.decode(count + field_varint(2, 3) + field_bytes(8, floats(3, 4)))
        self.assertEqual((first.radii, first.radii_sent), ([1.0, 2.0], True))
        self.assertEqual((second.radii, second.radii_sent), ([1.0, 2.0], False))
        self.assertEqual((third.radii, third.radii_sent), ([3.0, 4.0], True))


if __name__ == "__main__":
    unittest.main()
