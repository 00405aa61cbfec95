"""X_ITE in headless Chromium under a virtual clock: the harness records, the judge gives verdicts."""
