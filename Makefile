# rss-workbench: every target bootstraps its own virtual environment on a bare machine.
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
OUT    ?= out

# Side venv for the commonroad-io oracle: commonroad-io pins protobuf==3.20.2, which our
# MCAP protobuf support cannot use, so it gets its own venv that also sees the project venv.
ORACLE_VENV ?= .venv-oracle-commonroad
ORACLE_STAMP := $(ORACLE_VENV)/.installed

# Side venv for the independent criticality cross-check (commonroad-crime, which brings
# commonroad-io and so the same protobuf pin): built like the commonroad-io oracle's.
CRIME_VENV ?= .venv-oracle-crime
CRIME_STAMP := $(CRIME_VENV)/.installed

# Side venv for the ad-rss-map-integration 5.0 cross-check (its wheel needs the §8.4 fix).
MAP_ORACLE_VENV ?= .venv-oracle-adrss-map
MAP_ORACLE_STAMP := $(MAP_ORACLE_VENV)/.installed

# Side venv for the coverage-guided fuzzer (atheris, a binary wheel for CPython 3.11 on
# x86-64 Linux): kept apart so that the project venv never carries it; sees the project venv.
FUZZ_VENV ?= .venv-fuzz
FUZZ_STAMP := $(FUZZ_VENV)/.installed
# Seconds per target; FUZZ_TARGETS (space-separated) limits the run to some targets.
FUZZ_SECONDS ?= 600
FUZZ_TARGETS ?=

# mypyc-compiled twins of the scene-creation modules (rss/compiled.py): rebuilt whenever a
# source changes; skipped with a message where no C compiler exists (pure Python then).
COMPILED := build/compiled/manifest.json

.PHONY: all setup compiled demo test lint typecheck layers pytest oracle-commonroad oracle-crime acceptance oracle-adrss-map bench bench-fleet samples goldens screenshot fuzz clean

all: test

$(STAMP): pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(0 if sys.version_info >= (3, 11) else "rss-workbench needs Python >= 3.11, found " + sys.version.split()[0])'
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test,dev]'
	@touch $(STAMP)

setup: $(STAMP)

$(COMPILED): $(STAMP) $(wildcard rss/*.py rss/structured/*.py rss/scene/*.py rss/unstructured/*.py) reachsets/bound_scalar.py reachsets/small_scalar.py reachsets/clip_rings.py reachsets/clip_scalar.py reachsets/clip_cells.py reachsets/track_scalar.py tools/build_compiled.py
	$(BIN)/python tools/build_compiled.py

compiled: $(COMPILED)

demo: $(STAMP) $(COMPILED)
	$(BIN)/workbench demo sample_logs --out $(OUT)/demo

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

typecheck: $(STAMP)
	$(BIN)/mypy workbench loaders rss reachsets tests bench

layers: $(STAMP)
	$(BIN)/lint-imports

pytest: $(STAMP) $(COMPILED)
	$(BIN)/python -m pytest -n 2 --dist loadfile -m "not acceptance" $(PYTEST_ARGS)

$(ORACLE_STAMP): $(STAMP)
	$(PYTHON) -m venv $(ORACLE_VENV)
	$(ORACLE_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(ORACLE_VENV)/bin/python -m pip install --quiet commonroad-io==2026.1
	$(ORACLE_VENV)/bin/python -m pip install --quiet --no-deps --upgrade protobuf==$$($(BIN)/python -c 'import google.protobuf as p; print(p.__version__)')
	$(ORACLE_VENV)/bin/python -c 'import pathlib, sys, sysconfig; pathlib.Path(sysconfig.get_paths()["purelib"], "zz_project_venv.pth").write_text(f"import site; site.addsitedir({sys.argv[1]!r})\n")' "$$($(BIN)/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
	@touch $(ORACLE_STAMP)

oracle-commonroad: $(ORACLE_STAMP)
	WORKBENCH_ORACLE_ENV=commonroad PROTOCOL_BUFFERS_PYTHON_IMPLEMENTATION=python \
		$(ORACLE_VENV)/bin/python -m pytest -q -p no:cacheprovider tests/loaders/test_oracle_commonroad.py

$(CRIME_STAMP): $(STAMP)
	$(PYTHON) -m venv $(CRIME_VENV)
	$(CRIME_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(CRIME_VENV)/bin/python -m pip install --quiet commonroad-crime==0.4.5
	$(CRIME_VENV)/bin/python -m pip install --quiet --no-deps --upgrade protobuf==$$($(BIN)/python -c 'import google.protobuf as p; print(p.__version__)')
	$(CRIME_VENV)/bin/python -c 'import pathlib, sys, sysconfig; pathlib.Path(sysconfig.get_paths()["purelib"], "zz_project_venv.pth").write_text(f"import site; site.addsitedir({sys.argv[1]!r})\n")' "$$($(BIN)/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
	@touch $(CRIME_STAMP)

oracle-crime: $(CRIME_STAMP) $(COMPILED)
	WORKBENCH_ORACLE_ENV=crime PROTOCOL_BUFFERS_PYTHON_IMPLEMENTATION=python \
		$(CRIME_VENV)/bin/python -m pytest -q -p no:cacheprovider tests/workbench/triage/test_crime_measure.py

# Issue 27's acceptance on the 11 NGSIM scenarios (tests/workbench/triage), whole in the side
# venv (the real-conflict clause needs commonroad-crime). Not part of `test` yet.
acceptance: $(CRIME_STAMP) $(COMPILED)
	WORKBENCH_ORACLE_ENV=crime PROTOCOL_BUFFERS_PYTHON_IMPLEMENTATION=python \
		$(CRIME_VENV)/bin/python -m pytest -q -p no:cacheprovider -m acceptance tests/workbench/triage

$(MAP_ORACLE_STAMP):
	$(PYTHON) -m venv $(MAP_ORACLE_VENV)
	$(MAP_ORACLE_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(MAP_ORACLE_VENV)/bin/python -m pip install --quiet ad-rss-map-integration==5.0.0
	$(MAP_ORACLE_VENV)/bin/python tools/link_adrss_map_libs.py
	@touch $(MAP_ORACLE_STAMP)

oracle-adrss-map: $(STAMP) $(COMPILED) $(MAP_ORACLE_STAMP)
	RSS_MAP_ORACLE_PYTHON=$(abspath $(MAP_ORACLE_VENV))/bin/python \
		$(BIN)/python -m pytest -q -p no:cacheprovider tests/rss/scene/test_crosscheck_adrss_map.py \
		tests/rss/scene/test_crosscheck_drives.py tests/rss/scene/test_scene_reference.py

$(FUZZ_STAMP): $(STAMP)
	$(PYTHON) -m venv $(FUZZ_VENV)
	$(FUZZ_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(FUZZ_VENV)/bin/python -m pip install --quiet atheris==3.0.0
	$(FUZZ_VENV)/bin/python -c 'import pathlib, sys, sysconfig; pathlib.Path(sysconfig.get_paths()["purelib"], "zz_project_venv.pth").write_text(f"import site; site.addsitedir({sys.argv[1]!r})\n")' "$$($(BIN)/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
	@touch $(FUZZ_STAMP)

# Coverage-guided fuzzing of every loader entry point, FUZZ_SECONDS each (docs/fuzzing.md);
# resumes from $(OUT)/fuzz/<target>/corpus. Findings: exit 1, minimized inputs listed.
fuzz: $(FUZZ_STAMP)
	$(FUZZ_VENV)/bin/python -m tests.fuzz.run --seconds $(FUZZ_SECONDS) --out $(OUT)/fuzz $(FUZZ_TARGETS)

test: lint typecheck layers pytest oracle-commonroad oracle-crime acceptance oracle-adrss-map

# `make bench BENCH="bench_rss bench_unstructured"` re-measures those sections only (bench.run --update).
bench: $(STAMP) $(COMPILED) $(MAP_ORACLE_STAMP)
	$(BIN)/python -m bench.run --out docs/benchmarks.md $(if $(BENCH),--update $(BENCH))

samples: $(STAMP) $(COMPILED)
	$(BIN)/workbench samples sample_logs

# The one update switch of the golden per-frame records (tests/goldens, docs/testing.md):
# rewrites the files that changed and reports per file which frames and keys moved.
# Refused under CI=true. GOLDEN_ARGS="--variant adrss-5.0 --engine rss --log parking_lot.mcap"
# narrows it.
goldens: $(STAMP) $(COMPILED)
	$(BIN)/python -m tests.goldens.update $(GOLDEN_ARGS)

# Re-render the README screenshot from the demo recording (needs mesa-vulkan-drivers).
screenshot: demo
	bash tools/screenshot.sh $(OUT)/demo/highway_cut_in.rrd docs/replay_reach_highway_cut_in.png 120

clean:
	rm -rf $(VENV) $(ORACLE_VENV) $(CRIME_VENV) $(MAP_ORACLE_VENV) $(FUZZ_VENV) $(OUT) .mypy_cache .ruff_cache .pytest_cache build

# Issue 30's scale facts: the fleet section of docs/benchmarks.md (FLEET_DRIVES=200 by default).
FLEET_DRIVES ?= 200
bench-fleet: $(STAMP) $(COMPILED)
	$(BIN)/python -m bench.bench_fleet --drives $(FLEET_DRIVES) --out docs/benchmarks.md
