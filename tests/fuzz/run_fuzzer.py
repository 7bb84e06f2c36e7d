#!/usr/bin/env python3
"""Runs one libFuzzer harness for a bounded time (the fuzz.run.<harness>
tests), keeps its whole output in a log, and writes what the run did
(executions, speed, coverage, corpus) to <stats>/<harness>.json for
fuzz_summary.py.

A crash, leak, UB report, timeout (--timeout per input) or out-of-memory
(--rss-limit-mb, or one allocation above --malloc-limit-mb) ends the run with
libFuzzer's non-zero status, which this script passes on after printing the
report and where the input was kept.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

def last_status(log):
    """The last libFuzzer status line: '#N DONE cov: C ft: F corp: U/S ...'."""
    status = {}
    for line in log.splitlines():
        m = re.match(r"#(\d+)\s+\w+\s+cov: (\d+) ft: (\d+) corp: (\d+)/(\d+)(b|Kb|Mb)", line)
        if m:
            scale = {"b": 1, "Kb": 1024, "Mb": 1024 * 1024}[m.group(6)]
            status = {"cov": int(m.group(2)), "ft": int(m.group(3)), "corpus_units": int(m.group(4)),
                      "corpus_bytes": int(m.group(5)) * scale}
    return status


def finding(log):
    """The lines that say what a failed run found, in at most 16 lines: the
    sanitizer's or libFuzzer's ERROR line, the top of the first stack, the
    SUMMARY and where the input was written.  CI keeps only part of a long
    log; this digest is printed first and again by fuzz.summary."""
    lines = log.splitlines()
    keep = []
    start = next((i for i, line in enumerate(lines)
                  if re.search(r"==\d+==\s*ERROR|ERROR: libFuzzer|runtime error:|ALARM: working on the last Unit", line)),
                 None)
    if start is not None:
        keep.append(lines[start])
        frames = [line.strip() for line in lines[start + 1:] if re.match(r"\s*#\d+ 0x", line)]
        keep += frames[:8]
    keep += [line for line in lines if line.startswith("SUMMARY:") or "Test unit written to" in line
             or line.startswith("MS: ")][:4]
    return keep[:16]


def final_stats(log):
    stats = {}
    for m in re.finditer(r"^stat::(\w+):\s+(\d+)", log, re.MULTILINE):
        stats[m.group(1)] = int(m.group(2))
    return stats


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--fuzzer", required=True)
    p.add_argument("--name", required=True)
    p.add_argument("--seconds", type=int, required=True)
    p.add_argument("--max-len", type=int, required=True)
    p.add_argument("--work", required=True, help="folder for the corpus, artifacts, log and stats")
    p.add_argument("--seeds", action="append", default=[], help="read-only seed folders")
    p.add_argument("--dict", action="append", default=[], help="dictionaries (joined into one)")
    p.add_argument("--timeout", type=int, required=True, help="seconds an input may take (longer: a hang)")
    p.add_argument("--rss-limit-mb", type=int, required=True, help="memory the process may hold")
    p.add_argument("--malloc-limit-mb", type=int, required=True, help="largest single allocation")
    p.add_argument("--option", action="append", default=[], help="another libFuzzer option, e.g. -detect_leaks=0")
    args = p.parse_args()

    corpus = os.path.join(args.work, "corpus", args.name)
    artifacts = os.path.join(args.work, "artifacts", args.name)
    stats_dir = os.path.join(args.work, "stats")
    for d in (corpus, artifacts, stats_dir):
        os.makedirs(d, exist_ok=True)
    log_path = os.path.join(args.work, args.name + ".log")
    stats_path = os.path.join(stats_dir, args.name + ".json")
    if os.path.exists(stats_path):
        os.remove(stats_path)

    command = [args.fuzzer, corpus] + [s for s in args.seeds if os.path.isdir(s)]
    command += ["-max_total_time=%d" % args.seconds, "-max_len=%d" % args.max_len,
                "-timeout=%d" % args.timeout, "-malloc_limit_mb=%d" % args.malloc_limit_mb,
                "-rss_limit_mb=%d" % args.rss_limit_mb, "-print_final_stats=1",
                "-artifact_prefix=" + artifacts + "/"] + args.option
    if args.dict:
        joined = os.path.join(args.work, args.name + ".dict")
        with open(joined, "w") as out:
            for d in args.dict:
                with open(d) as f:
                    out.write(f.read())
        command.append("-dict=" + joined)

    # libFuzzer's -detect_leaks=0 only stops the search for leaks per input;
    # LeakSanitizer still checks the whole process at exit unless
    # ASAN_OPTIONS says otherwise (VTK's leaks on refused files, see README).
    env = dict(os.environ)
    if "-detect_leaks=0" in args.option:
        env["ASAN_OPTIONS"] = ":".join(filter(None, [env.get("ASAN_OPTIONS", ""), "detect_leaks=0"]))
    # The harnesses' scratch folders live under TMPDIR and go at exit, but
    # libFuzzer leaves by _Exit on -max_total_time, a timeout or an OOM, so
    # they get a TMPDIR of their own that this script removes.
    scratch = os.path.join(args.work, args.name + ".tmp")
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    env["TMPDIR"] = scratch
    print("running:", " ".join(command), flush=True)
    started = time.monotonic()
    try:
        with open(log_path, "w") as log:
            rc = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=env).returncode
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    seconds = time.monotonic() - started
    with open(log_path, errors="replace") as f:
        text = f.read()

    stats = final_stats(text)
    run = {"harness": args.name, "seconds": round(seconds, 1), "status": rc,
           "executions": stats.get("number_of_executed_units", 0),
           "exec_per_sec": stats.get("average_exec_per_sec", 0),
           "new_units": stats.get("new_units_added", 0),
           "peak_rss_mb": stats.get("peak_rss_mb", 0)}
    run.update(last_status(text))
    if rc != 0:
        run["finding"] = finding(text) or ["libFuzzer exited with %d and printed no report" % rc]
    with open(stats_path, "w") as f:
        json.dump(run, f, indent=1)
    print("%(harness)s: %(executions)d executions in %(seconds).0f s (%(exec_per_sec)d/s)" % run +
          ", coverage %s edges, %s features, corpus %s inputs" % (run.get("cov"), run.get("ft"),
                                                                 run.get("corpus_units")))
    if rc != 0:
        print("\nFINDING (digest):\n  " + "\n  ".join(run["finding"]))
        print("\n--- the end of %s ---" % log_path)
        print("\n".join(text.splitlines()[-80:]))
        kept = sorted(os.listdir(artifacts))
        print("\nFINDING in %s: libFuzzer exited with %d; input(s) kept in %s: %s" %
              (args.name, rc, artifacts, ", ".join(kept) or "none"))
        print("Fix the parser, then copy the input to tests/fuzz/regressions/%s/ (see tests/fuzz/README.md)."
              % args.name)
    return rc


if __name__ == "__main__":
    sys.exit(main())
