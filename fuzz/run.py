"""Run the fuzz harnesses (make fuzz, make fuzz-smoke).

    python fuzz/run.py --runs 200000            # every harness, 200000 runs each
    python fuzz/run.py --smoke                  # the corpus plus a short run of each (CI)
    python fuzz/run.py --runs 1000 design_curve # one harness

Each harness starts from its corpus in fuzz/corpus/<name> with a working copy in
build/fuzz/work/<name>; afterwards the inputs that add coverage are merged back into the
repository's corpus (not in --smoke). Findings are written to build/fuzz/crash-* and make the
run fail. Prints one line per harness: runs executed, seconds, findings.
"""

import argparse
import pathlib
import re
import shutil
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
HARNESSES = ("hull_description", "offsets_csv", "sections_csv", "tecplot", "xyz_grid", "design_curve")
MAX_LEN = 8192          # bytes per input
TIMEOUT_S = 60          # one input running longer than this is a finding (a hang)
RSS_LIMIT_MB = 4096     # one input using more memory than this is a finding


def fuzz_command(name, corpus_dirs, extra):
    return [sys.executable, str(HERE / f"fuzz_{name}.py"), *map(str, corpus_dirs), f"-max_len={MAX_LEN}",
            f"-timeout={TIMEOUT_S}", f"-rss_limit_mb={RSS_LIMIT_MB}",
            f"-artifact_prefix={ROOT / 'build' / 'fuzz'}/", "-print_final_stats=1", *extra]


def run_one(name, runs, smoke):
    corpus = HERE / "corpus" / name
    work = ROOT / "build" / "fuzz" / "work" / name
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    extra = [f"-runs={runs}"] + (["-max_total_time=60"] if smoke else [])
    start = time.perf_counter()
    proc = subprocess.run(fuzz_command(name, [work, corpus], extra), cwd=HERE, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    log = proc.stdout + proc.stderr
    done = re.search(r"stat::number_of_executed_units:\s*(\d+)", log)
    executed = int(done.group(1)) if done else 0
    if proc.returncode != 0:
        print(log[-6000:], file=sys.stderr)
    elif not smoke:
        subprocess.run(fuzz_command(name, [corpus, work], ["-merge=1"]), cwd=HERE, capture_output=True, text=True)
    return executed, seconds, proc.returncode


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("names", nargs="*", default=HARNESSES, help="harnesses to run (default: all)")
    ap.add_argument("--runs", type=int, default=200000, help="runs per harness")
    ap.add_argument("--smoke", action="store_true", help="corpus plus 2000 runs each, at most 60 s each, no merge")
    args = ap.parse_args()
    (ROOT / "build" / "fuzz").mkdir(parents=True, exist_ok=True)
    runs = 2000 if args.smoke else args.runs
    total, failed = 0, []
    for name in args.names:
        if name not in HARNESSES:
            sys.exit(f"unknown harness {name!r}; expected one of {', '.join(HARNESSES)}")
        executed, seconds, code = run_one(name, runs, args.smoke)
        total += executed
        print(f"fuzz {name:18s} {executed:9d} runs {seconds:8.1f} s  {'ok' if code == 0 else 'FINDING'}", flush=True)
        if code != 0:
            failed.append(name)
    print(f"fuzz total {total} runs, {len(failed)} harness(es) with findings")
    passed = len(args.names) - len(failed)
    print(f"{passed} passed, {len(failed)} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
