# Fairlines — the two commands of the README, plus bench. Every target does its own set-up
# on a fresh machine: system packages with apt-get, Python packages with pip into .venv.

PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
PIP := $(PY) -m pip
JOBS ?= 2
OUT ?= out
SYS_PACKAGES := libeigen3-dev libgtest-dev
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: setup sysdeps pydeps build cpp-test py-test test demo bench clean blender-deps addon blender-test blender-demo blender-bench blender-screenshot

setup: sysdeps pydeps

sysdeps:
	@dpkg -s $(SYS_PACKAGES) >/dev/null 2>&1 || { \
	  echo "installing system packages: $(SYS_PACKAGES)"; \
	  $(SUDO) apt-get update -qq && $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(SYS_PACKAGES); }

$(VENV)/.deps-stamp: requirements-dev.txt
	$(PYTHON) -m venv $(VENV)
	$(PIP) install -q --upgrade pip
	$(PIP) install -q -r requirements-dev.txt
	touch $@

pydeps: $(VENV)/.deps-stamp

# The Python package with its compiled engine (incremental: build/py-* is kept).
build: setup
	$(PIP) install -q --no-build-isolation --no-deps .

cpp-test: sysdeps pydeps
	$(VENV)/bin/cmake -S . -B build/cpp -G Ninja -DCMAKE_MAKE_PROGRAM=$(abspath $(VENV)/bin/ninja) \
	  -DFAIRLINES_BUILD_TESTS=ON -DFAIRLINES_BUILD_PYTHON=OFF -DCMAKE_BUILD_TYPE=Release
	$(VENV)/bin/cmake --build build/cpp -j $(JOBS)
	cd build/cpp && $(abspath $(VENV)/bin/ctest) --output-on-failure -j $(JOBS)

py-test: build
	$(PY) -m pytest -q tests/python

test: cpp-test py-test blender-test

demo: build
	$(PY) examples/demo.py --out $(OUT)

bench: build
	$(PY) bench/run_all.py

clean:
	rm -rf build $(OUT) dist

# ---- Blender add-on (issue 7) -------------------------------------------------------------
# Two Blenders, both on CPython 3.11: the newest `bpy` module from PyPI (extension install,
# into .venv-bpy) and Debian's `blender` package (3.4, legacy add-on install, system python3
# with python3-numpy). xvfb is for the node-editor screenshot.
BPY_VENV := .venv-bpy
BPY_VERSION ?= 5.0.1
BLENDER_SYS_PACKAGES := blender python3-numpy xvfb

$(BPY_VENV)/.bpy-stamp:
	$(PYTHON) -m venv $(BPY_VENV)
	$(BPY_VENV)/bin/python -m pip install -q bpy==$(BPY_VERSION)
	touch $@

blender-deps: $(BPY_VENV)/.bpy-stamp
	@dpkg -s $(BLENDER_SYS_PACKAGES) >/dev/null 2>&1 || { \
	  echo "installing system packages: $(BLENDER_SYS_PACKAGES)"; \
	  $(SUDO) apt-get update -qq && $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(BLENDER_SYS_PACKAGES); }

# dist/fairlines_blender-<v>-extension.zip (4.2+) and -legacy.zip (3.4 .. 4.1), engine inside.
addon: build
	$(PY) tools/package_addon.py

blender-test: build blender-deps
	$(PY) -m pytest -q -p no:cacheprovider tests/blender

blender-demo: addon blender-deps
	BLENDER_USER_RESOURCES=$(abspath $(OUT))/blender/user $(BPY_VENV)/bin/python examples/blender_demo.py \
	  --zip "$$(ls dist/fairlines_blender-*-extension.zip)" --out $(OUT)/blender

blender-bench: build blender-deps
	$(PY) bench/bench_blender_latency.py

# docs/node_editor.png: Debian's Blender with its interface under Xvfb (throw-away user dirs).
blender-screenshot: addon blender-deps
	rm -rf build/shot
	BLENDER_USER_SCRIPTS=$(abspath build/shot/scripts) BLENDER_USER_CONFIG=$(abspath build/shot/config) \
	  blender -b --factory-startup --python tools/blender_screenshot.py -- --zip none --prefs-only
	BLENDER_USER_SCRIPTS=$(abspath build/shot/scripts) BLENDER_USER_CONFIG=$(abspath build/shot/config) \
	  xvfb-run -a -s "-screen 0 1600x1000x24" blender --python tools/blender_screenshot.py -- \
	  --zip "$$(ls dist/fairlines_blender-*-legacy.zip)" --out docs/node_editor.png
