"""The mutants installed as a plug-in distribution, the way pip leaves one, without pip.

A folder holding x3drbp_mutants-0.1.0.dist-info (METADATA and entry_points.txt, one
`x3drbp.backends` entry point per mutant) is a site: on PYTHONPATH, every process the runner
starts (they inherit the environment) finds the mutants in the backend registry. The modules
they name are this package's, found on the path the runner's children already have.
"""

from __future__ import annotations

import os

from conformance.mutants.table import BY_NAME

GROUP = "x3drbp.backends"  # backends.base.GROUP, not imported: the parent imports no backend
DIST = "x3drbp_mutants"


def install(folder: str) -> str:
    """The site folder, made (or remade) with every mutant's entry point; returns it."""
    info = os.path.join(folder, f"{DIST}-0.1.0.dist-info")
    os.makedirs(info, exist_ok=True)
    with open(os.path.join(info, "METADATA"), "w") as f:
        f.write(f"Metadata-Version: 2.1\nName: {DIST.replace('_', '-')}\nVersion: 0.1.0\n")
    with open(os.path.join(info, "entry_points.txt"), "w") as f:
        f.write("\n".join([f"[{GROUP}]", *(f"{m.backend} = conformance.mutants.plugin:{m.attribute}"
                                           for m in BY_NAME.values()), ""]))
    return folder


def on_path(folder: str) -> str:
    """This process's PYTHONPATH with the site first: the value its children need."""
    kept = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p and p != folder]
    return os.pathsep.join([folder, *kept])
