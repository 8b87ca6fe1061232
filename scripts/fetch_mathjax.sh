#!/usr/bin/env bash
# Vendor MathJax 3 (es5 bundle only) from the npm registry so that the built
# site typesets maths offline. Idempotent: does nothing if the requested
# version is already unpacked.
#
#   scripts/fetch_mathjax.sh [DEST]   (default: build/vendor/mathjax)
#
# The site build copies build/vendor/ into _build/html via html_extra_path,
# so the browser loads /mathjax/tex-chtml.js from the site itself.
set -euo pipefail

version="${MATHJAX_VERSION:-3.2.2}"
dest="${1:-build/vendor/mathjax}"
stamp_dir="${MATHJAX_STAMP_DIR:-build}"  # outside $dest/.. : that folder is copied into the site
stamp="${stamp_dir}/.mathjax-${version}.stamp"

if [[ -f "$stamp" && -f "$dest/tex-chtml.js" ]]; then
    exit 0
fi

command -v npm >/dev/null || { echo "fetch_mathjax: npm not found" >&2; exit 1; }

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

echo "fetch_mathjax: npm pack mathjax@${version}"
(cd "$tmp" && npm pack --silent "mathjax@${version}" >/dev/null)
tar -xzf "$tmp"/mathjax-"${version}".tgz -C "$tmp" package/es5 package/LICENSE

rm -rf "$dest"
mkdir -p "$dest"
cp -R "$tmp/package/es5/." "$dest/"
cp "$tmp/package/LICENSE" "$dest/LICENSE"
mkdir -p "$stamp_dir"
rm -f "$stamp_dir"/.mathjax-*.stamp
touch "$stamp"
echo "fetch_mathjax: MathJax ${version} in ${dest}"
