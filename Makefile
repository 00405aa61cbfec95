# Two commands do all the set-up on a fresh machine with Python 3.11+:
#   make report  installs into .venv and runs the main job: x3drbp check over the bundled
#                scenes, then x3drbp report (conformance, comparisons, sweeps, stability and
#                the feature tables) into out/report/index.html and report.md
#   make test    installs into .venv (with the dev tools) and runs the tests
PYTHON ?= python3
VENV := .venv
STAMP := $(VENV)/.installed

.PHONY: report test bench

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/pip install --quiet --upgrade pip
	$(VENV)/bin/pip install --quiet -e '.[dev]'
	touch $(STAMP)

report: $(STAMP)
	$(VENV)/bin/x3drbp check -q scenes
	$(VENV)/bin/x3drbp report --out out/report

test: $(STAMP)
	$(VENV)/bin/python -m pytest -q

bench: $(STAMP)
	$(VENV)/bin/python benchmarks/load_large.py
	$(VENV)/bin/python benchmarks/run_overhead.py --backends mujoco,bullet,dart
