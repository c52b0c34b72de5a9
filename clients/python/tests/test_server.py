"""The client against the real dem-server: one server for the module, on a free loopback port in a
temporary data folder, running small jobs (a few hundred steps of a pouring, under a second each).
The binaries come from DEM_BINARY_DIR (default /work/main/build)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import time
import unittest
import uuid
from unittest import mock
from pathlib import Path
from typing import Any

from demclient import ApiError, Client, Frame, Job, ProtocolError, SpecFileError, Study

from .support import BINARY_DIR, ServerProcess, dem_run, pouring_spec, require_binaries, temporary_folder
from .test_inline import SQUARE_DAT, binary_stl

server: ServerProcess | None = None
work = Path()


def setUpModule() -> None:
    global server, work
    require_binaries()
    work = temporary_folder("demclient-server-")
    server = ServerProcess(work / "data")


def tearDownModule() -> None:
    if server is not None:
        server.stop()
    shutil.rmtree(work, ignore_errors=True)


def new_client() -> Client:
    assert server is not None
    return Client(server.url, token="", timeout=30)  # "": no token, whatever the environment says


def wait_for_state(client: Client, job: Job, state: str, seconds: float = 30) -> Job:
    end = time.monotonic() + seconds
    while (current := client.job(job)).state != state:
        if time.monotonic() > end or current.finished:
            raise AssertionError(f"job {job.id} is {current.state}, not {state}")
        time.sleep(0.02)
    return current


def write_json(path: Path, value: Any) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(value, indent=1))
    return path


def mesh_folder(folder: Path) -> None:
    """A floor in the legacy mesh format (Fortran numbers), a closed box as binary STL, and a
    clump template: every kind of file a spec can name."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "floor.dat").write_text(SQUARE_DAT)
    lo, hi = (-0.05, -0.05, 0.1), (0.05, 0.05, 0.2)
    v = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    (folder / "block.stl").write_bytes(binary_stl([t for a, b, c, d in faces for t in ((v[a], v[b], v[c]), (v[a], v[c], v[d]))]))
    (folder / "pair.txt").write_text("# two spheres\n-0.006, 0, 0, 0.01\n0.006 0 0 0.01  # right\n")


def spec_with_files() -> dict[str, Any]:
    spec = pouring_spec(300, 100, name="inline")
    del spec["lattices"]
    spec["walls"] = [{"name": "floor", "material": "steel", "mesh": {"file": "floor.dat"}}]
    spec["packings"] = [{"material": "granite", "inside": {"file": "block.stl"}, "count": 30,
                         "sizes": {"dMin": 0.008, "dMax": 0.012, "mean": 0.01}}]  # fmt: skip
    spec["clumpShapes"] = [{"name": "pair", "file": "pair.txt"}]
    spec["clumps"] = [{"shape": "pair", "material": "granite", "position": {"x": 0.1, "z": 0.05}},
                      {"shape": "pair", "material": "granite", "position": {"x": -0.1, "z": 0.05}}]  # fmt: skip
    return spec


class FinishedJobTest(unittest.TestCase):
    """A job run to its end on the server, and the same spec run by `dem run`."""

    client: Client
    job: Job
    polled: list[Job]
    folder: Path

    @classmethod
    def setUpClass(cls) -> None:
        cls.client = new_client()
        cls.folder = work / "finished"
        spec_file = write_json(cls.folder / "spec.json", pouring_spec(400, 100, name="finished", tags=["finished"]))
        submitted = cls.client.submit(spec_file)
        dem_run(spec_file, cls.folder / "local")  # beside the server's run, on the other core
        cls.polled = []
        cls.job = cls.client.wait(submitted, progress=cls.polled.append, poll=0.05)

    def test_wait_follows_the_job_to_its_end(self) -> None:
        self.assertEqual(self.job.state, "succeeded")
        self.assertEqual((self.job.step, self.job.total_steps, self.job.progress), (400, 400, 1.0))
        self.assertEqual(self.polled[-1].state, "succeeded")
        progress = [j.progress for j in self.polled]
        self.assertEqual(progress, sorted(progress))
        self.assertTrue({j.state for j in self.polled} <= {"queued", "running", "succeeded"})
        self.assertEqual(self.job.tags, ["finished"])
        self.assertEqual(self.job.links["frames"], f"/api/v1/jobs/{self.job.id}/frames")

    def test_results_are_the_results_json_artifact_and_the_local_runs(self) -> None:
        results = self.client.results(self.job)
        self.assertEqual(results, self.job.results)
        downloaded = self.client.download(self.job, "results.json", self.folder / "results-server.json")
        self.assertEqual(json.loads(downloaded.read_text()), results)
        local = json.loads((self.folder / "local" / "results.json").read_text())
        self.assertEqual(results["status"], "completed")
        # the same spec finds the same, but for the wall time it took
        self.assertEqual({**local, "runSeconds": 0}, {**results, "runSeconds": 0})

    def test_artifacts_are_the_bytes_dem_run_writes(self) -> None:
        artifacts = {a.name: a for a in self.client.artifacts(self.job)}
        self.assertIn("outputs.tar", artifacts)
        local = {p.name for p in (self.folder / "local").iterdir()}
        compared = sorted(set(artifacts) & local - {"results.json"})  # results.json: its runSeconds differ
        self.assertIn("ANIMATION_3D.dat", compared)
        self.assertIn("particles.pvd", compared)
        into = self.folder / "downloads"
        into.mkdir()
        for name in compared:
            with self.subTest(name):
                path = self.client.download(self.job, name, into)  # a folder: the file goes in it
                self.assertEqual(path, into / name)
                self.assertEqual(path.stat().st_size, artifacts[name].size)
                self.assertEqual(path.read_bytes(), (self.folder / "local" / name).read_bytes())
        self.assertEqual(list(into.glob("*.part*")), [])

    def test_a_download_into_a_folder_not_there_yet_makes_it(self) -> None:
        # an independent tester's finding: "runs/demo/" (the README's example) raised
        # FileNotFoundError, and "out/" wrote a file named out
        whole = (self.folder / "local" / "Energy.dat").read_bytes()
        into = self.folder / "new" / "folder"
        path = self.client.download(self.job, "Energy.dat", str(into) + "/")
        self.assertEqual(path, into / "Energy.dat")
        self.assertEqual(path.read_bytes(), whole)
        deep = self.folder / "deep" / "missing" / "energy.txt"
        self.assertEqual(self.client.download(self.job, "Energy.dat", deep).read_bytes(), whole)

    def test_a_spec_of_another_type_is_refused_and_nothing_is_read(self) -> None:
        read_end, write_end = os.pipe()
        os.write(write_end, b"{}")
        os.close(write_end)
        try:
            with self.assertRaises(TypeError):
                self.client.submit(read_end)  # type: ignore[arg-type]
            os.fstat(read_end)  # still open: it was not taken for a file to read
        finally:
            os.close(read_end)

    def test_a_next_link_back_to_a_page_read_is_a_protocol_error(self) -> None:
        calls = []

        def page(target: str) -> dict[str, Any]:
            calls.append(target)
            if len(calls) > 10:  # the loop the client must stop: fail, not hang
                raise AssertionError("the client followed a looping next link 10 times")
            return {"jobs": [], "next": "/api/v1/jobs?after=1"}

        with mock.patch.object(self.client._http, "get_json", side_effect=page):
            with self.assertRaises(ProtocolError):
                list(self.client.jobs())

    def test_a_partial_download_is_continued_with_a_range_request(self) -> None:
        whole = (self.folder / "local" / "ANIMATION_3D.dat").read_bytes()
        dest = self.folder / "resumed" / "ANIMATION_3D.dat"
        dest.parent.mkdir()
        part = dest.with_name(dest.name + ".part")
        half = len(whole) // 2
        # a part of the right length but other bytes: only a range request keeps them as they are
        part.write_bytes(b"#" * half)
        self.client.download(self.job, "ANIMATION_3D.dat", dest)
        self.assertEqual(dest.read_bytes(), b"#" * half + whole[half:])
        self.assertFalse(part.exists())
        # the same with the ETag of another version: If-Range makes the server send the whole file
        part.write_bytes(b"#" * half)
        dest.with_name(dest.name + ".part.etag").write_text('"another-version"')
        self.client.download(self.job, "ANIMATION_3D.dat", dest)
        self.assertEqual(dest.read_bytes(), whole)
        # a part that is already whole: the server answers 416 and the part becomes the file
        part.write_bytes(whole)
        self.client.download(self.job, "ANIMATION_3D.dat", dest)
        self.assertEqual(dest.read_bytes(), whole)
        self.assertEqual(sorted(p.name for p in dest.parent.iterdir()), ["ANIMATION_3D.dat"])

    def test_a_finished_job_cannot_be_cancelled_or_resumed(self) -> None:
        for action in (self.client.cancel, self.client.resume):
            with self.subTest(action.__name__), self.assertRaises(ApiError) as caught:
                action(self.job)
            self.assertEqual(caught.exception.status, 409)

    def test_a_finished_jobs_frames_end_at_once(self) -> None:
        with self.client.frames(self.job) as stream:
            self.assertEqual(list(stream), [])
        self.assertEqual(stream.close_code, 1000)
        self.assertTrue(stream.close_reason)


class PagingTest(unittest.TestCase):
    client: Client
    ids: list[int]

    @classmethod
    def setUpClass(cls) -> None:
        cls.client = new_client()
        jobs = [cls.client.submit(pouring_spec(20, 10, name=f"page {k}", tags=["paging", f"k:{k}"])) for k in range(5)]
        cls.client.submit(pouring_spec(20, 10, name="page 9", tags=["not-paging"]))
        cls.ids = [j.id for j in jobs]
        for job in jobs:
            cls.client.wait(job, poll=0.05)

    def test_pages_are_followed_by_their_next_links(self) -> None:
        client = new_client()
        with mock.patch.object(client._http, "get_json", wraps=client._http.get_json) as get_json:
            self.assertEqual([j.id for j in client.jobs(tag="paging", page_size=2)], self.ids)
        targets = [c.args[0] for c in get_json.call_args_list]
        self.assertEqual(len(targets), 3)
        self.assertEqual(targets[0], "/api/v1/jobs?limit=2&tag=paging")
        self.assertIn(f"after={self.ids[1]}", targets[1])

    def test_filters(self) -> None:
        def ids(**filters: Any) -> list[int]:
            return [j.id for j in self.client.jobs(page_size=3, **filters)]

        self.assertEqual(ids(tag=["paging", "k:3"]), [self.ids[3]])
        self.assertEqual(ids(name="page 2"), [self.ids[2]])  # a space in the query: %20, not +
        self.assertEqual(ids(state="succeeded", tag="paging"), self.ids)
        self.assertEqual(ids(state=["queued", "running"], tag="paging"), [])
        everything = ids()
        self.assertTrue(set(self.ids) < set(everything))
        self.assertEqual(everything, sorted(everything))

    def test_a_page_size_out_of_range_is_refused_at_once(self) -> None:
        with self.assertRaises(ValueError):
            self.client.jobs(page_size=0)  # before any iteration: nothing is fetched yet

    def test_a_bad_filter_is_an_api_error(self) -> None:
        with self.assertRaises(ApiError) as caught:
            list(self.client.jobs(state="sleeping"))
        self.assertEqual(caught.exception.status, 400)
        self.assertIn("sleeping", caught.exception.detail)

    def test_an_idempotency_key_gives_the_same_job_again(self) -> None:
        key = f"paging-{uuid.uuid4()}"
        spec = pouring_spec(20, 10, name="idempotent")
        first = self.client.submit(spec, idempotency_key=key)
        again = self.client.submit(spec, idempotency_key=key)
        self.assertEqual((again.id, first.replayed, again.replayed), (first.id, False, True))
        self.assertEqual(again.idempotency_key, key)
        with self.assertRaises(ApiError) as caught:
            self.client.submit(pouring_spec(21, 10, name="idempotent"), idempotency_key=key)
        self.assertEqual(caught.exception.status, 422)
        self.client.wait(first, poll=0.05)


class FramesTest(unittest.TestCase):
    def check_frames(self, frames: list[Frame], job: Job) -> None:
        self.assertTrue(frames)
        for f in frames:
            self.assertEqual((f.job, f.particle_count, f.total_steps), (job.id, job.particles, job.total_steps))
            self.assertEqual(len(f.positions), job.particles)
            self.assertEqual(len(f.velocities), job.particles)
            self.assertEqual(len(f.radii), job.particles)
        self.assertTrue(frames[0].radii_sent)  # a viewer's first frame brings the radii
        self.assertTrue(all(0.011 < r < 0.013 for r in frames[0].radii))  # the lattice's 0.012 m, in float32
        steps = [f.step for f in frames]
        self.assertEqual(steps, sorted(set(steps)))

    def test_frames_of_a_running_job_and_of_one_that_was_queued(self) -> None:
        client = new_client()
        blocker = client.submit(pouring_spec(10**6, 10**5, name="blocker"))
        blocker = wait_for_state(client, blocker, "running")
        # the watched job waits behind the blocker: its stream is open before it starts
        watched = client.submit(pouring_spec(600, 200, name="watched", touching=True))
        self.assertEqual(watched.state, "queued")
        with client.frames(watched, force_chains=True) as queued_stream:
            with self.assertRaises(ApiError) as caught:
                client.results(watched)
            self.assertEqual(caught.exception.status, 404)
            with client.frames(blocker) as running_stream:
                first = [next(running_stream) for _ in range(3)]
                self.check_frames(first, blocker)
                self.assertEqual(client.cancel(blocker).state, "cancelled")
                rest = list(running_stream)
            self.assertEqual((running_stream.close_code, running_stream.close_reason), (1000, "job cancelled"))
            self.assertTrue(all(f.step > first[-1].step for f in rest))
            frames = list(queued_stream)
        self.assertEqual((queued_stream.close_code, queued_stream.close_reason), (1000, "job succeeded"))
        watched = client.job(watched)
        self.check_frames(frames, watched)
        last = frames[-1]
        self.assertEqual(last.step, watched.total_steps)  # the last step is always sent
        # force chains come with the files' frames (every 200 steps), and the last step is one
        self.assertTrue(last.force_chains)
        for chain in last.force_chains:
            self.assertTrue(0 <= chain.i < watched.particles and 0 <= chain.j < watched.particles)
        self.assertEqual(len(last.walls), 1)  # the floor plate, two triangles
        self.assertEqual(len(last.walls[0].triangles), 2)
        self.assertGreater(last.kinetic_energy, 0)

    def test_an_unknown_jobs_frames_are_a_404(self) -> None:
        with self.assertRaises(ApiError) as caught:
            new_client().frames(987654)
        self.assertEqual(caught.exception.status, 404)


class ErrorsTest(unittest.TestCase):
    def test_an_invalid_spec_names_each_field(self) -> None:
        spec = pouring_spec(20, 10, tags=["no spaces"])
        spec["materials"][0]["density"] = -1
        with self.assertRaises(ApiError) as caught:
            new_client().submit(spec)
        e = caught.exception
        self.assertEqual((e.status, e.detail, e.title), (400, "invalid spec", "Bad Request"))
        self.assertEqual(e.instance, "/api/v1/jobs")
        self.assertTrue(any(p.startswith("materials[0].density: ") for p in e.problems), e.problems)
        self.assertTrue(any(p.startswith("tags[0]: ") for p in e.problems), e.problems)
        self.assertIn("materials[0].density", str(e))

    def test_an_unknown_job_is_a_404(self) -> None:
        with self.assertRaises(ApiError) as caught:
            new_client().job(987654)
        self.assertEqual(caught.exception.status, 404)
        self.assertIn("987654", caught.exception.detail)
        self.assertEqual(caught.exception.problems, [])

    def test_a_file_that_cannot_be_read_is_named_before_anything_is_sent(self) -> None:
        spec = pouring_spec(20, 10)
        spec["walls"][0] = {"name": "floor", "material": "steel", "mesh": {"file": "no-such-mesh.dat"}}
        with self.assertRaises(SpecFileError) as caught:
            new_client().submit(spec, base_dir=str(work))
        self.assertEqual(len(caught.exception.problems), 1)
        self.assertTrue(caught.exception.problems[0].startswith("walls[0].mesh.file: "))

    def test_a_mesh_with_a_file_and_inline_vertices_is_refused_by_the_server(self) -> None:
        folder = work / "both"
        mesh_folder(folder)
        spec = pouring_spec(20, 10)
        spec["walls"][0] = {"name": "floor", "material": "steel",
                            "mesh": {"file": "floor.dat", "vertices": [{"x": 1}, {"y": 1}, {"z": 1}],
                                     "triangles": [{"i": 1, "j": 2, "k": 3}]}}  # fmt: skip
        with self.assertRaises(ApiError) as caught:
            new_client().submit(spec, base_dir=str(folder))
        self.assertTrue(any(p.startswith("walls[0].mesh") for p in caught.exception.problems), caught.exception.problems)


class InlineTest(unittest.TestCase):
    def test_the_inlined_spec_is_the_one_dem_submit_sends(self) -> None:
        folder = work / "inline"
        mesh_folder(folder)
        spec_file = write_json(folder / "spec.json", spec_with_files())
        client = new_client()
        key = f"inline-{uuid.uuid4()}"
        job = client.submit(spec_file, idempotency_key=key)
        # The server compares an idempotent retry's spec with the first as protobuf bytes: `dem
        # submit` of the same file with the same key gets this job only if its inlining (the C++
        # one) made exactly the same spec.
        env = {k: v for k, v in os.environ.items() if k not in ("DEM_SERVER", "DEM_SERVER_TOKEN")}
        dem = subprocess.run(
            [str(BINARY_DIR / "dem"), "submit", str(spec_file), "--idempotency-key", key, "--quiet", "--server", client.server],
            capture_output=True, text=True, env=env, timeout=60,
        )  # fmt: skip
        self.assertEqual((dem.returncode, dem.stdout.strip()), (0, str(job.id)), dem.stderr)
        changed = spec_with_files()
        changed["walls"][0]["mesh"]["scale"] = 1.5
        with self.assertRaises(ApiError) as caught:  # so a different spec does not pass for the same
            client.submit(changed, idempotency_key=key, base_dir=str(folder))
        self.assertEqual(caught.exception.status, 422)
        job = client.wait(job, poll=0.05)
        self.assertEqual((job.state, job.particles), ("succeeded", 34))  # 30 packed spheres, 2 clumps of 2


class StudyTest(unittest.TestCase):
    def test_a_study_whose_base_is_a_file_naming_a_mesh(self) -> None:
        folder = work / "study"
        mesh_folder(folder)
        base = pouring_spec(200, 100)
        base["walls"][0] = {"name": "floor", "material": "steel", "mesh": {"file": "floor.dat"}}
        write_json(folder / "base.json", base)
        study_file = write_json(
            folder / "study.json",
            {"name": "friction", "base": "base.json", "parameters": [{"path": "interactions[0].friction", "values": [0.3, 0.6]}]},
        )
        client = new_client()
        study = client.submit_study(study_file)
        self.assertEqual([run.parameters for run in study.jobs],
                         [{"interactions[0].friction": 0.3}, {"interactions[0].friction": 0.6}])  # fmt: skip
        seen: list[Study] = []
        study = client.wait_study(study, progress=seen.append, poll=0.05)
        self.assertTrue(study.finished)
        self.assertEqual(study.counts, {"succeeded": 2})
        self.assertIs(seen[-1].finished, True)
        table = client.study_results(study)
        self.assertEqual([row["run"] for row in table["rows"]], [1, 2])
        for row, run in zip(table["rows"], study.jobs):
            self.assertEqual((row["job"], row["state"]), (run.job, "succeeded"))
            assert run.job is not None
            self.assertEqual(row["results"], client.results(run.job))
            self.assertEqual(client.job(run.job).name, f"friction #{row['run']} (interactions[0].friction={row['parameters']['interactions[0].friction']})")
        self.assertEqual(client.study(study.id).id, study.id)
        self.assertIn(study.id, [s.id for s in client.studies()])

    def test_an_invalid_study_names_the_parameter(self) -> None:
        study = {"name": "bad", "base": pouring_spec(20, 10), "parameters": [{"path": "bonds.x", "values": [1]}]}
        with self.assertRaises(ApiError) as caught:
            new_client().submit_study(study)
        self.assertEqual(caught.exception.status, 400)
        self.assertTrue(any(p.startswith("parameters[0].path: ") for p in caught.exception.problems), caught.exception.problems)


if __name__ == "__main__":
    unittest.main()
