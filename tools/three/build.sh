#!/bin/sh
# Rebuild src/weavecut/kitpage/static/three.min.js (the vendored viewer) from the npm registry:
# three.js and esbuild at the versions pinned in package.json (package-lock.json holds their
# hashes), bundled and minified to one classic script (IIFE) with the parts entry.js names.
# Same versions, same bytes. Run from anywhere: sh tools/three/build.sh
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out="$here/../../src/weavecut/kitpage/static"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$here/package.json" "$here/package-lock.json" "$here/entry.js" "$work/"
cd "$work"
npm ci --no-audit --no-fund --ignore-scripts > /dev/null
version=$(node -p "require('./node_modules/three/package.json').version")
node_modules/.bin/esbuild entry.js --bundle --minify --format=iife --global-name=WeaveCutThree \
  --legal-comments=none --target=es2020 --banner:js="/* three.js r$(echo "$version" | cut -d. -f2) (MIT licence: three.LICENSE), the parts of tools/three/entry.js, bundled by esbuild */" \
  --outfile="$out/three.min.js" --log-level=warning
cp node_modules/three/LICENSE "$out/three.LICENSE"
echo "wrote $out/three.min.js ($(wc -c < "$out/three.min.js") bytes), three $version"
