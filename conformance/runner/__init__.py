"""Running cases on backends: each run a child process (children), judged (verdicts), on the backends found here (probe)."""
