# Two entry points, both from a fresh machine with Python >= 3.11 and make:
#   make run   installs everything into .venv and runs the main job
#   make test  installs everything into .venv and runs the test suite
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: run test lint bench clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[all]"
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/stickslip simulate --lam 3 --zeta 0.1 --dva none --plot results/simulate-rigid.png
	$(BIN)/stickslip simulate --lam 3 --zeta 0.1 --dva optimal --plot results/simulate-optimal.png
	@echo "Figures written to results/"

test: $(STAMP)
	$(BIN)/python -m pytest

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy

bench: $(STAMP)
	$(BIN)/python benchmarks/bench_engine.py

clean:
	rm -rf $(VENV) build dist .pytest_cache
