#!/usr/bin/env bash
# Opens the HTML report of the faulty water plant in headless Chromium and checks what a
# person would see: the page loads without a console error, and the rendered DOM has P2's
# timing diagram with a track per signal of its counterexample. Writes a screenshot.
#
#   tools/browser_check.sh [OUT_DIR]     (default: a temporary folder; needs chromium)
#
# II_PROVE names the binary to run (default: `cargo run --release --quiet --`).
# On Debian: apt-get install chromium. .ci/run installs it and runs this.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-$(mktemp -d)}
mkdir -p "$out"
browser=$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)
if [ -z "$browser" ]; then
  echo "browser_check: no chromium on PATH (apt-get install chromium)" >&2
  exit 2
fi
if [ -n "${II_PROVE:-}" ]; then ii_prove=("$II_PROVE"); else ii_prove=(cargo run --release --quiet --); fi
report="$out/water_faulty.html"
status=0
"${ii_prove[@]}" --format html examples/water_faulty.ld examples/water.ii >"$report" || status=$?
[ "$status" -eq 1 ] || { echo "browser_check: expected exit 1 (P2 refuted), got $status" >&2; exit 1; }
flags=(--headless --disable-gpu --no-sandbox --hide-scrollbars --enable-logging=stderr --v=0)
"$browser" "${flags[@]}" --dump-dom "file://$(realpath "$report")" >"$out/dom.html" 2>"$out/console.log"
"$browser" "${flags[@]}" --window-size=1100,2600 --screenshot="$out/water_faulty.png" \
  "file://$(realpath "$report")" >/dev/null 2>>"$out/console.log"
if grep -E "CONSOLE|Uncaught" "$out/console.log" | grep -qiE "error|uncaught"; then
  echo "browser_check: console errors:" >&2
  grep -E "CONSOLE|Uncaught" "$out/console.log" >&2
  exit 1
fi
# The tracks the browser rendered are the signals of P2's text diagram.
expected=$("${ii_prove[@]}" --format json --only P2 examples/water_faulty.ld examples/water.ii |
  python3 -c 'import json,sys
d=json.load(sys.stdin)["properties"][0]["counterexample"]["diagram"]
for l in d:
    i=next((k for k,c in enumerate(l) if "\u2580"<=c<="\u259f"),None)
    if i and l[:i].strip(): print(l[:i].rstrip())' | sort) || true
rendered=$(python3 -c 'import re,sys,html
dom=open(sys.argv[1],encoding="utf-8").read()
sec=dom[dom.index("id=\"p-P2\""):]
sec=sec[:sec.index("</section>")]
for m in re.findall(r"<g class=\"track\" data-signal=\"([^\"]*)\"",sec): print(html.unescape(m))' "$out/dom.html" | sort)
if [ -z "$rendered" ] || [ "$expected" != "$rendered" ]; then
  echo "browser_check: the rendered tracks differ from P2's counterexample" >&2
  diff <(echo "$expected") <(echo "$rendered") >&2 || true
  exit 1
fi
echo "browser_check: ok ($(echo "$rendered" | wc -l) tracks rendered; screenshot $out/water_faulty.png)"
