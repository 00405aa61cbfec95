"""Rotations as unit quaternions (w, x, y, z), in bulk: arrays of shape (..., 4)."""

from __future__ import annotations

import numpy as np

IDENTITY = np.array([1.0, 0.0, 0.0, 0.0])


def unit(v: np.ndarray) -> np.ndarray:
    """Vectors (..., 3) scaled to length 1, each by its largest component first: the norm of
    1e200 0 0 overflows to inf and that of 1e-170 0 0 underflows to 0, where either is +x. Only
    a zero vector (each component 0 or -0) has no direction: it stays zero."""
    v = np.asarray(v, dtype=np.float64)
    big = np.abs(v).max(axis=-1, keepdims=True)
    v = np.divide(v, big, out=np.zeros_like(v), where=big > 0)
    norm = np.linalg.norm(v, axis=-1, keepdims=True)  # in [1, sqrt 3]
    return np.divide(v, norm, out=np.zeros_like(v), where=norm > 0)


def from_axis_angle(rot: np.ndarray) -> np.ndarray:
    """X3D SFRotation(s) (x, y, z, angle) to quaternions; a zero axis means no rotation."""
    rot = np.asarray(rot, dtype=np.float64)
    axis = unit(rot[..., :3])
    half = 0.5 * rot[..., 3:4] * np.any(axis != 0, axis=-1, keepdims=True)
    return np.concatenate([np.cos(half), axis * np.sin(half)], axis=-1)


def to_axis_angle(q: np.ndarray) -> np.ndarray:
    """Quaternions to X3D rotations, angle in [0, pi], axis (0 0 1) for no rotation."""
    q = np.asarray(q, dtype=np.float64)
    q = np.where(q[..., :1] < 0, -q, q)  # the short way round
    v = q[..., 1:]
    s = np.linalg.norm(v, axis=-1, keepdims=True)
    angle = 2.0 * np.arctan2(s[..., 0], q[..., 0])
    axis = np.divide(v, s, out=np.broadcast_to([0.0, 0.0, 1.0], v.shape).copy(), where=s > 1e-300)
    return np.concatenate([axis, angle[..., None]], axis=-1)


def multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product a * b (apply b, then a)."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    if a.ndim == 1 and b.ndim == 1:  # one product (a joint's output, each frame): Python floats, the same sums
        aw, ax, ay, az = a.tolist()
        bw, bx, by, bz = b.tolist()
        return np.array([aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                         aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw])
    aw, ax, ay, az = a[..., 0], a[..., 1], a[..., 2], a[..., 3]
    bw, bx, by, bz = b[..., 0], b[..., 1], b[..., 2], b[..., 3]
    out = np.empty(a.shape if a.shape == b.shape else np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = aw * bw - ax * bx - ay * by - az * bz
    out[..., 1] = aw * bx + ax * bw + ay * bz - az * by
    out[..., 2] = aw * by - ax * bz + ay * bw + az * bx
    out[..., 3] = aw * bz + ax * by - ay * bx + az * bw
    return out


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross products of (n, 3) arrays: np.cross's axis handling costs more than
    the arithmetic for the few dozen rows a frame reads (and so does np.broadcast_shapes for
    the common case, two arrays of one shape)."""
    out = np.empty(a.shape if a.shape == b.shape else np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def conjugate(q: np.ndarray) -> np.ndarray:
    return np.asarray(q, dtype=np.float64) * np.array([1.0, -1.0, -1.0, -1.0])


def rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Vectors v turned by quaternions q (broadcasting over leading axes)."""
    q = np.asarray(q, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64)
    if q.ndim == 1 and v.ndim == 1:  # one vector (a backend's joint frames at build): Python floats, the same sums
        w, x, y, z = q.tolist()
        a, b, c = v.tolist()
        t0, t1, t2 = 2.0 * (y * c - z * b), 2.0 * (z * a - x * c), 2.0 * (x * b - y * a)
        return np.array([a + w * t0 + (y * t2 - z * t1), b + w * t1 + (z * t0 - x * t2),
                         c + w * t2 + (x * t1 - y * t0)])
    w, u = q[..., :1], q[..., 1:]
    t = 2.0 * cross(u, v)
    return v + w * t + cross(u, t)


def matrix(q: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of quaternions."""
    w, x, y, z = np.moveaxis(np.asarray(q, dtype=np.float64), -1, 0)
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1)], axis=-2)


def from_matrix(m: np.ndarray) -> np.ndarray:
    """Rotation matrices (n, 3, 3) to unit quaternions w x y z. Row k of `rows` is 4 q_k q;
    the row with the largest q_k is the best conditioned. (`rows` in one stack, not five: a
    backend calls this every frame, DART's state(), and the stacks were a third of its time.)"""
    m00, m11, m22 = m[:, 0, 0], m[:, 1, 1], m[:, 2, 2]
    a, b, c = m[:, 2, 1] - m[:, 1, 2], m[:, 0, 2] - m[:, 2, 0], m[:, 1, 0] - m[:, 0, 1]
    d, e, f = m[:, 0, 1] + m[:, 1, 0], m[:, 0, 2] + m[:, 2, 0], m[:, 1, 2] + m[:, 2, 1]
    rows = np.stack([1 + m00 + m11 + m22, a, b, c,
                     a, 1 + m00 - m11 - m22, d, e,
                     b, d, 1 - m00 + m11 - m22, f,
                     c, e, f, 1 - m00 - m11 + m22], -1).reshape(len(m), 4, 4)
    k = np.argmax(np.diagonal(rows, axis1=1, axis2=2), axis=1)
    q = rows[np.arange(len(m)), k]
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def twist_angle(q: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """The angle of the rotation q about a unit axis (swing-twist decomposition), in (-pi, pi]."""
    q = np.asarray(q, dtype=np.float64)
    proj = np.sum(q[..., 1:] * axis, axis=-1)
    angle = 2.0 * np.arctan2(proj, q[..., 0])
    return (angle + np.pi) % (2 * np.pi) - np.pi


def angle_between(q1: np.ndarray, q2: np.ndarray) -> np.ndarray:
    """The angle of q1 * conj(q2), accurate for small angles (no acos)."""
    d = multiply(q1, conjugate(q2))
    return 2.0 * np.arctan2(np.linalg.norm(d[..., 1:], axis=-1), np.abs(d[..., 0]))
