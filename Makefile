# Two entry points, both from a fresh machine with Python >= 3.11 and make:
#   make run   installs everything into .venv and runs the main job
#   make test  installs everything into .venv and runs the test suite
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: run test browser lint bench docs clean clean-cache

$(STAMP): pyproject.toml
	@echo "make: creating the virtual environment $(VENV)"
	$(PYTHON) -m venv $(VENV)
	@echo "make: installing stickslip and its dependencies into $(VENV) with pip (about a minute; quiet until done)"
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[all]"
	@echo "make: installed; now compiling the numba kernels once, so that no first run waits for them"
	@# one family per core; stickslip compile names each family as it is ready
	$(BIN)/stickslip compile
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/stickslip reproduce --out results
	@echo "Open results/report.html (or results/report.md); figures in results/figures, data in results/data"

test: $(STAMP)
	@$(MAKE) --no-print-directory browser
	@# one worker per core (pytest-xdist); a file's tests stay together in one worker
	$(BIN)/python -m pytest -n auto --dist loadfile

# What the browser test (tests/test_app_browser.py) needs besides the Python extras: Debian's
# Chromium. Installed here, in the open, as root when missing; a failure is tolerated (the test
# then skips and says why). The test suite itself never installs anything.
browser:
	@if command -v chromium >/dev/null 2>&1 || [ -x /usr/bin/chromium ]; then \
		echo "browser tests: chromium is installed"; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
		echo "browser tests: installing chromium and chromium-driver with apt-get (the browser test skips if this fails)"; \
		mkdir -p $(VENV); ( apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium chromium-driver ) \
			> $(VENV)/browser-install.log 2>&1 \
			&& echo "browser tests: chromium installed (log: $(VENV)/browser-install.log)" \
			|| echo "browser tests: apt-get could not install chromium (log: $(VENV)/browser-install.log); tests/test_app_browser.py will skip"; \
	else \
		echo "browser tests: chromium is missing and installing it needs root and apt-get; tests/test_app_browser.py will skip"; \
	fi

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy

# the documentation site, warnings as errors; the gallery (examples/) runs as part of it
docs: $(STAMP)
	$(BIN)/sphinx-build -W --keep-going -b html docs docs/_build/html
	@echo "Open docs/_build/html/index.html"

bench: $(STAMP)
	$(BIN)/python benchmarks/bench_engine.py --quick
	$(BIN)/python benchmarks/bench_map.py
	$(BIN)/python benchmarks/bench_friction.py
	$(BIN)/python benchmarks/bench_basin.py
	$(BIN)/python benchmarks/bench_startup.py
	$(BIN)/python benchmarks/bench_dask.py
	$(BIN)/python benchmarks/bench_structure.py --quick
	$(BIN)/python benchmarks/bench_identify.py

clean-cache:
	find src -name '*.nbi' -delete -o -name '*.nbc' -delete

clean: clean-cache
	rm -rf $(VENV) build dist .pytest_cache docs/_build docs/generated docs/auto_examples docs/api.rst docs/sg_execution_times.rst
