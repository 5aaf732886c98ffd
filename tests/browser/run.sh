#!/usr/bin/env bash
# The browser test of the HTML report: `gltfmat report` over ../shared/real-world/gltf2, opened
# in Debian's Chromium by playwright-core; fails on a console error or a broken image and
# leaves a screenshot in target/. In CI, Chromium is installed when missing; elsewhere the
# test is skipped, loudly, when it is.
#   tests/browser/run.sh [GLTFMAT]
set -euo pipefail
cd "$(dirname "$0")/../.."
gltfmat=${1:-target/debug/gltfmat}
shared=${GLTFMAT_SHARED:-../shared}
if ! command -v chromium >/dev/null; then
  if [ -n "${CI:-}" ]; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
  else
    echo "SKIPPED LOUDLY: the browser test needs Debian's chromium (apt-get install chromium)" >&2
    exit 0
  fi
fi
if [ ! -d "$shared/real-world/gltf2" ]; then
  echo "$shared/real-world/gltf2 is missing: the browser test needs ../shared beside the checkout" >&2
  [ -n "${CI:-}" ] && exit 1
  echo "SKIPPED LOUDLY" >&2
  exit 0
fi
(cd tests/browser && npm ci --silent --no-audit --no-fund)
"$gltfmat" report "$shared/real-world/gltf2" -o target/browser-report.html --force
node tests/browser/report.mjs target/browser-report.html target/browser-report.png
