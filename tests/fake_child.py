"""A stand-in for the interpreter conformance.runner starts its children with: a shell script,
so that a test can make a child crash, hang or fail on cue."""

from __future__ import annotations

import stat


def fake_python(tmp_path, script: str) -> str:
    """The path of an executable /bin/sh script with this body, for children.sys.executable."""
    path = tmp_path / "fake-python"
    path.write_text("#!/bin/sh\n" + script)
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return str(path)
