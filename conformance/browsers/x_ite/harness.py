"""The X_ITE browser (npm `x_ite`: the component on Bullet through ammo.js), run headless in
Chromium, as an implementation under test: it writes a trace of a scene the way any browser
author would (docs/implementers.md), and the suite judges that trace as it judges any.

record.mjs (beside this module) drives it through playwright-core with Debian's chromium
(no browser download) under a virtual clock (page.html, also beside it): frame k is at
k / frame_rate exactly, the state read at time 0 is the scene as loaded, before any step,
and two runs are bit-identical. X_ITE reads its fields through its own scripting API.

The step X_ITE takes is its own: each frame it advances the frame's duration (a moving
average of the frame period) in `iterations` substeps, so the closed forms are judged at
dt = 1 / (frame_rate * iterations) (`step`).
"""

from __future__ import annotations

import json
import math
import os
import shutil
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass, field

from x3d_core.files import atomic
from x3d_core.model.scene import Scene
from x3d_core.semantics.world import node_names, worlds

from conformance.runner import children

HERE = os.path.dirname(os.path.abspath(__file__))
CHROMIUM = os.environ.get("X3DRBP_CHROMIUM", "/usr/bin/chromium")
INSTALL = "make x-ite-install"
# GL performance notes SwiftShader prints on every page: noise, not the scene's messages
NOISE = "GL Driver Message"


def unavailable() -> str | None:
    """Why X_ITE cannot run here, or None."""
    if shutil.which("node") is None:
        return f"node is not installed (Debian: apt-get install nodejs npm; then {INSTALL})"
    if not os.access(CHROMIUM, os.X_OK):
        return f"no chromium at {CHROMIUM} (set X3DRBP_CHROMIUM, or run {INSTALL})"
    for package in ("x_ite", "playwright-core"):
        if not os.path.isdir(os.path.join(HERE, "node_modules", package)):
            return f"{package} is not installed in {HERE} (run {INSTALL})"
    return None


class NotRecordable(ValueError):
    """The scene has an output X_ITE's page cannot name."""


def outputs(scene: Scene) -> dict:
    """What the page reads each frame: every RigidBody of every collection, disabled ones and
    those of a disabled collection included (that they do not move is what their fields say),
    the joint outputs forceOutput selects, every CollisionSensor; and the enabled collections,
    which it holds for one frame before the run (record.mjs says why). All by DEF name, which
    is how a page finds a node (Scene.getNamedNode), so a node without one is refused by name."""
    found: dict = {"collections": [], "bodies": [], "joints": {}, "sensors": []}
    names = node_names(scene)
    for w in worlds(scene):
        found["collections"].append(w.name)
        found["joints"].update({j.name: list(j.outputs) for j in w.joints if j.outputs})
    for c in scene.of_type("RigidBodyCollection"):
        found["bodies"] += [names[id(b)] for b in c.get("bodies") or () if b is not None
                            and b.type_name == "RigidBody" and names[id(b)] not in found["bodies"]]
    found["sensors"] = [names[id(s)] for s in scene.of_type("CollisionSensor")]
    defined = {n.def_name for n in scene.nodes() if n.def_name}
    unnamed = [n for n in (*found["collections"], *found["bodies"], *found["joints"], *found["sensors"])
               if n not in defined]
    if unnamed:
        raise NotRecordable(f"{', '.join(unnamed)}: a page reads nodes by DEF name, and these have none")
    return found


# X_ITE draws a frame only when more than 1 / MaximumFrameRate seconds have passed since
# the last (X3DBrowser.advanceTime), and its browser option MaximumFrameRate is 80 unless a
# page changes it: no X_ITE of default options runs faster
MAXIMUM_FRAME_RATE = 80.0


def reachable_rate(rate: float) -> float:
    """The case's frame rate where X_ITE reaches it; else rate / k for the least k that
    brings it under X_ITE's maximum, so every frame still falls on one of the case's."""
    return rate if rate < MAXIMUM_FRAME_RATE else rate / (math.floor(rate / MAXIMUM_FRAME_RATE) + 1)


def step(scene: Scene, frame_rate: float) -> float:
    """The physics step X_ITE takes at this frame rate: the frame in `iterations` substeps
    (of the first enabled collection; one step for a scene with none)."""
    found = worlds(scene)
    return 1.0 / (frame_rate * (found[0].iterations if found else 1))


@dataclass
class Recording:
    """One run of a scene in X_ITE: what to run, then what came of it."""
    scene: str
    out: str  # the trace's path
    frame_rate: float
    duration: float
    what: dict  # outputs(scene)
    ok: bool = False
    error: str | None = None
    blew_up: str | None = None  # the first output that was not finite: the trace stops before it
    frames: int = 0
    wall_s: float | None = None
    messages: list[str] = field(default_factory=list)


def _job(runs: Sequence[Recording]) -> dict:
    return {"chromium": CHROMIUM,
            "runs": [{"scene": os.path.abspath(r.scene), "out": os.path.abspath(r.out), "frameRate": r.frame_rate,
                      "duration": r.duration, "loadFrames": 100000, **r.what} for r in runs]}


def record(runs: Sequence[Recording], timeout: float) -> None:
    """Runs them in one browser, in order, filling in each result. A browser that crashes or
    passes `timeout` seconds in all leaves the runs it did not finish with that as their error."""
    if not runs:
        return
    with tempfile.TemporaryDirectory(prefix="x3drbp-x_ite-") as folder:
        job = os.path.join(folder, "job.json")
        atomic.write_json(job, _job(runs))
        done = children.call(["node", os.path.join(HERE, "record.mjs"), job], timeout)
    if done.returncode is None:
        ended = f"timeout: the browser passed {timeout:g} s"
    else:
        ended = f"the browser exited with status {done.returncode}: {_last_line(done.stderr)}"
    for line in done.stdout.splitlines():
        try:
            d = json.loads(line)
            r = runs[int(d["run"])]
        except (ValueError, KeyError, IndexError, TypeError):
            continue
        r.ok, r.error, r.frames, r.wall_s = bool(d["ok"]), d.get("error"), int(d.get("frames", 0)), d.get("wallSeconds")
        r.blew_up = d.get("blewUp")
        r.messages = [m for m in d.get("messages", []) if NOISE not in m]
    for r in runs:
        if not r.ok and r.error is None:
            r.error = ended


def _last_line(text: str) -> str:
    lines = [s for s in text.strip().splitlines() if s.strip()]
    return lines[-1].strip() if lines else "no message"
