"""`x3drbp check`: load and validate scenes, and say what each uses."""

from __future__ import annotations

import argparse
import sys

from x3d_core.encodings.load import load
from x3d_core.files.paths import none_under, scene_files, shown
from x3d_core.model.scene import LoadError
from x3d_core.semantics.analysis import features, summarize
from x3d_core.semantics.outcome import outcome_warnings


def cmd_check(args: argparse.Namespace) -> int:
    files = scene_files(args.paths)
    if not files:
        print(f"x3drbp check: {none_under(args.paths)}", file=sys.stderr)
        return 2
    failed = 0
    for path in files:
        try:
            scene = load(path)
        except LoadError as e:
            for d in e.diagnostics:
                if d.severity == "error" or not args.quiet:
                    print(d)
            failed += 1
            continue
        except Exception as e:  # a bug of ours, never the file's fault: still one line, no traceback
            print(f"{shown(path)}:1:1: error: internal error while reading ({type(e).__name__}: {e}); please report it")
            failed += 1
            continue
        scene.diagnostics.extend(outcome_warnings(scene))
        for d in scene.diagnostics:
            if d.severity == "error" or not args.quiet:
                print(d)
        if scene.errors:
            failed += 1
            continue
        if not args.quiet:
            print(f"{shown(path)}: ok ({scene.encoding}, X3D {scene.version}, {len(scene.warnings)} warning{'' if len(scene.warnings) == 1 else 's'})")
            for line in summarize(scene).lines():
                print(f"  {line}")
            print(f"  features: {' '.join(features(scene)) or 'none'}")
    if len(files) > 1:
        print(f"{len(files) - failed} of {len(files)} files ok")
    return 1 if failed else 0


def add_command(sub) -> None:
    check = sub.add_parser("check", help="load and validate X3D files; summarize what each scene uses")
    check.add_argument("paths", nargs="+", help="files, or folders searched for .x3d/.x3dv/.x3dj files")
    check.add_argument("-q", "--quiet", action="store_true", help="print errors only")
    check.set_defaults(func=cmd_check)
