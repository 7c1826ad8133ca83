#!/usr/bin/env bash
# Checks the HTTP contract openapi/openapi.json with the tools pinned in contract/ (installed
# by `npm ci --prefix contract`, which `make contract` runs when package-lock.json changes):
#
#   1. `redocly lint` with contract/redocly.yaml (recommended-strict: every rule an error): any problem fails;
#   2. openapi-typescript generates the TypeScript types into a temporary directory and
#      `tsc --noEmit --strict` checks them together with contract/check.ts, which builds every
#      request with its required fields alone and reads every response.
#
#   scripts/contract.sh [OPENAPI_JSON]      (default openapi/openapi.json)
#
# Nothing generated is kept. No network: telemetry and update checks are off.
set -euo pipefail

repo="$(cd "$(dirname "$0")/.." && pwd)"
cd "$repo"
spec="${1:-openapi/openapi.json}"
bin="$repo/contract/node_modules/.bin"

for tool in redocly openapi-typescript tsc; do
    if [[ ! -x "$bin/$tool" ]]; then
        echo "contract: $bin/$tool is missing; run: npm ci --prefix contract" >&2
        exit 1
    fi
done

# Redocly CLI: no usage data, no update or announcement notices (they fetch from the network).
export REDOCLY_TELEMETRY=off
export REDOCLY_SUPPRESS_UPDATE_NOTICE=true
export REDOCLY_SUPPRESS_NOTIFICATIONS=true

scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT

step() {
    local name="$1" start="$EPOCHREALTIME"
    shift
    echo "contract: $name" >&2
    "$@"
    echo "contract: $name: ok ($(awk "BEGIN { printf \"%.1f\", $EPOCHREALTIME - $start }") s)" >&2
}

lint() {
    "$bin/redocly" lint --config contract/redocly.yaml --format stylish "$spec"
}

types() {
    # --default-non-nullable false: by default openapi-typescript 7 makes every property
    # with a `default` non-optional, which is right for responses but would mark defaulted
    # request fields required; the contract's own `required` lists are what is checked.
    # Run from the repository root so that it finds no redocly.yaml of its own.
    "$bin/openapi-typescript" "$spec" --output "$scratch/openapi.d.ts" \
        --default-non-nullable false >/dev/null
}

typecheck() {
    cp contract/check.ts "$scratch/check.ts"
    # Just these two files: no ambient @types from wherever the temporary directory is.
    cat >"$scratch/tsconfig.json" <<'JSON'
{
  "compilerOptions": {
    "target": "es2022",
    "module": "esnext",
    "moduleResolution": "bundler",
    "types": [],
    "exactOptionalPropertyTypes": true
  },
  "files": ["check.ts", "openapi.d.ts"]
}
JSON
    # Errors name contract/check.ts (the copy's lines are the same).
    "$bin/tsc" --project "$scratch" --noEmit --strict | sed "s|^.*/check\.ts(|contract/check.ts(|"
}

step "redocly lint $spec" lint
step "openapi-typescript $spec" types
step "tsc --noEmit --strict contract/check.ts" typecheck
