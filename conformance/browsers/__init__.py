"""Real X3D browsers run headless on the conformance cases and judged as the backends are."""
