"""Rendering of results (markdown, HTML, plots, rerun recordings).

Layering (docs/layout.md; tests/test_project.py holds it): reports read results
(x3d_core, conformance.results); they run nothing and import no engine.
"""
