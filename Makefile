# weave-cut: `make run` builds every recipe in templates/recipes into build/<recipe>/ (the
# figures recipe is also `make figures`) with a page build/<recipe>/index.html each, and
# build/index.html linking them; `make test` runs the tests but the slow ones, `make test-slow`
# those (`make test-all` both, as CI does), `make docs` redraws the
# README's images. All create .venv and install the project first when needed, with the exact
# versions of constraints.txt (`make lock` renews it; `make test-latest` tries the newest).

PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
WC     := $(VENV)/bin/weave-cut
STAMP  := $(VENV)/.installed
LOCK   := constraints.txt
SRC    := $(shell find src -name '*.py' 2>/dev/null) pyproject.toml
OUT    := build

RECIPES := $(wildcard templates/recipes/*.toml) $(wildcard examples/*.toml)
BUILT   := $(patsubst %.toml,$(OUT)/%/.built,$(notdir $(RECIPES)))

.PHONY: run figures docs test test-slow test-all test-latest lock fuzz bench bench-engine bench-kits mutation clean help
.DELETE_ON_ERROR:

help:  ## list the targets
	@grep -E '^[a-z-]+:.*## ' $(MAKEFILE_LIST) | sed 's/:.*## /\t/'

$(STAMP): pyproject.toml setup.py $(LOCK)
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -c $(LOCK) -e '.[test]'
	touch $(STAMP)

# Python keeps compiled modules (and pytest its rewritten test modules) in __pycache__ (ignored
# by git) even where the environment says not to: every test process and every command the
# tests start would compile the package and the tests anew (about 6 s CPU per test process)
unexport PYTHONDONTWRITEBYTECODE

JOBS   ?= $(shell nproc 2>/dev/null || echo 2)

run: $(STAMP)  ## build every recipe (templates/recipes, examples) into build/ (incremental, one recipe per core)
	@$(MAKE) --no-print-directory --output-sync=target -j$(JOBS) $(OUT)/index.html
	@echo "built into $(OUT)/: $(notdir $(basename $(RECIPES))); open $(OUT)/index.html"

$(OUT)/index.html: $(BUILT)
	$(PY) -m weavecut.kitpage $@ $(patsubst %/.built,%/index.html,$(BUILT))

# a recipe is rebuilt when it or the package changed; each recipe has its own folder, which
# belongs to make (--force: replace files a weave-cut without a manifest left there)
$(OUT)/%/.built: templates/recipes/%.toml $(STAMP) $(SRC) $(wildcard templates/recipes/*.svg)
	@mkdir -p $(OUT)  # weave-cut makes the output folder, not the folders above it
	$(WC) -q build $< -o $(OUT)/$* --force > /dev/null
	touch $@

$(OUT)/%/.built: examples/%.toml $(STAMP) $(SRC) examples/*.obj examples/*.json examples/*.svg examples/*.dxf
	@mkdir -p $(OUT)
	$(WC) -q build $< -o $(OUT)/$* --force > /dev/null
	touch $@

figures: $(OUT)/figures/.built  ## every paper figure weave-cut reproduces, into build/figures/

docs: $(STAMP)  ## redraw the README's images (docs/, examples/previews/) from the code
	$(PY) docs/make_docs.py

PYTEST := $(PY) -m pytest -n auto --dist worksteal

test: $(STAMP)  ## the tests but those marked slow, in parallel processes (with the versions of constraints.txt)
	$(PYTEST) -m "not slow"

test-slow: $(STAMP)  ## the tests marked slow (whole commands, browsers, servers, subprocesses), in parallel processes
	$(PYTEST) -m slow

test-all: test test-slow  ## every test: the quick ones, then the slow ones (what CI runs)

# test-latest runs the halves of make test and make test-slow (the same pytest lines: the
# targets themselves, with .venv-latest for .venv and no stamp, so nothing installs the lock)
test-latest:  ## make test and make test-slow with the newest release of every dependency (.venv-latest); says which versions differ from constraints.txt
	$(PYTHON) -m venv .venv-latest
	.venv-latest/bin/python -m pip install --quiet --upgrade pip
	.venv-latest/bin/python -m pip install --quiet --upgrade --upgrade-strategy eager -e '.[test]'
	.venv-latest/bin/python -m pip freeze --exclude-editable > .venv-latest/versions.txt
	@grep -v '^#' $(LOCK) | diff - .venv-latest/versions.txt | grep '^[<>]' \
		| sed 's/^</  locked:/; s/^>/  newest:/' || echo "  the newest releases are the locked ones"
	$(MAKE) --no-print-directory --keep-going test test-slow VENV=.venv-latest STAMP=

lock:  ## renew constraints.txt: the newest release of every dependency and test tool, pinned
	rm -rf .venv-lock
	$(PYTHON) -m venv .venv-lock
	.venv-lock/bin/python -m pip install --quiet --upgrade pip
	.venv-lock/bin/python -m pip install --quiet '.[test]'
	{ echo "# exact versions for make test, make run and CI; renewed by make lock"; \
	  .venv-lock/bin/python -m pip freeze --exclude weave-cut; } > $(LOCK).part
	mv $(LOCK).part $(LOCK)
	rm -rf .venv-lock build/lib build/bdist*
	@echo "$(LOCK) renewed: check it in after make test passes"

fuzz: $(STAMP)  ## the untrusted-input fuzz suite with the long hypothesis profile
	HYPOTHESIS_PROFILE=long $(PY) -m pytest tests/untrusted -k "fuzz or corpus"

bench: $(STAMP)  ## run the benchmarks (throughput, ratios against peers)
	$(PY) -m pip install --quiet -c $(LOCK) -e '.[bench]' || echo "some peers did not install"
	$(PY) benchmarks/bench_snub.py
	$(PY) benchmarks/bench_weave.py
	$(PY) benchmarks/bench_schemes.py
	$(PY) benchmarks/bench_levels.py
	$(PY) benchmarks/bench_memory.py
	$(PY) benchmarks/bench_mesh_io.py
	$(PY) benchmarks/bench_startup.py  # fails when --help gets slow against import numpy
	$(PY) benchmarks/bench_puzzle.py
	$(PY) benchmarks/bench_kits.py

bench-kits: $(STAMP)  ## whole kit commands (paper models, laser card, puzzle, ball) against the frozen code of before they were made fast: CPU and ratio
	$(PY) benchmarks/bench_kits.py

bench-engine: $(STAMP)  ## the engine at scale (snub step, stats, OBJ read, memory guard, schemes, tiles), before and after its speed work, in one run (about 5 minutes on a quiet machine)
	$(PY) -m pip install --quiet -c $(LOCK) -e '.[bench]' || echo "some peers did not install"
	$(PY) benchmarks/bench_engine.py

MUTATION_SAMPLE ?= 100
mutation: $(STAMP)  ## mutation testing, a random sample of 100 mutants per package (MUTATION_SAMPLE=0: all; PACKAGES="weave export"; MUTATION_ARGS=--survivors): build/mutation/report.md
	$(PY) -m pip install --quiet -c $(LOCK) -e '.[mutation]'
	$(PY) tools/mutation.py --sample $(MUTATION_SAMPLE) $(MUTATION_ARGS) $(PACKAGES)

clean:  ## remove build outputs (keeps .venv)
	rm -rf $(OUT) .pytest_cache .hypothesis
