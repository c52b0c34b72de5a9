"""Inlining a spec's files: the mesh and clump template readers, and which fields get inlined.
(That the result is the very spec `dem submit` sends is checked against the server in
test_server.py.)"""

from __future__ import annotations

import os
import shutil
import struct
import unittest
from typing import Any, Sequence

from demclient.errors import SpecFileError
from demclient.inline import file_references, inline_files
from demclient.meshes import MeshFileError, parse_fortran_real, parse_legacy_mesh, parse_stl, read_clump_template

from .support import temporary_folder

SQUARE_DAT = "4 2\n-1.5D-1 -.15 0.\n1.5E-1,-0.15,0\n+.15 1.5-1 0.0\n\n-0.15\t0.15 0d0\r\n1 2 3\n1.0 3 4\n"
SQUARE = [(-0.15, -0.15, 0.0), (0.15, -0.15, 0.0), (0.15, 0.15, 0.0), (-0.15, 0.15, 0.0)]


def binary_stl(triangles: Sequence[Sequence[tuple[float, float, float]]], header: bytes = b"solid exported") -> bytes:
    data = header.ljust(80, b" ") + struct.pack("<I", len(triangles))
    for t in triangles:
        data += struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *p) for p in t) + b"\0\0"
    return data


class FortranRealTest(unittest.TestCase):
    def test_the_forms_docs_formats_md_lists(self) -> None:
        valid = {"7.547503e+002": 754.7503, "1.0E9": 1e9, "1.0D9": 1e9, "1.0d-3": 1e-3, ".5": 0.5, "5.": 5.0,
                 "+3": 3.0, "-3.25": -3.25, "1.0-100": 1e-100, "2+3": 2000.0}  # fmt: skip
        for token, value in valid.items():
            self.assertEqual(parse_fortran_real(token), value, token)
        for token in ["1.2.3", "1.0e", "abc", "nan", "inf", "", ".", "+", "e5", "1e400", "1e-400", "5x", "1_0", "1" * 200]:
            self.assertIsNone(parse_fortran_real(token), token)


class LegacyMeshTest(unittest.TestCase):
    def test_fortran_numbers_commas_and_blank_lines(self) -> None:
        mesh = parse_legacy_mesh(SQUARE_DAT, "floor.dat")
        self.assertEqual(mesh.vertices, SQUARE)
        self.assertEqual(mesh.triangles, [(0, 1, 2), (0, 2, 3)])

    def test_errors_name_the_file_and_line(self) -> None:
        cases = {
            "": "t.dat: the file is empty",
            "3 1\n0 0 0\n1 0 0\n": "t.dat: the file ends after 2 of 3 vertices (truncated, last line 3)",
            "3 1\n0 0 0\n1 0 0\n0 1 0\n1 2 7\n": "t.dat line 5: triangle 1 refers to vertex 7, but the vertices are numbered 1 to 3",
            "3 1\n0 0 0\n1 0 x\n0 1 0\n1 2 3\n": 't.dat line 3: expected a number, got "x"',
            "3 1\n0 0 0\n1 0 0\n0 1 0\n0 1 2\n": 't.dat line 5: a vertex index (the first vertex is 1) must be a whole number >= 1, got "0"',
            "3 1\n0 0 0\n1 0 0\n0 1 0\n1 2 3\n1 2 3\n": "t.dat line 6: more lines than the 3 vertices and 1 triangles of line 1",
            "3 0\n": "t.dat line 1: the mesh has no triangles",
        }  # fmt: skip
        for text, message in cases.items():
            with self.subTest(message), self.assertRaises(MeshFileError) as caught:
                parse_legacy_mesh(text, "t.dat")
            self.assertEqual(str(caught.exception), message)


class StlTest(unittest.TestCase):
    TRIANGLES = [(SQUARE[0], SQUARE[1], SQUARE[2]), (SQUARE[0], SQUARE[2], SQUARE[3])]

    def test_ascii_corners_shared_by_facets_are_merged(self) -> None:
        facets = "".join(
            "facet normal 0 0 1\n outer loop\n" + "".join(f"  vertex {x} {y} {z}\n" for x, y, z in t) + " endloop\nendfacet\n"
            for t in self.TRIANGLES
        )
        mesh = parse_stl(f"solid square\n{facets}endsolid square\n".encode(), "s.stl")
        self.assertEqual(mesh.vertices, SQUARE)
        self.assertEqual(mesh.triangles, [(0, 1, 2), (0, 2, 3)])

    def test_binary_even_with_solid_in_its_header(self) -> None:
        mesh = parse_stl(binary_stl(self.TRIANGLES, b"solid but binary"), "s.stl")
        f = struct.unpack("<f", struct.pack("<f", 0.15))[0]  # float32 corners, widened exactly
        self.assertEqual(mesh.vertices, [(-f, -f, 0.0), (f, -f, 0.0), (f, f, 0.0), (-f, f, 0.0)])
        self.assertEqual(mesh.triangles, [(0, 1, 2), (0, 2, 3)])

    def test_errors(self) -> None:
        with self.assertRaisesRegex(MeshFileError, r"^s.stl: binary STL header says 2 triangles, but the file holds only 1 \(truncated\)$"):
            parse_stl(binary_stl(self.TRIANGLES)[:-50], "s.stl")
        with self.assertRaisesRegex(MeshFileError, r"^s.stl line 6: a facet with more than 3 vertices$"):
            parse_stl(b"solid\nfacet\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\nendfacet\n", "s.stl")


class ClumpTemplateTest(unittest.TestCase):
    def setUp(self) -> None:
        self.dir = temporary_folder("demclient-clump-")
        self.addCleanup(shutil.rmtree, self.dir)

    def read(self, text: str) -> list[Any]:
        path = self.dir / "t.txt"
        path.write_text(text)
        return read_clump_template(str(path))

    def test_comments_commas_and_blanks(self) -> None:
        self.assertEqual(
            self.read("# two spheres\n-0.006, 0, 0, 0.01\n\n0.006 0 0 1e-2  # right\n"),
            [((-0.006, 0.0, 0.0), 0.01), ((0.006, 0.0, 0.0), 0.01)],
        )

    def test_errors(self) -> None:
        path = self.dir / "t.txt"
        cases = {
            "0 0 0\n": f'{path} line 1: expected four numbers "x y z r"',
            "0 0 0 1 2\n": f'{path} line 1: expected four numbers "x y z r"',
            "+1 0 0 1\n": f'{path} line 1: expected four numbers "x y z r"',  # as std::from_chars
            "0 0 0 inf\n": f'{path} line 1: expected four numbers "x y z r"',
            "# only\n0 0 0 0\n": f"{path} line 2: the radius must be positive",
            "# nothing\n": f"clump template {path} has no spheres",
        }
        for text, message in cases.items():
            with self.subTest(text), self.assertRaises(MeshFileError) as caught:
                self.read(text)
            self.assertEqual(str(caught.exception), message)


class InlineFilesTest(unittest.TestCase):
    def setUp(self) -> None:
        self.dir = temporary_folder("demclient-inline-")
        self.addCleanup(shutil.rmtree, self.dir)
        (self.dir / "floor.dat").write_text(SQUARE_DAT)
        (self.dir / "box.stl").write_bytes(binary_stl(StlTest.TRIANGLES))
        (self.dir / "pair.txt").write_text("-1 0 0 1\n1 0 0 1\n")

    def spec(self) -> dict[str, Any]:
        return {
            "walls": [{"name": "floor", "mesh": {"file": "floor.dat", "format": "LEGACY", "scale": 2}},
                      {"name": "plane", "plane": {}}],
            "packings": [{"inside": {"file": "box.stl"}}],
            "lattices": [{"inside": {"file": "box.stl", "format": 2}}],
            "stages": [{"name": "load", "add_walls": [{"name": "lid", "mesh": {"file": str(self.dir / "floor.dat")}}]}],
            "clump_shapes": [{"name": "pair", "file": "pair.txt", "scale": 0.01}],
        }  # fmt: skip

    def test_every_kind_of_file_is_inlined_and_the_rest_kept(self) -> None:
        spec = self.spec()
        self.assertEqual(
            file_references(spec),
            ["walls[0].mesh.file", "packings[0].inside.file", "lattices[0].inside.file",
             "stages[0].addWalls[0].mesh.file", "clumpShapes[0].file"],
        )  # fmt: skip
        out = inline_files(spec, str(self.dir))
        self.assertEqual(file_references(out), [])
        self.assertEqual(spec, self.spec(), "the caller's spec is left as it was")
        floor = out["walls"][0]["mesh"]
        self.assertEqual(floor["scale"], 2)  # placing kept; file and format gone
        self.assertNotIn("format", floor)
        self.assertEqual(floor["vertices"][1], {"x": 0.15, "y": -0.15, "z": 0.0})
        self.assertEqual(floor["triangles"], [{"i": 1, "j": 2, "k": 3}, {"i": 1, "j": 3, "k": 4}])  # 1-based
        self.assertEqual(len(out["packings"][0]["inside"]["vertices"]), 4)
        self.assertEqual(len(out["lattices"][0]["inside"]["triangles"]), 2)
        self.assertEqual(out["stages"][0]["add_walls"][0]["mesh"]["vertices"], floor["vertices"])  # absolute path
        self.assertEqual(out["clump_shapes"][0]["spheres"][0], {"center": {"x": -1.0, "y": 0.0, "z": 0.0}, "radius": 1.0})
        self.assertEqual(out["clump_shapes"][0]["scale"], 0.01)
        self.assertEqual(out["walls"][1], {"name": "plane", "plane": {}})

    def test_files_that_cannot_be_read_are_named_by_field(self) -> None:
        spec = {"walls": [{"mesh": {"file": "missing.dat"}}], "clumpShapes": [{"name": "p", "file": "nope.txt"}]}
        with self.assertRaises(SpecFileError) as caught:
            inline_files(spec, str(self.dir))
        self.assertEqual(
            caught.exception.problems,
            [f"walls[0].mesh.file: {self.dir / 'missing.dat'}: cannot open the file",
             f"clumpShapes[0].file: cannot open clump template {self.dir / 'nope.txt'}"],
        )  # fmt: skip

    def test_a_mesh_with_both_a_file_and_inline_content_is_left_for_the_server_to_refuse(self) -> None:
        spec = {"walls": [{"mesh": {"file": "floor.dat", "vertices": [{"x": 1}], "triangles": [{"i": 1, "j": 1, "k": 1}]}}]}
        self.assertEqual(inline_files(spec, str(self.dir)), spec)

    def test_relative_names_without_a_folder_are_read_from_the_working_folder(self) -> None:
        self.addCleanup(os.chdir, os.getcwd())
        os.chdir(self.dir)
        spec = {"walls": [{"mesh": {"file": "floor.dat"}}]}
        self.assertEqual(len(inline_files(spec)["walls"][0]["mesh"]["vertices"]), 4)


if __name__ == "__main__":
    unittest.main()
