"""Conformance cases, expectations, metrics, runner and the x3drbp command line."""
