"""Engine adapters: one module per engine against a small backend protocol.

Layering (docs/layout.md; tests/test_project.py holds it): modules here import
x3d_core and their engine, never conformance or reports. The protocol and the adapters
arrive with the evaluator.
"""
