# arcspline: HTTP service that approximates cubic Bezier spirals by arc splines.
#
#   docker build -t arcspline .                       # or: podman build -t arcspline .
#   docker run --rm -p 8000:8000 arcspline
#
# Behind a TLS-intercepting proxy, hand the proxy's CA bundle to the build as a secret:
#   docker build --secret id=ca,src=/etc/ssl/certs/ca-certificates.crt -t arcspline .
# Without the secret the build trusts the usual public CAs (pip: certifi; apt: plain http).
# The secret is only mounted into the RUN steps that download; it never lands in a layer.
#
# Local podman specifics (base image made with debootstrap, runc, host network) live in
# scripts/image.sh, not here: `make image`, `make image-test`.

ARG DEBIAN_IMAGE=debian:bookworm-slim

# ---------------------------------------------------------------------------------------------
# base: Debian's python3 (3.11 on bookworm), nothing else.
FROM ${DEBIAN_IMAGE} AS base
ENV LANG=C.UTF-8 \
    PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1
RUN --mount=type=secret,id=ca \
    set -eu; \
    export DEBIAN_FRONTEND=noninteractive; \
    if [ -s /run/secrets/ca ]; then set -- -o Acquire::https::CAInfo=/run/secrets/ca; fi; \
    apt-get "$@" update; \
    apt-get "$@" install -y --no-install-recommends python3; \
    apt-get clean; \
    rm -rf /var/lib/apt/lists/* /var/cache/apt/*; \
    python3 --version

# ---------------------------------------------------------------------------------------------
# deps: a virtual environment with the pinned runtime dependencies (requirements/runtime.lock).
# Its layer only changes with the lock file, so a code change ships a small layer, not numpy.
FROM base AS deps
RUN --mount=type=secret,id=ca \
    set -eu; \
    export DEBIAN_FRONTEND=noninteractive; \
    if [ -s /run/secrets/ca ]; then set -- -o Acquire::https::CAInfo=/run/secrets/ca; fi; \
    apt-get "$@" update; \
    apt-get "$@" install -y --no-install-recommends python3-venv; \
    rm -rf /var/lib/apt/lists/*; \
    python3 -m venv /opt/venv
ENV PATH=/opt/venv/bin:$PATH \
    PIP_NO_CACHE_DIR=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    PIP_DEFAULT_TIMEOUT=120 \
    PIP_PROGRESS_BAR=off
COPY requirements/runtime.lock /tmp/runtime.lock
RUN --mount=type=secret,id=ca \
    set -eu; \
    if [ -s /run/secrets/ca ]; then \
        export PIP_CERT=/run/secrets/ca REQUESTS_CA_BUNDLE=/run/secrets/ca SSL_CERT_FILE=/run/secrets/ca; \
    fi; \
    pip install --only-binary=:all: -r /tmp/runtime.lock; \
    rm /tmp/runtime.lock; \
    pip uninstall -y -q pip; \
    python -m compileall -q /opt/venv; \
    site="$(python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"; \
    echo /opt/app >"$site/arcspline-app.pth"

# ---------------------------------------------------------------------------------------------
# builder: the project itself, its geometry kernels compiled (Cython, C++) with the pinned
# build requirements (requirements/build.lock), into /opt/app, which the venv's
# arcspline-app.pth puts on sys.path. The compiler stays in this stage.
FROM deps AS builder
RUN --mount=type=secret,id=ca \
    set -eu; \
    export DEBIAN_FRONTEND=noninteractive; \
    if [ -s /run/secrets/ca ]; then set -- -o Acquire::https::CAInfo=/run/secrets/ca; fi; \
    apt-get "$@" update; \
    apt-get "$@" install -y --no-install-recommends g++ python3-dev; \
    rm -rf /var/lib/apt/lists/*
WORKDIR /src
COPY requirements/build.lock requirements/build.lock
RUN --mount=type=secret,id=ca \
    set -eu; \
    if [ -s /run/secrets/ca ]; then \
        export PIP_CERT=/run/secrets/ca REQUESTS_CA_BUNDLE=/run/secrets/ca SSL_CERT_FILE=/run/secrets/ca; \
    fi; \
    python3 -m venv /opt/build; \
    /opt/build/bin/pip install --only-binary=:all: -r requirements/build.lock
COPY pyproject.toml setup.py README.md* ./
COPY service ./service
RUN --mount=type=secret,id=ca \
    set -eu; \
    if [ -s /run/secrets/ca ]; then \
        export PIP_CERT=/run/secrets/ca REQUESTS_CA_BUNDLE=/run/secrets/ca SSL_CERT_FILE=/run/secrets/ca; \
    fi; \
    /opt/build/bin/pip install --no-deps --no-build-isolation --target /opt/app . ; \
    # The `arcspline` command pip wrote runs the build venv's python: point it at the runtime's.
    sed -i '1s|^#!.*|#!/opt/venv/bin/python|' /opt/app/bin/arcspline; \
    find /opt/app -name '*.so' -exec strip --strip-unneeded {} +; \
    python -m compileall -q /opt/app; \
    cd / && python -c "import arcspline.__main__, arcspline.api.app, numpy, fastapi, uvicorn"; \
    /opt/app/bin/arcspline --version

# ---------------------------------------------------------------------------------------------
# runtime: python3 + the venv, unprivileged, read-only-root friendly.
FROM base AS runtime
RUN set -eu; \
    groupadd --gid 10001 arcspline; \
    useradd --uid 10001 --gid arcspline --no-create-home --no-log-init \
        --home-dir /nonexistent --shell /usr/sbin/nologin arcspline
# The venv (dependencies, no pip), then the project: two layers, the big one cached.
COPY --from=deps /opt/venv /opt/venv
COPY --from=builder /opt/app /opt/app
# PYTHONSAFEPATH: `python -m arcspline` imports the installed package, never the working dir.
# PATH: the venv's python (its .pth adds /opt/app), and the `arcspline` command.
# XDG_CACHE_HOME: ezdxf keeps its font cache there (HOME is /nonexistent; /tmp is the one
# writable place under a read-only root), else it warns on every start and scans again.
ENV PATH=/opt/venv/bin:/opt/app/bin:$PATH \
    PYTHONSAFEPATH=1 \
    XDG_CACHE_HOME=/tmp/.cache
WORKDIR /
# Numeric user, so Kubernetes' runAsNonRoot can verify it without reading /etc/passwd.
USER 10001:10001
EXPOSE 8000
STOPSIGNAL SIGTERM
# No curl in the image: probe with the standard library. The port follows ARCSPLINE_PORT when
# the container is started on another port (the command line sets it, see CMD).
HEALTHCHECK --interval=30s --timeout=5s --start-period=20s --retries=3 \
    CMD ["python", "-c", "import os, urllib.request; urllib.request.urlopen('http://127.0.0.1:%s/healthz' % os.environ.get('ARCSPLINE_PORT', '8000'), timeout=4)"]
# One server process per container; the geometry process pool lives inside it.
CMD ["python", "-m", "arcspline", "--host", "0.0.0.0", "--port", "8000"]
