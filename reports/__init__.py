"""Rendering of results (markdown, HTML, plots, rerun recordings).

Layering (DESIGN.md): reports read results; they run nothing and import no engine.
"""
