"""Processes as Linux's /proc lists them, for the tests that prove no run outlives its command."""

from __future__ import annotations

import os
from typing import NamedTuple


class Proc(NamedTuple):
    state: str  # Z: a zombie, ended and not yet reaped
    ppid: int
    pgrp: int
    session: int


def table() -> dict[int, Proc]:
    """Every process: pid -> its state, parent, process group and session."""
    out = {}
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                with open(f"/proc/{name}/stat", encoding="utf-8", errors="replace") as f:
                    stat = f.read()
            except OSError:
                continue
            state, ppid, pgrp, session = stat[stat.rindex(")") + 2:].split()[:4]
            out[int(name)] = Proc(state, int(ppid), int(pgrp), int(session))
    return out
