# Two-command set-up: `make report` and `make test` each create .venv and install
# the package (editable, with the dev extra) when it is missing or older than
# pyproject.toml.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.dfa-installed
# numba compiles the kernels once and caches them where `.venv/bin/dfa` does (dfa/core/cache.py): in
# ~/.cache/dfa/numba/<key>, the key a hash of dfa/core/*.py and of the Python and numba versions, so `make` and
# the command share one cache and an edited kernel never loads stale code. DFA_CACHE_DIR moves the folder; an
# explicit NUMBA_CACHE_DIR is used as it is (then clear it yourself after editing dfa/core/).
export MPLBACKEND := Agg

.PHONY: all venv report test lint docs explore bench readme clean

all: test

$(STAMP): pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	@# the distribution was renamed dfa -> dfa-haptics: drop an old editable install of this checkout
	@$(BIN)/python -m pip uninstall --quiet --yes dfa >/dev/null 2>&1 || true
	@# pip byte-compiles every file of every package on one core (sympy, scipy, matplotlib, ...: 45 s of a fresh
	@# install); compileall does it on every core (36 s in all on 2 cores). Not left to the first imports: with
	@# PYTHONDONTWRITEBYTECODE set, as on CI, every process would compile what it imports again (the suite +50 s).
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-compile -e '.[dev]'
	@$(BIN)/python -m compileall -q -j 0 "$$($(BIN)/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')" >/dev/null || true
	@# the bytecode pip writes for a regular install (an editable one, with PYTHONDONTWRITEBYTECODE set, would
	@# compile every module again in every command: about 0.15 s of `dfa stiffness --quick`)
	@$(BIN)/python -m compileall -q dfa >/dev/null
	@touch $(STAMP)

venv: $(STAMP)

# The validation paragraph of the report comes from the summary named here, never from a file found by chance.
VALIDATION_SUMMARY := $(wildcard reports/validation/validation.json)

# The default device's report with its 20 × 20 Z-width: it reproduces the committed reports/design_report_delta.*
# and reports/figures/delta_* byte for byte (git status stays clean).
report: $(STAMP)
	$(BIN)/dfa report --out reports --format both --zwidth 20 --tune $(if $(VALIDATION_SUMMARY),--validation $(VALIDATION_SUMMARY))

# The whole suite (doctests included), and beside it format, lint, layering and types (their output is printed
# when the suite ends; either failing fails the target). Work stealing: an idle worker takes tests queued on the
# other (with the default distribution one worker sat idle while the other finished its slow tests: 392 s against
# 294 s for the same suite on 2 cores). Lint beside the suite instead of after it: 15 s less on 2 cores. Before the
# suite, tests/compile_kernels.py compiles the big kernels once, in two processes, beside lint (on a cold cache both
# workers would each compile them, at the same time); with a warm cache it only loads them.
test: $(STAMP)
	@mkdir -p .cache; $(MAKE) --no-print-directory lint > .cache/lint.log 2>&1 & lint=$$!; \
	$(BIN)/python tests/compile_kernels.py; warmed=$$?; \
	HYPOTHESIS_PROFILE=ci $(BIN)/python -m pytest -q -n 2 --dist worksteal; tests=$$?; \
	wait $$lint; linted=$$?; cat .cache/lint.log; \
	if [ $$tests -ne 0 ] || [ $$linted -ne 0 ] || [ $$warmed -ne 0 ]; then \
	echo "make test: tests exit $$tests, lint exit $$linted, kernel warm-up exit $$warmed"; exit 1; fi

# Format, lint, layering (import contracts in pyproject.toml) and types.
lint: $(STAMP)
	$(BIN)/ruff format --check .
	$(BIN)/ruff check .
	$(BIN)/lint-imports
	$(BIN)/mypy

# Random hypothesis examples, many more of them: hunt for counterexamples on demand.
explore: $(STAMP)
	HYPOTHESIS_PROFILE=explore $(BIN)/python -m pytest -q -n 2 --dist worksteal -p no:cacheprovider

# Rewrite the README's console examples with what the code prints now (tests check them).
readme: $(STAMP)
	$(BIN)/python examples/readme_console.py --write

# API reference, paper reproduction, validation and benchmarks as a site in docs/_build/html.
docs: $(STAMP)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -e '.[docs]'
	$(BIN)/python -m sphinx -b html -q -W --keep-going docs docs/_build/html

bench: $(STAMP)
	$(BIN)/python benchmarks/run.py --out reports/benchmarks.md

clean:
	rm -rf $(VENV) .cache build *.egg-info docs/_build docs/generated docs/api.md
