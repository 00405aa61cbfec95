"""What the commands answer a mistyped option and what `backends` prints (issue 29): the
subcommand's own usage with the option meant, and no engine's banner among the backends."""

from __future__ import annotations

import subprocess
import sys

import pytest

from backends import base
from conftest import ROOT, SCENES


def _x3drbp(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "x3drbp", *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=300)


@pytest.mark.parametrize("typo", [["--duraton", "2"], ["--duraton=2"]])
def test_a_mistyped_option_gets_the_command_s_usage_and_the_option_meant(typo):
    r = _x3drbp("run", f"{SCENES}/examples/pendulum.x3d", "--backend", "bullet", *typo)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.startswith("usage: x3drbp run ") and "usage: x3drbp [-h]" not in r.stderr
    assert r.stderr.rstrip().endswith("did you mean --duration?")


def test_an_unknown_word_far_from_every_option_is_refused_without_a_guess():
    r = _x3drbp("advise", f"{SCENES}/examples/pendulum.x3d", "--zzzzzzzz")
    assert r.returncode == 2 and "usage: x3drbp advise " in r.stderr and "did you mean" not in r.stderr


@pytest.mark.skipif(isinstance(base.available().get("bullet", "absent"), str), reason="pybullet not installed")
def test_backends_prints_no_engine_banner():
    r = _x3drbp("backends", "--features")
    assert r.returncode == 0 and "build time" not in r.stdout + r.stderr, r.stderr
    assert r.stdout.startswith("bullet ") or "\nbullet " in r.stdout


@pytest.mark.parametrize("argv, says", [
    (["expectations", "--check", "--cases", ","], "x3drbp expectations: --cases names no case: ','"),
    (["expectations", "--check", "--backends", " , "], "x3drbp expectations: --backends names no backend: ' , '"),
    (["validate", "scenes/examples/pendulum.x3d", "--trace", "t.csv", "--against", ","],
     "x3drbp validate: --against names no backend: ','"),
    (["x-ite", "cases", "--cases", ",", "--out", "o"], "x3drbp x-ite: --cases names no case: ','"),
])
def test_a_list_option_that_names_nothing_is_bad_usage_not_the_default(tmp_path, monkeypatch, capsys, argv, says):
    """`--cases ,` ran every case (and `--backends ,` every backend), as if the option were not
    given, where `--dts ,` was already refused as a mistake."""
    from conformance.analyses import validation
    from x3drbp import main as cli_main
    from conformance.runner import verdicts

    def ran(*args, **kwargs):
        raise AssertionError("it ran")
    monkeypatch.setattr(verdicts, "run_matrix", ran)
    monkeypatch.setattr(validation, "run_backends", ran)
    if argv[0] == "validate":
        trace = tmp_path / "t.csv"
        installed = [b for b, v in base.available().items() if not isinstance(v, str)]
        if not installed:
            pytest.skip("no engine is installed")
        assert cli_main(["run", f"{ROOT}/{argv[1]}", "--backend", installed[0], "--duration", "0.1", "--trace", str(trace)]) == 0
        argv = ["validate", f"{ROOT}/{argv[1]}", "--trace", str(trace), *argv[4:]]
        capsys.readouterr()
    monkeypatch.chdir(tmp_path)
    assert cli_main(argv) == 2
    assert capsys.readouterr().err.splitlines() == [says]
