"""Mutant engines: how sensitive the conformance suite is to the bugs X3D browsers really have.

A mutant is a real backend wrapping one of x3drbp's own (table.py: one row each): it makes one
realistic browser bug, by editing the World before the engine builds it (a field ignored, read in
the wrong units or the wrong sense) or by distorting what the built simulation reports or
receives (a state one step late, loads in the body frame). plugin.py makes each row a backend of
the `x3drbp.backends` entry point group and site.py installs them all as a plug-in distribution
in a folder on PYTHONPATH, so that the ordinary runner runs every mutant in its own child
process, as it runs any engine.

A mutant is killed when some case's verdict on it is worse than on its unmutated base (score.py
says the rule); `python -m conformance.mutants` runs every mutant on every case its base passes
and writes the score to out/mutants/. A survivor is a gap of the suite: its row names the case
that would catch it.
"""
