#!/usr/bin/env bash
# Fetch LinuxCNC's stand-alone G-code interpreter `rs274` (Debian's linuxcnc-uspace, plus
# the Boost.Python library it links) and unpack it into a cache, without installing
# anything: the G-code tests run every program they generate through it.
#
#   scripts/fetch-rs274.sh        prints the directory to use as ROOT:
#       LD_LIBRARY_PATH=ROOT/usr/lib:ROOT/usr/lib/x86_64-linux-gnu ROOT/usr/bin/rs274 ...
#
# The cache is $RS274_CACHE_DIR, default .cache/rs274 in the repository (git-ignored). A
# second run finds it complete and returns at once; concurrent runs (pytest-xdist workers)
# serialise on a lock file. Otherwise exits with a message saying what is missing: status 2
# when this machine cannot fetch it (not Debian or Ubuntu, no such package in its sources, no
# network or no root for `apt-get update`): the tests then skip, except in CI (CI=true); and
# status 1 when what was fetched is broken or the cache cannot be written.
set -euo pipefail

repo="$(cd "$(dirname "$0")/.." && pwd)"
cache="${RS274_CACHE_DIR:-$repo/.cache/rs274}"
root="$cache/root"
stamp="$root/.complete"

die() {
    echo "fetch-rs274: $*" >&2
    exit 1
}

unavailable() {
    echo "fetch-rs274: $*" >&2
    exit 2
}

[[ "$(uname -s)" == Linux ]] || unavailable "rs274 is fetched as Debian packages: Linux only"
command -v flock >/dev/null || unavailable "needs flock (util-linux)"
mkdir -p "$cache" || die "cannot create the cache directory $cache"
exec 9>"$cache/.lock"
flock 9 || die "cannot lock $cache/.lock"

libpath() {
    local dirs=("$1/usr/lib" "$1/usr/lib/x86_64-linux-gnu" "$1/usr/lib/$(uname -m)-linux-gnu")
    local IFS=:
    echo "${dirs[*]}"
}

# The interpreter prints its canonical commands and exits 0 on a valid program.
smoke_test() {
    local dir="$1" scratch
    scratch="$(mktemp -d)"
    printf 'G17 G21 G90 G91.1 G94 F100\nG0 X0 Y0\nG2 X10 Y0 I5 J0\nM2\n' >"$scratch/ok.ngc"
    printf 'T1 P1 D0.1 Z0\n' >"$scratch/tool.tbl"
    if HOME="$scratch" LD_LIBRARY_PATH="$(libpath "$dir")" \
        "$dir/usr/bin/rs274" -t "$scratch/tool.tbl" -g "$scratch/ok.ngc" \
        >"$scratch/out" 2>"$scratch/err" && grep -q 'ARC_FEED' "$scratch/out"; then
        rm -rf "$scratch"
        return 0
    fi
    cat "$scratch/err" >&2
    rm -rf "$scratch"
    return 1
}

if [[ -f "$stamp" ]]; then
    echo "$root"
    exit 0
fi

command -v apt-get >/dev/null && command -v dpkg >/dev/null ||
    unavailable "needs apt-get and dpkg (a Debian or Ubuntu machine) to fetch linuxcnc-uspace"

if ! apt-cache show linuxcnc-uspace >/dev/null 2>&1; then
    echo "fetch-rs274: no package list knows linuxcnc-uspace; running apt-get update" >&2
    apt-get update -qq >&2 || unavailable "apt-get update failed (run it as root, or fetch as root once)"
    apt-cache show linuxcnc-uspace >/dev/null 2>&1 ||
        unavailable "linuxcnc-uspace is not in this machine's package sources (Debian 12 has it)"
fi

# The Boost.Python library the interpreter links (libboost-python1.74.0 on Debian 12).
boost="$(apt-cache depends linuxcnc-uspace | sed -n 's/^ *Depends: \(libboost-python[0-9.]*\)$/\1/p' | head -n1)"
[[ -n "$boost" ]] || unavailable "cannot tell which libboost-python linuxcnc-uspace needs"

work="$(mktemp -d "$cache/fetch.XXXXXX")"
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get download -q -o APT::Sandbox::User=root linuxcnc-uspace "$boost" >&2) ||
    unavailable "apt-get download linuxcnc-uspace $boost failed (no network?)"

# Shared libraries the interpreter needs that a minimal machine may lack: fetch those too.
declare -A provider=([libpython3.11.so.1.0]=libpython3.11 [libtirpc.so.3]=libtirpc3)
mkdir "$work/root"
for deb in "$work"/*.deb; do dpkg -x "$deb" "$work/root"; done
missing="$(LD_LIBRARY_PATH="$(libpath "$work/root")" ldd "$work/root/usr/bin/rs274" |
    awk '/not found/ {print $1}')"
for lib in $missing; do
    pkg="${provider[$lib]:-}"
    [[ -n "$pkg" ]] || unavailable "rs274 needs $lib, which no known package provides"
    (cd "$work" && apt-get download -q -o APT::Sandbox::User=root "$pkg" >&2) ||
        unavailable "apt-get download $pkg failed (no network?)"
    dpkg -x "$work/$pkg"_*.deb "$work/root"
done

smoke_test "$work/root" || die "the unpacked rs274 does not run (see its output above)"
touch "$work/root/.complete"
rm -rf "$root"
mv "$work/root" "$root"
echo "$root"
