"""Rerun recordings of runs: each backend's bodies moving side by side, and where they part.

One .rrd from the parsed traces (the same arrays conformance/analyses/compare.py
measures) and the scene's collision plan; it runs no engine. Everything is sent in columns
(rr.send_columns: a whole time column and one array per entity), so recording costs little
next to the simulation it shows. Entities, on one timeline `time` (simulation seconds):

    /BACKEND/bodies/BODY                 Transform3D per frame (trace position, orientation)
    /BACKEND/bodies/BODY/GEOMETRY        the collidable's shape, static, in the body's frame
    /BACKEND/bodies/BODY/marker          a point, for a body without a collidable
    /BACKEND/static/GEOMETRY             collidables on no body, in the world
    /BACKEND/contacts/SENSOR             CollisionSensor contacts: Points3D and normals (Arrows3D)
    /joints/JOINT/FIELD/BACKEND          joint outputs (one series per component)
    /divergence/A_vs_B/QUANTITY_STAT     compare's per-frame max and rms over bodies, and threshold
    /divergence/A_vs_B/QUANTITY_first_over  a point on the plot where the threshold is first passed
    /divergence/A_vs_B/events            a WARN TextLog at that time: the bodies over it
"""

from __future__ import annotations

import re
import time
from collections.abc import Sequence

import numpy as np
import rerun as rr
import rerun.blueprint as rrb

from conformance.results import JOINT_OUTPUTS, ORIENTATION, POSITION, Divergence, PairComparison
from x3d_core.files import atomic
from x3d_core.model.scene import Scene
from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import Geometry
from x3d_core.semantics.world import STATIC, worlds
from x3d_core.traces.trace import TraceView

from .rerun_shapes import marker, shape, xyzw

TIMELINE = "time"
NORMAL_LENGTH = 0.1  # m: how long a contact normal is drawn
# a backend's colour in every view (tab10), by its place in the run
PALETTE = [(31, 119, 180), (255, 127, 14), (44, 160, 44), (214, 39, 40), (148, 103, 189),
           (140, 86, 75), (227, 119, 194), (127, 127, 127), (188, 189, 34), (23, 190, 207)]
_CONTACT = re.compile(r"contacts\[(\d+)\]\.position$")


def path(*parts: str) -> str:
    """An entity path from names as they are (a DEF may hold characters rerun escapes)."""
    return rr.new_entity_path(list(parts))


def pair_name(p: PairComparison) -> str:
    return f"{p.a}_vs_{p.b}"


def _times(t: np.ndarray) -> list[rr.TimeColumn]:
    return [rr.TimeColumn(TIMELINE, duration=t)]


def placed_shapes(scene: Scene) -> list[tuple[tuple[str, ...], Geometry]]:
    """Each collidable and where it hangs below a backend's root: its body, or static."""
    return [(("static", g.name) if g.body == STATIC else ("bodies", w.bodies.names[g.body], g.name), g)
            for w in worlds(scene) for g in (w.collisions.geometries if w.collisions is not None else [])]


def _geometry(rec: rr.RecordingStream, backend: str, shapes: Sequence[tuple[tuple[str, ...], Geometry]],
              names: Sequence[str], color: tuple[int, int, int]) -> None:
    """Static shapes: each body's collidables in its frame, the static environment in the
    world, a marker for a body with none."""
    for where, g in shapes:
        rec.log(path(backend, *where), rr.Transform3D(translation=g.position, quaternion=xyzw(g.orientation)),
                shape(g, color), static=True)
    drawn = {where[1] for where, _ in shapes if where[0] == "bodies"}
    for n in names:
        if n not in drawn:
            rec.log(path(backend, "bodies", n, "marker"), marker(color), static=True)


def _poses(rec: rr.RecordingStream, backend: str, trace: TraceView, names: Sequence[str]) -> None:
    for n in names:
        t, p = trace.series(n, POSITION)
        q = xyzw(R.from_axis_angle(trace.series(n, ORIENTATION)[1]))
        rec.send_columns(path(backend, "bodies", n), _times(t), rr.Transform3D.columns(translation=p, quaternion=q))


def _contacts(rec: rr.RecordingStream, backend: str, trace: TraceView, frames: np.ndarray,
              color: tuple[int, int, int]) -> None:
    """Every sensor's contacts per frame; a frame without any gets an empty row, so that
    the last contacts do not linger."""
    if not len(frames):
        return
    sensors: dict[str, list[str]] = {}
    for node, fld in trace.keys():
        if _CONTACT.match(fld):
            sensors.setdefault(node, []).append(fld)
    for node, flds in sensors.items():
        parts = [(trace.series(node, f), trace.series(node, f.replace(".position", ".contactNormal"))[1])
                 for f in flds]
        t = np.concatenate([tp[0] for tp, _ in parts])
        order = np.argsort(t, kind="stable")
        at = np.searchsorted(frames, t[order])
        counts = np.bincount(at, minlength=len(frames))
        p = np.concatenate([tp[1] for tp, _ in parts])[order]
        n = np.concatenate([nv for _, nv in parts])[order]
        columns = [*rr.Points3D.columns(positions=p, colors=np.tile(color, (len(p), 1))).partition(counts),
                   *rr.Arrows3D.columns(origins=p, vectors=n * NORMAL_LENGTH).partition(counts)]
        rec.send_columns(path(backend, "contacts", node), _times(frames), columns)


def _joints(rec: rr.RecordingStream, backend: str, trace: TraceView) -> bool:
    """Each joint output as a series (one line per component); whether there was any."""
    keys = [(n, f) for n, f in trace.keys() if f in JOINT_OUTPUTS]
    for node, fld in keys:
        t, v = trace.series(node, fld)
        rec.send_columns(path("joints", node, fld, backend), _times(t),
                         rr.Scalars.columns(scalars=v.ravel()).partition(np.full(len(t), v.shape[1])))
    return bool(keys)


def _divergence(rec: rr.RecordingStream, p: PairComparison, d: Divergence) -> None:
    """compare's per-frame series as they are, the threshold, and the first crossing marked."""
    if not len(d.frame_max):  # the runs share no body
        return
    where = ("divergence", pair_name(p))
    for stat, values in (("max", d.frame_max), ("rms", d.frame_rms)):
        rec.send_columns(path(*where, f"{d.quantity}_{stat}"), _times(p.times), rr.Scalars.columns(scalars=values))
    rec.send_columns(path(*where, f"{d.quantity}_threshold"), _times(p.times),
                     rr.Scalars.columns(scalars=np.full(len(p.times), d.threshold)))
    first = d.first_over
    if first is None:
        return
    rec.set_time(TIMELINE, duration=first.time)
    rec.log(path(*where, f"{d.quantity}_first_over"), rr.Scalars(first.values[0]),
            rr.SeriesPoints(markers="cross", marker_sizes=8.0))
    over = ", ".join(f"{b} {v:.3g} {d.unit}" for b, v in zip(first.bodies, first.values))
    rec.log(path(*where, "events"), rr.TextLog(f"{p.a} and {p.b}: {d.quantity} passes {d.threshold:g} {d.unit} "
                                               f"at t = {first.time:g} s: {over}", level=rr.TextLogLevel.WARN))
    rec.reset_time()


def blueprint(backends: Sequence[str], pairs: bool, joints: bool) -> rrb.Blueprint:
    """A 3D view per backend side by side and one of them all overlaid; below, the plots."""
    views = [rrb.Spatial3DView(name=b, origin=path(b)) for b in backends]
    if len(backends) > 1:
        views.append(rrb.Spatial3DView(name="all backends", origin="/", contents=[f"{path(b)}/**" for b in backends]))
    plots = []
    if pairs:
        plots += [rrb.TimeSeriesView(name="divergence", origin="/divergence"),
                  rrb.TextLogView(name="first divergence", origin="/divergence")]
    if joints:
        plots.append(rrb.TimeSeriesView(name="joint outputs", origin="/joints"))
    return rrb.Blueprint(rrb.Vertical(rrb.Horizontal(*views), *([rrb.Horizontal(*plots)] if plots else []),
                                      row_shares=[2, 1] if plots else None), collapse_panels=True)


def write_recording(out: str, scene: Scene, runs: Sequence[tuple[str, TraceView]],
                    pairs: Sequence[PairComparison] = ()) -> float:
    """Writes the recording of these runs (backend, parsed trace) and their comparisons to
    `out`, whole or not at all: rerun encodes it in memory (its memory sink: no file, no
    writer thread), and the bytes go through x3d_core.files.atomic as every other output does. Not
    rr.save: its file sink writes in a thread of its own, and on a full disk it either kept
    the command waiting on a flush that never ended (deaf to SIGTERM, native code) or logged
    the error and returned, leaving a truncated .rrd under its final name. `out` a symbolic
    link: its target is replaced; /dev/null: the recording is discarded. The file gets the
    usual 0666 less the umask (an existing one keeps its mode). Returns the seconds it took;
    atomic.CannotWrite (one line, the path and why) where it cannot be written."""
    started = time.perf_counter()
    rec = rr.RecordingStream("x3drbp", make_default=False)
    rec.set_log_time_enabled(False)  # simulation time is the one timeline
    memory = rec.memory_recording()  # before anything is logged: it holds the whole stream
    shapes = placed_shapes(scene)
    any_joints = False
    for k, (backend, trace) in enumerate(runs):
        color = PALETTE[k % len(PALETTE)]
        names = trace.bodies()
        _geometry(rec, backend, shapes, names, color)
        _poses(rec, backend, trace, names)
        frames = np.unique(np.concatenate([trace.series(n, POSITION)[0] for n in names])) if names else np.empty(0)
        _contacts(rec, backend, trace, frames, color)
        any_joints |= _joints(rec, backend, trace)
    for p in pairs:
        for d in (p.position, p.orientation):
            _divergence(rec, p, d)
    rec.send_blueprint(blueprint([b for b, _ in runs], bool(pairs), any_joints), make_active=False, make_default=True)
    atomic.write_bytes(out, memory.drain_as_bytes())
    return time.perf_counter() - started
