#!/usr/bin/env bash
# Times every ctest test, one at a time, and writes the table (test, labels, seconds, date)
# into docs/development.md between the "test timings" markers; the times are ctest's own
# (its JUnit output). Run from anywhere, after a build:
#   tools/test_timings.sh [build dir, default build/] [more ctest arguments, e.g. -L quick]
# With TIMINGS_STDOUT=1 it prints the table instead of editing the doc.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
shift || true
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
ctest --test-dir "$build" --show-only=json-v1 "$@" > "$scratch/tests.json"
start=$(date +%s)
# -j1: each test alone, so a time is that test's; failures still give a time.
ctest --test-dir "$build" -j1 --output-junit "$scratch/junit.xml" "$@" > "$scratch/ctest.log" 2>&1 || true
wall=$(( $(date +%s) - start ))
TIMINGS_WALL=$wall python3 - "$scratch/tests.json" "$scratch/junit.xml" "$root/docs/development.md" <<'PY'
import datetime, json, os, sys, xml.etree.ElementTree as ET
tests_json, junit, doc = sys.argv[1:4]
labels = {}
for t in json.load(open(tests_json))["tests"]:
    for p in t.get("properties", []):
        if p["name"] == "LABELS":
            labels[t["name"]] = ", ".join(p["value"])
rows = []
for case in ET.parse(junit).getroot().iter("testcase"):
    status = case.get("status")
    note = {"run": "", "fail": " (failed)", "notrun": " (skipped)"}.get(status, " (" + str(status) + ")")
    rows.append((float(case.get("time")), case.get("name"), note))
rows.sort(key=lambda r: (-r[0], r[1]))
today = datetime.date.today().isoformat()
total = sum(r[0] for r in rows)
out = [f"Measured {today} with `tools/test_timings.sh` (`ctest -j1`, Release, the 2-core machine shared "
       f"with other builds): {len(rows)} tests, {total:.0f} s of test time, {os.environ['TIMINGS_WALL']} s wall.",
       "", "| test | labels | seconds |", "|---|---|---:|"]
for t, name, note in rows:
    out.append(f"| {name.replace('|', '&#124;')}{note} | {labels.get(name, '')} | {t:.2f} |")
table = "\n".join(out) + "\n"
if os.environ.get("TIMINGS_STDOUT"):
    sys.stdout.write(table)
    sys.exit(0)
begin, end = "<!-- test timings: begin (tools/test_timings.sh writes this) -->\n", "<!-- test timings: end -->\n"
text = open(doc).read()
if begin not in text or end not in text:
    sys.exit(f"{doc} has no test timings markers")
head, rest = text.split(begin, 1)
open(doc, "w").write(head + begin + table + end + rest.split(end, 1)[1])
print(f"{doc}: {len(rows)} tests, {total:.0f} s")
PY
