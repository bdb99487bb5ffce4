#!/usr/bin/env bash
# End-to-end test of `nurbs-box serve` in headless Chromium: installs what is missing
# (Debian's chromium, playwright-core via npm ci), builds the binary, runs serve.test.mjs.
# Prints "N passed, M failed"; exit status 0 when all passed.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
if [ ! -x /usr/bin/chromium ]; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
fi
if ! command -v node >/dev/null 2>&1; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq nodejs npm >/dev/null
fi
(cd "$here" && { [ -d node_modules/playwright-core ] || npm ci --no-audit --no-fund >/dev/null; })
target="${CARGO_TARGET_DIR:-$root/target}"
(cd "$root" && cargo build --release --bin nurbs-box)
cd "$here"
NURBS_BOX_BIN="$target/release/nurbs-box" node serve.test.mjs
