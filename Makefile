# Two commands do all the set-up on a fresh machine with Python 3.11+:
#   make report  installs into .venv and runs the main job: x3drbp check over the bundled
#                scenes, then x3drbp report (conformance, comparisons, sweeps, stability and
#                the feature tables) into out/report/index.html and report.md
#   make test    installs into .venv (with the dev tools) and runs the tests
# The documentation (README.md and docs/, as a site: mkdocs.yml):
#   make docs    builds it into out/site, failing on any warning (tests/test_docs.py too)
# Opt-in, for the X_ITE browser (Debian's chromium and nodejs, npm packages pinned in
# conformance/browsers/x_ite/package-lock.json; no browser download):
#   make x-ite   installs them, then runs the main job with X_ITE's column (report --x-ite)
#   make test-x-ite  the tests that drive the real browser (pytest -m x_ite); test-x-ite-only
#                runs them without installing (they skip, saying why, where it is missing)
PYTHON ?= python3
VENV := .venv
STAMP := $(VENV)/.installed

.PHONY: report test docs bench ode-lib x-ite x-ite-install test-x-ite test-x-ite-only

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/pip install --quiet --upgrade pip
	$(VENV)/bin/pip install --quiet -e '.[dev]'
	touch $(STAMP)

# The ode backend loads the system's libode (Debian: libode8): installed here where it is missing
# and the machine allows it (root, or sudo without a password, and apt-get), said in one line;
# else ODE is unavailable, said in one line, and its tests skip, saying why.
ode-lib:
	@if ldconfig -p 2>/dev/null | grep -q libode; then :; \
	elif command -v apt-get >/dev/null && { [ "$$(id -u)" -eq 0 ] || sudo -n true 2>/dev/null; }; then \
		s=$$([ "$$(id -u)" -eq 0 ] || echo "sudo -n"); \
		if $$s apt-get update -q >/dev/null 2>&1 && \
		   $$s apt-get install -y -q --no-install-recommends libode8 >/dev/null 2>&1; then \
			echo "make: installed libode8 (apt-get install libode8) for the ode backend"; \
		else echo "make: could not install libode8 (apt-get failed): the ode backend is unavailable"; fi; \
	else echo "make: libode8 is missing and cannot be installed here (no apt-get, or no root or sudo): the ode backend is unavailable"; fi

report: $(STAMP) ode-lib
	$(VENV)/bin/x3drbp check -q conformance/cases scenes
	$(VENV)/bin/x3drbp report --out out/report

test: $(STAMP) ode-lib
	$(VENV)/bin/python -m pytest -q

docs: $(STAMP)
	$(VENV)/bin/python -m mkdocs build --strict --site-dir out/site

SUDO := $(shell [ "$$(id -u)" -eq 0 ] || echo sudo)
X_ITE := conformance/browsers/x_ite

x-ite-install:
	@# only what is missing: a machine with Node from elsewhere (NodeSource's nodejs brings its own npm)
	@# cannot also take Debian's npm, which conflicts with it
	@missing=; [ -x /usr/bin/chromium ] || missing=chromium; command -v npm >/dev/null || missing="$$missing nodejs npm"; \
	if [ -n "$$missing" ]; then \
		$(SUDO) apt-get update -q && $(SUDO) apt-get install -y -q --no-install-recommends $$missing; fi
	cd $(X_ITE) && npm ci --no-audit --no-fund --loglevel=error

x-ite: $(STAMP) x-ite-install
	$(VENV)/bin/x3drbp check -q conformance/cases scenes
	$(VENV)/bin/x3drbp report --x-ite --out out/report

test-x-ite: $(STAMP) x-ite-install test-x-ite-only

test-x-ite-only: $(STAMP)
	$(VENV)/bin/python -m pytest -q -m x_ite

bench: $(STAMP)
	$(VENV)/bin/python benchmarks/load_large.py
	$(VENV)/bin/python benchmarks/run_overhead.py --backends mujoco,bullet,dart
