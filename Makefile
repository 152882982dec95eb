# weave-cut: `make run` builds every recipe in templates/recipes into build/<recipe>/,
# `make test` runs the tests. Both create .venv and install the project first when needed.

PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
WC     := $(VENV)/bin/weave-cut
STAMP  := $(VENV)/.installed
SRC    := $(shell find src -name '*.py' 2>/dev/null) pyproject.toml
OUT    := build

RECIPES := $(wildcard templates/recipes/*.toml) $(wildcard examples/*.toml)
BUILT   := $(patsubst %.toml,$(OUT)/%/.built,$(notdir $(RECIPES)))

.PHONY: run figures test bench clean help
.DELETE_ON_ERROR:

help:  ## list the targets
	@grep -E '^[a-z]+:.*## ' $(MAKEFILE_LIST) | sed 's/:.*## /\t/'

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

run: $(BUILT)  ## build every recipe (templates/recipes, examples) into build/ (incremental)
	@echo "built into $(OUT)/: $(notdir $(basename $(RECIPES)))"

# a recipe is rebuilt when it or the package changed; each recipe has its own folder
$(OUT)/%/.built: templates/recipes/%.toml $(STAMP) $(SRC)
	$(WC) -q build $< -o $(OUT)/$* > /dev/null
	touch $@

$(OUT)/%/.built: examples/%.toml $(STAMP) $(SRC) examples/*.obj examples/*.json examples/*.svg examples/*.dxf
	$(WC) -q build $< -o $(OUT)/$* > /dev/null
	touch $@

figures: $(STAMP)  ## every paper figure weave-cut reproduces, into build/figures/
	mkdir -p $(OUT)/figures
	@for name in $$($(WC) figure --list | cut -d' ' -f1); do \
		case $$name in level-image) ext=png;; *) ext=svg;; esac; \
		echo "figure $$name"; $(WC) -q figure $$name -o $(OUT)/figures/$$name.$$ext || exit 1; \
	done

test: $(STAMP)  ## run the whole test suite
	$(PY) -m pytest

bench: $(STAMP)  ## run the benchmarks (throughput, ratios against peers)
	$(PY) -m pip install --quiet -e '.[bench]' || echo "some peers did not install"
	$(PY) benchmarks/bench_snub.py
	$(PY) benchmarks/bench_weave.py
	$(PY) benchmarks/bench_schemes.py
	$(PY) benchmarks/bench_levels.py
	@for b in benchmarks/bench_puzzle.py benchmarks/bench_strands.py; do \
		[ -f $$b ] && $(PY) $$b || true; done

clean:  ## remove build outputs (keeps .venv)
	rm -rf $(OUT) .pytest_cache .hypothesis
