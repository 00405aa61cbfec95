"""What x3drbp measures beyond a case's verdict: comparisons of runs, sweeps, the hard cases, traces of other implementations."""
