# weave-cut: `make run` builds the default outputs into build/, `make test` runs the tests.
# Both create .venv and install the project first when needed.

PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
WC     := $(VENV)/bin/weave-cut
STAMP  := $(VENV)/.installed
SRC    := $(shell find src -name '*.py' 2>/dev/null) pyproject.toml
OUT    := build

DEFAULT_OUTPUTS := \
	$(OUT)/pentagon-level4.svg $(OUT)/pentagon-level4.dxf \
	$(OUT)/square-grid-level3.svg $(OUT)/square-grid-level3.dxf \
	$(OUT)/square-grid-weave-level2.svg $(OUT)/pentagon-weave-level4.png

.PHONY: run test bench clean help
.DELETE_ON_ERROR:

help:  ## list the targets
	@grep -E '^[a-z]+:.*## ' $(MAKEFILE_LIST) | sed 's/:.*## /\t/'

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

run: $(DEFAULT_OUTPUTS)  ## build the default outputs into build/
	@echo "built: $(DEFAULT_OUTPUTS)"

$(OUT):
	mkdir -p $(OUT)

$(OUT)/pentagon-level4.%: $(STAMP) $(SRC) | $(OUT)
	$(WC) subdivide pentagon --levels 4 -o $@

$(OUT)/square-grid-level3.%: $(STAMP) $(SRC) | $(OUT)
	$(WC) subdivide square-grid --levels 3 -o $@

$(OUT)/square-grid-weave-level2.svg: $(STAMP) $(SRC) | $(OUT)
	$(WC) weave square-grid --levels 2 --outline-level 1 -o $@

$(OUT)/pentagon-weave-level4.png: $(STAMP) $(SRC) | $(OUT)
	$(WC) weave pentagon --levels 4 --outline-level 3 --palette puzzle -o $@

test: $(STAMP)  ## run the whole test suite
	$(PY) -m pytest

bench: $(STAMP)  ## run the benchmarks (throughput, ratios against peers)
	$(PY) -m pip install --quiet -e '.[bench]' || echo "some peers did not install"
	$(PY) benchmarks/bench_snub.py

clean:  ## remove build outputs (keeps .venv)
	rm -rf $(OUT) .pytest_cache .hypothesis
