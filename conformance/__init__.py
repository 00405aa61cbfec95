"""The conformance suite, one job per part (the command line above it is x3drbp/):

- results.py: the result types every part hands on and reports/ reads;
- cases/: the conformance cases, one folder each (scene, expectation, mutations);
- expectations/: every verdict pinned, one file per backend;
- runner/: each run in a child process (children), the cases' verdicts (verdicts), the
  backends found here (probe);
- analyses/: comparisons of runs, sweeps of speed against error, the hard cases, checks
  of another implementation's trace;
- browsers/: real X3D browsers driven headless (x_ite);
- mutants/: mutant engines that measure how sensitive the cases are;
- pytest_plugin.py: the cases as tests in an engine's own test run.
"""
