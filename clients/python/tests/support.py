"""What the server tests share: the real dem-server on a free loopback port in a temporary data
folder, `dem run` of a spec, and small job specs."""

from __future__ import annotations

import copy
import os
import re
import signal
import subprocess
import tempfile
import time
import unittest
from pathlib import Path
from typing import Any

# Where dem and dem-server are: CTest passes the build folder; by hand, the usual one.
BINARY_DIR = Path(os.environ.get("DEM_BINARY_DIR", "/work/main/build"))
SOURCE_DIR = Path(__file__).resolve().parents[3]  # clients/python/tests -> the project


def require_binaries() -> None:
    """Skips the server tests when the binaries are not built, unless DEM_BINARY_DIR names the
    folder they must be in (as CTest does): then their absence is a failure, not a skip."""
    missing = [name for name in ("dem", "dem-server") if not (BINARY_DIR / name).is_file()]
    if not missing:
        return
    message = f"{', '.join(missing)} not in {BINARY_DIR} (set DEM_BINARY_DIR to the build folder)"
    if "DEM_BINARY_DIR" in os.environ:
        raise RuntimeError(message)
    raise unittest.SkipTest(message)


class ServerProcess:
    """dem-server on a port it picks (--port 0), its data in `data`; output to a log file, not a
    pipe, so a server that prints a lot can never block on a pipe no one reads."""

    def __init__(self, data: Path, *extra: str) -> None:
        self.log = data.parent / "server.log"
        self._log_file = open(self.log, "wb")
        # OMP_WAIT_POLICY=PASSIVE: idle OpenMP threads sleep instead of spinning on the 2 cores
        env = {**os.environ, "OMP_WAIT_POLICY": "PASSIVE"}
        env.pop("DEM_SERVER_TOKEN", None)  # a token from the caller's shell would lock the tests out
        self.process = subprocess.Popen(
            [str(BINARY_DIR / "dem-server"), "--data", str(data), "--port", "0", *extra],
            stdout=self._log_file,
            stderr=subprocess.STDOUT,
            env=env,
        )
        self.url = self._wait_for_address()

    def _wait_for_address(self, seconds: float = 20.0) -> str:
        # its first line: "dem-server listening on http://127.0.0.1:PORT/ (data: DIR)"
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            m = re.search(rb"listening on (http://[0-9.]+:\d+)", self.log.read_bytes())
            if m:
                return m.group(1).decode("ascii")
            if self.process.poll() is not None:
                break
            time.sleep(0.02)
        self.stop()
        raise RuntimeError(f"dem-server did not start: {self.log.read_text(errors='replace')}")

    def stop(self) -> None:
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(15)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self._log_file.close()


def dem_run(spec_file: Path, out: Path) -> None:
    """`dem run SPEC --out OUT`: the files the same spec gives without a server."""
    subprocess.run(
        [str(BINARY_DIR / "dem"), "run", str(spec_file), "--out", str(out), "--quiet"],
        check=True,
        stdout=subprocess.DEVNULL,
        env={**os.environ, "OMP_WAIT_POLICY": "PASSIVE"},
    )


# The demo case (cases/demo/spec.json) made small: spheres on a hexagonal lattice poured into a
# steel box, one thread (byte-identical to any other count, and kind to a 2-core machine).
_POURING: dict[str, Any] = {
    "name": "pouring",
    "materials": [
        {"name": "granite", "density": 2650, "youngsModulus": 5e7, "poissonRatio": 0.25},
        {"name": "steel", "rigid": True},
    ],
    "interactions": [
        {"a": "granite", "b": "granite", "restitution": 0.5, "friction": 0.5, "rollingFriction": 0.05},
        {"a": "granite", "b": "steel", "restitution": 0.5, "friction": 0.4, "rollingFriction": 0.05},
    ],
    "contact": {"normal": "HERTZ", "rolling": "EPSD"},
    "lattices": [
        {
            "kind": "HEX",
            "min": {"x": -0.1, "y": -0.1, "z": 0.05},
            "max": {"x": 0.1, "y": 0.1, "z": 0.35},
            "radius": 0.012,
            "spacing": 1.3,
            "material": "granite",
            "velocity": {"x": 0.3},
        }
    ],
    "walls": [
        {
            "name": "floor",
            "material": "steel",
            "plate": {
                "c1": {"x": -0.15, "y": -0.15},
                "c2": {"x": 0.15, "y": -0.15},
                "c3": {"x": 0.15, "y": 0.15},
                "c4": {"x": -0.15, "y": 0.15},
            },
        },
        {"name": "left", "material": "steel", "plane": {"point": {"x": -0.15}, "normal": {"x": 1}}},
        {"name": "right", "material": "steel", "plane": {"point": {"x": 0.15}, "normal": {"x": -1}}},
        {"name": "front", "material": "steel", "plane": {"point": {"y": -0.15}, "normal": {"y": 1}}},
        {"name": "back", "material": "steel", "plane": {"point": {"y": 0.15}, "normal": {"y": -1}}},
    ],
    "gravity": {"z": -9.81},
    "numerics": {"threads": 1},
    "time": {"steps": 400},
    "outputs": {"everySteps": 100, "forceChains": True},
}


def pouring_spec(steps: int, every: int, name: str = "pouring", tags: list[str] | None = None, touching: bool = False) -> dict[str, Any]:
    """`steps` steps, a file frame every `every`. `touching`: the lattice's spheres overlap and
    rest on the floor from the start, so every file frame has force chains."""
    spec = copy.deepcopy(_POURING)
    spec["name"] = name
    spec["time"] = {"steps": steps}
    spec["outputs"]["everySteps"] = every
    if tags:
        spec["tags"] = tags
    if touching:
        spec["lattices"][0]["spacing"] = 0.98
        spec["lattices"][0]["min"]["z"] = 0.0
    return spec


def temporary_folder(prefix: str) -> Path:
    return Path(tempfile.mkdtemp(prefix=prefix))
