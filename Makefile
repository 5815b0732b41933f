# The two commands a newcomer runs (see README.md):
#   make run    set everything up, then parse/lint/render/verify the lab shaders
#   make test   set everything up, then run the test suite
SHELL := /bin/bash
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: run test check setup system-deps clean

# Debian packages: glslang-tools is the reference compiler the tests compare
# against; the EGL/Mesa packages give moderngl a headless llvmpipe context; chromium is the
# browser of the WebGL backend (Playwright drives it; `playwright install` is never run).
DEBS := glslang-tools libegl1 libegl-mesa0 libgl1-mesa-dri chromium
system-deps:
	@missing=""; for p in $(DEBS); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && $$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	fi

$(STAMP): pyproject.toml
	python3 -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -e '.[test,webgl,jit]'
	touch $(STAMP)

setup: system-deps $(STAMP)

# The main job: check the lab and the corpus, lint the lab as the course grades it, render
# the gallery on the CPU, verify every part against OpenGL at several times and against WebGL
# (Shadertoy's browser), and write the HTML report of the lab (build/report.html).
run: setup
	$(VENV)/bin/glslcheck check lab_shaders tests/corpus
	$(VENV)/bin/glslcheck check lab_shaders --webgl
	$(VENV)/bin/glslcheck lint lab_shaders
	GLSLCHECK=$(VENV)/bin/glslcheck tools/update_gallery.sh
	$(VENV)/bin/glslcheck verify lab_shaders/*/ --size 320x180 --times 0,1.7,5.3
	$(VENV)/bin/glslcheck verify lab_shaders/*/ --size 320x180 --times 0,1.7 --against webgl
	mkdir -p build && $(VENV)/bin/glslcheck report lab_shaders -o build/report.html --time 1.7

test: setup
	$(PY) -m pytest -q

# The project's own checks: ruff's linter and formatter, and mypy's type check of the package
# (configuration of each in pyproject.toml).
LINTED := glslcheck tests tools benchmarks
check: setup
	$(VENV)/bin/ruff check $(LINTED)
	$(VENV)/bin/ruff format --check $(LINTED)
	$(VENV)/bin/mypy

clean:
	rm -rf $(VENV) build dist *.egg-info
