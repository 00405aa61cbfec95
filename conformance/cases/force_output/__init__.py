"""force_output: X3DRigidJointNode.forceOutput: which output fields a joint reports, by each rule of 37.3.3."""

from __future__ import annotations

from collections.abc import Sequence

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.results import Measure, Settings, spec

# Named's and Pair's: a forceOutput ignored (every output reported, or none) is whole rows off, at a tolerance of 0
EXACTLY = spec("37.3.3 X3DRigidJointNode: This field is used to control which of those outputs the author requires "
               "to be generated. The values of the array are to describe the names, exactly, of the output "
               "field(s) that are to be updated at the start of the next frame.",
               also=("37.3.3 X3DRigidJointNode: The forceOutput field is used to control which output fields are to "
                     "be generated for the next frame.",))
ALL = spec("37.3.3 X3DRigidJointNode: If \"ALL\" is specified anywhere in the array, all fields are to be updated.")
NONE_BESIDE = spec("37.3.3 X3DRigidJointNode: If \"NONE\" is specified, no updates are performed. If the list of "
                   "values is empty, it shall be treated as if \"NONE\" were specified. Other values provided in "
                   "addition to \"NONE\" shall be ignored.")
EMPTY = spec("37.3.3 X3DRigidJointNode: If \"NONE\" is specified, no updates are performed. If the list of values is "
             "empty, it shall be treated as if \"NONE\" were specified.")

# force_output.x3d: SingleAxisHingeJoint's outputs, and per hinge (its arm) what its forceOutput selects, and why
OUTPUTS = ("angle", "angleRate", "body1AnchorPoint", "body2AnchorPoint")
SELECTS = {"Named": ("Arm1", ("angle",), EXACTLY),
           "Pair": ("Arm2", ("angleRate", "body2AnchorPoint"), EXACTLY),
           "AllAmong": ("Arm3", OUTPUTS, ALL),
           "NoneAmong": ("Arm4", (), NONE_BESIDE),
           "Empty": ("Arm5", (), EMPTY)}


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Per hinge, the output rows wrong: a frame of a selected output without its row, or any row
    of an output not selected. Which rows a trace holds is no matter of integration or rounding:
    exact, tolerance 0. Each misreading is whole rows off (every output written, or the names
    beside NONE: at least one output at every frame), so any tolerance below a frame's row
    would do; 0 says the count is exact. The frames are the arm's: its state has a row at every
    frame."""
    tr = traces[0]
    out = []
    for joint, (arm, selected, basis) in SELECTS.items():
        frames = set(tr.series(arm, "position")[0].tolist())
        wrong = 0
        for f in OUTPUTS:
            rows = set(tr.series(joint, f)[0].tolist()) if (joint, f) in tr.keys() else set()
            wrong += len(frames - rows) if f in selected else len(rows)
        wanted = f"one a frame for {', '.join(selected)}, none for the others" if selected else "none at all"
        out.append(Measure(f"{joint}: output rows wrong ({wanted})", wrong, 0.0, "rows", basis))
    return out


CASE = Case("force_output", "force_output.x3d",
            "forceOutput on five SingleAxisHingeJoints: \"angle\"; \"angleRate\" \"body2AnchorPoint\"; \"angle\" "
            "\"ALL\"; \"NONE\" \"angleRate\"; empty: a row each frame for exactly the outputs selected (angle; those "
            "two; all four; none; none)",
            (Settings(0.25, 1 / 240),), expect,
            exercises=("SingleAxisHingeJoint.forceOutput",),
            # NONE's other values reported (X_ITE), every output reported whatever is named, an empty list read as ALL
            mutations=(Mutation("forceOutput='\"NONE\" \"angleRate\"'", "forceOutput='\"angleRate\"'"),
                       Mutation("forceOutput='\"angle\"'", "forceOutput='\"ALL\"'"),
                       Mutation("forceOutput=''", "forceOutput='\"ALL\"'")),
            warned=("SingleAxisHingeJoint NoneAmong.forceOutput",))
