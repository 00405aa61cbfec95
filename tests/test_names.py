"""File names as commands echo, split and number them: a name with a newline cannot forge a
line of `check`'s output, a comma in a scene's name can be written for `sweep --scenes`, and
results named after scenes never overwrite each other, whatever the scenes are called."""

from __future__ import annotations

import shutil
import subprocess
import sys

from conftest import ROOT, case_scene
from x3drbp import main as cli_main
from x3drbp import options
from x3drbp import report as R

FORGED = "x.x3d: ok (xml, X3D 4.0, 0 warnings)"


def test_scenes_of_one_stem_and_one_named_like_the_number_get_results_of_their_own():
    stems = R.stems(["a/ff.x3d", "b/ff.x3d", "ff-2.x3d"])
    assert stems == ["ff", "ff-3", "ff-2"]  # ff-2 is the third scene's own name: the second's number skips it
    assert R.stems(["ff-2.x3d", "a/ff.x3d", "b/ff.x3d", "c/ff.x3d"]) == ["ff-2", "ff", "ff-3", "ff-4"]


def test_a_file_name_with_a_newline_cannot_forge_a_line_of_check(tmp_path):
    good = tmp_path / f"{FORGED}\nevil.x3d"
    shutil.copy(case_scene("free_fall"), good)
    (tmp_path / f"b\n{FORGED}\nc.x3d").write_text("<X3D><Scene><Broken")
    r = subprocess.run([sys.executable, "-m", "x3drbp", "check", str(tmp_path)], cwd=ROOT,
                       capture_output=True, text=True, timeout=120)
    lines = r.stdout.splitlines()
    assert not any(ln.startswith(FORGED) for ln in lines), lines
    assert f"{str(good)!r}: ok (xml, X3D 4.0, 0 warnings)" in lines  # the name quoted, its newline escaped
    assert [ln for ln in lines if ": error: " in ln][0].startswith(repr(str(tmp_path / f"b\n{FORGED}\nc.x3d")) + ":1:")


def test_a_comma_in_a_scene_s_name_is_written_with_a_backslash(tmp_path, capsys):
    odd = tmp_path / "my scenes" / "a,b.x3d"
    odd.parent.mkdir()
    shutil.copy(case_scene("free_fall"), odd)
    escaped = str(odd).replace(",", "\\,")
    assert options.listed([f"projectile,{escaped}", "free_fall"]) == ["projectile", str(odd), "free_fall"]
    # the sweep takes the name (and stops at the unknown backend, before it loads the scene)
    assert cli_main(["sweep", "--scenes", escaped, "--backends", "nope", "--out", str(tmp_path / "o")]) == 2
    assert "unknown backend(s) nope" in capsys.readouterr().err
    steps = dict(R._steps(str(tmp_path / "r"), ["pymunk", "mujoco"], False, False, [str(odd)]))
    (sweep,) = steps["sweep"]
    assert options.listed([sweep[sweep.index("--scenes") + 1]])[-1] == str(odd)  # report escapes what it hands on


def test_a_terminal_escape_or_newline_in_a_def_name_or_a_path_is_shown_as_text(tmp_path, capsys):
    """A JSON DEF name `B\\u001b[31m...` reached the terminal raw in check's diagnostics and in
    validate's markdown (recolouring it; its newline split the line), as did a trace's or an
    output's name in validate's one-line refusals."""
    from reports.text import escape
    scene = tmp_path / "ball.x3dj"
    text = open(f"{ROOT}/scenes/examples/bouncing_ball.x3dj", encoding="utf-8").read()
    scene.write_text(text.replace('"@DEF": "Ball"', '"@DEF": "B\\u001b[31m\\nX"').replace('"@mass": 0.2', '"@mass": -0.2'))
    assert cli_main(["check", str(scene)]) == 1
    out = capsys.readouterr().out
    assert "\x1b" not in out and "RigidBody B\\x1b[31m\\nX.mass: -0.2 is out of range" in out.splitlines()[0]
    assert "\x1b" not in escape("B\x1b[31m<b>") and "B\\\\x1b" in escape("B\x1b[31m<b>")
    odd = str(tmp_path / "t\x1b[31m\nx.csv")
    assert cli_main(["validate", case_scene("free_fall"), "--trace", odd]) == 2
    assert capsys.readouterr().err == f"{str(tmp_path)}/t\\x1b[31m\\nx.csv: cannot read file: No such file or directory\n"
    json_out = str(tmp_path / "j\x1b[1m" / "x.json")
    assert cli_main(["validate", case_scene("free_fall"), "--trace", odd, "--json", json_out]) == 1
    err = capsys.readouterr().err
    assert "\x1b" not in err and err.count("\n") == 1 and "cannot write" in err
