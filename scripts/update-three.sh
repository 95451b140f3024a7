#!/usr/bin/env bash
# Refreshes the vendored three.js of the page (`meshvol serve`, `check --html`) from
# Debian's libjs-three: the minified library, the orbit controls and the licence.
# Run as root (it installs the package); commit what changes.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v apt-get >/dev/null || { echo "update-three.sh: needs Debian's apt-get" >&2; exit 1; }
dpkg -s libjs-three >/dev/null 2>&1 || { apt-get update -qq && apt-get install -y -qq libjs-three; }
src=/usr/share/javascript/three
dest=crates/meshvol-serve/src/page/vendor
cp "$src/three.min.js" "$dest/three.min.js"
cp "$src/examples/js/controls/OrbitControls.js" "$dest/OrbitControls.js"
cp /usr/share/doc/libjs-three/copyright "$dest/LICENSE-three.txt"
version=$(dpkg-query -W -f '${Version}' libjs-three)
revision=$(grep -o 'REVISION="[0-9a-z]*"' "$dest/three.min.js" | head -1)
echo "libjs-three $version ($revision)" > "$dest/VERSION"
# The page inlines these in a <script> element (check --html): they must not close it.
if grep -q '</script' "$dest/three.min.js" "$dest/OrbitControls.js"; then
    echo "update-three.sh: a vendored file contains '</script': the inlined page would break" >&2
    exit 1
fi
echo "vendored three.js: $(cat "$dest/VERSION")"
