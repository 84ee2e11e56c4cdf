#!/usr/bin/env bash
# Renders a report page in headless Chromium (Debian's chromium, installed when missing) to a PNG, to
# look at it as a reader would (1400 px wide, as the Chromium test reads it):
#   scripts/screenshot-report.sh REPORT/index.html OUT.png [HEIGHT_PX]
set -euo pipefail
page=$(realpath "$1"); png=$2; height=${3:-3000}
if ! command -v chromium >/dev/null; then
  sudo=(); [[ $(id -u) -ne 0 ]] && sudo=(sudo)
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends chromium
fi
profile=$(mktemp -d)
chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking \
  --disable-component-update --disable-sync --user-data-dir="$profile" --window-size=1400,"$height" \
  --screenshot="$png" "file://$page" 2>/dev/null
rm -rf "$profile"
echo "screenshot: $png"
