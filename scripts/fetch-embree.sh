#!/usr/bin/env bash
# Fetches Embree 4.4.1 + oneTBB (the shared libraries from the PyPI wheel pyembree2==1.0.1,
# pinned by sha256) into a project-local, git-ignored directory:
#
#   .deps/embree/lib/libembree4.so.4   (RUNPATH $ORIGIN, finds the libtbb.so.12 beside it)
#   .deps/embree/lib/libtbb.so.12
#   .deps/embree/SHA256SUMS            (checksums of the extracted files)
#
# Usage: scripts/fetch-embree.sh [DEST]      (DEST defaults to <repo>/.deps/embree)
#
# Idempotent: if DEST already holds the libraries and they match SHA256SUMS, nothing is
# downloaded. Any failure stops the script with a message saying what to do.
# To use another Embree 4 (>= 4.3) install instead, skip this script and set EMBREE_DIR to a
# directory containing lib/libembree4.so.4 when building scratchwave-embree.
set -euo pipefail

PACKAGE=pyembree2
VERSION=1.0.1
WHEEL_SHA256=bb8efdd7c92f85a20ec7ee787b06bbd716b6b4255e59cca6b2e6a40bd05ba121
LIBS=(libembree4.so.4 libtbb.so.12)

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
DEST=${1:-$ROOT/.deps/embree}

die() {
    echo "fetch-embree: error: $*" >&2
    exit 1
}

if [[ -f $DEST/SHA256SUMS ]] && (cd "$DEST" && sha256sum --quiet --check SHA256SUMS >/dev/null 2>&1); then
    echo "fetch-embree: Embree already present in $DEST (checksums ok)"
    exit 0
fi

command -v python3 >/dev/null || die "python3 is required (it runs pip to download the wheel)"
python3 -m pip --version >/dev/null 2>&1 ||
    die "python3 has no pip; install it (Debian: apt-get install python3-pip)"
command -v sha256sum >/dev/null || die "sha256sum (coreutils) is required"

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

echo "fetch-embree: downloading $PACKAGE==$VERSION from PyPI"
# Pin the wheel's tags so the result does not depend on the local Python version.
python3 -m pip download --quiet --no-deps --only-binary=:all: \
    --python-version 3.11 --platform manylinux_2_28_x86_64 \
    --dest "$WORK" "$PACKAGE==$VERSION" ||
    die "pip could not download $PACKAGE==$VERSION (is PyPI reachable?)"

shopt -s nullglob
wheels=("$WORK"/"$PACKAGE"-"$VERSION"-*.whl)
((${#wheels[@]} == 1)) || die "expected one $PACKAGE wheel, pip produced: $(ls "$WORK")"
WHEEL=${wheels[0]}

actual=$(sha256sum "$WHEEL" | cut -d' ' -f1)
[[ $actual == "$WHEEL_SHA256" ]] ||
    die "checksum mismatch for $(basename "$WHEEL"): expected $WHEEL_SHA256, got $actual. Refusing to install it."

mkdir -p "$WORK/lib"
python3 - "$WHEEL" "$WORK/lib" "${LIBS[@]}" <<'PY' || die "could not extract the libraries from the wheel"
import calendar, os, sys, zipfile

wheel, out, wanted = sys.argv[1], sys.argv[2], sys.argv[3:]
with zipfile.ZipFile(wheel) as z:
    by_name = {os.path.basename(n): n for n in z.namelist()}
    for lib in wanted:
        if lib not in by_name:
            sys.exit(f"{lib} is not in the wheel")
        path = os.path.join(out, lib)
        with z.open(by_name[lib]) as src, open(path, "wb") as dst:
            dst.write(src.read())
        # the wheel's own timestamp, not the time of extraction: the same pinned file gets
        # the same mtime in every clone, so cargo does not rebuild what links it
        # (backend-embree/build.rs watches the library)
        t = calendar.timegm(z.getinfo(by_name[lib]).date_time + (0, 0, 0))
        os.utime(path, (t, t))
PY

# Install atomically: build the final tree beside DEST, then swap it in.
mkdir -p "$(dirname "$DEST")"
STAGE=$(mktemp -d "$(dirname "$DEST")/.embree-stage.XXXXXX")
chmod 755 "$STAGE"
mkdir -p "$STAGE/lib"
for lib in "${LIBS[@]}"; do
    install -p -m 0755 "$WORK/lib/$lib" "$STAGE/lib/$lib"
done
ln -s libembree4.so.4 "$STAGE/lib/libembree4.so"
cat >"$STAGE/SOURCE" <<INFO
Embree 4.4.1 and oneTBB shared libraries extracted from the PyPI wheel
$(basename "$WHEEL") (sha256 $WHEEL_SHA256)
by scripts/fetch-embree.sh. Embree: Apache-2.0; oneTBB: Apache-2.0.
INFO
(cd "$STAGE" && sha256sum lib/libembree4.so.4 lib/libtbb.so.12 >SHA256SUMS)
rm -rf "$DEST"
mv "$STAGE" "$DEST"
echo "fetch-embree: installed Embree 4.4.1 into $DEST"
