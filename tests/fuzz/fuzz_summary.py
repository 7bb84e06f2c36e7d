#!/usr/bin/env python3
"""The table of the last bounded fuzzing runs (fuzz.summary): one row per
harness from the <stats>/<harness>.json files run_fuzzer.py writes, in
Markdown, as tests/fuzz/README.md shows it.  Fails when a harness named on
the command line has no stats (its run did not finish) or found something;
it then prints each finding's digest again, so that the cause survives a CI
log that keeps only its end.

    fuzz_summary.py STATS_DIR HARNESS...
"""
import json
import os
import sys


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    folder, harnesses = sys.argv[1], sys.argv[2:]
    rows, missing = [], []
    for h in harnesses:
        path = os.path.join(folder, h + ".json")
        if not os.path.exists(path):
            missing.append(h)
            continue
        with open(path) as f:
            rows.append(json.load(f))
    print("| harness | executions | exec/s | coverage (edges) | features | corpus (inputs / KiB) | seconds | result |")
    print("|---|---:|---:|---:|---:|---:|---:|---|")
    for r in rows:
        print("| %s | %d | %d | %s | %s | %s / %.0f | %.0f | %s |" % (
            r["harness"], r["executions"], r["exec_per_sec"], r.get("cov", "?"), r.get("ft", "?"),
            r.get("corpus_units", "?"), r.get("corpus_bytes", 0) / 1024, r["seconds"],
            "ok" if r["status"] == 0 else "FINDING (status %d)" % r["status"]))
    total = sum(r["executions"] for r in rows)
    print("\n%d executions in %.0f s of fuzzing over %d harnesses" % (total, sum(r["seconds"] for r in rows), len(rows)))
    failed = 0
    for r in rows:
        if r["status"] != 0:
            failed += 1
            print("\nFINDING in %s (status %d):\n  %s" % (r["harness"], r["status"],
                                                         "\n  ".join(r.get("finding", ["(no digest)"]))))
    if missing:
        print("no finished run for: " + ", ".join(missing))
    return 1 if missing or failed else 0


if __name__ == "__main__":
    sys.exit(main())
