"""Cold-process wall times of the command lines the README quotes (issue 21: every entry point as
fast as its decision).

Each command is started ``--repeat`` times as a fresh process (imports included) and its median wall
time recorded with the verdict line it printed; writes ``benchmarks/results/cli.json``. The targets:
``--version`` and ``--help`` under 0.3 s of CPU, ``derive single-user --delay 10000`` under 3 s, ``derive multi-user --users 1000 --uniform`` under
5 s (symbolic and numeric), the delay-margin search ending by its deadline.

    python benchmarks/bench_cli.py [--repeat 3]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"

WALL = ["--param", "K=2", "--param", "T=0.001", "--param", "b=0.0201", "--param", "B=0.001"]
USERS = ["--param", "b=0.02", "--param", "K_0=1", "--param", "B_0=0.001", "--param", "K=0.01", "--param", "B=0.00001",
         "--param", "T=0.001"]
COMMANDS = {
    # issue 29: the parsers load no SymPy or NumPy, so these cost the interpreter's start-up (< 0.3 s of CPU)
    "--version": ["--version"],
    "--help": ["--help"],
    "audit --help": ["audit", "--help"],
    "single-user, delay 10 000": ["derive", "single-user", "--delay", "10000", *WALL],
    "single-user, delay 1 000": ["derive", "single-user", "--delay", "1000", *WALL],
    "multi-user, 20 users, uniform, symbolic": ["derive", "multi-user", "--users", "20", "--uniform"],
    "multi-user, 1000 users, uniform, symbolic": ["derive", "multi-user", "--users", "1000", "--uniform"],
    "multi-user, 1000 users, uniform, numeric, delay 3": ["derive", "multi-user", "--users", "1000", "--uniform", "--delay", "3", *USERS],
    "delay margin, passive for 1.5 million delays (--deadline 10)": [
        "derive", "single-user", "--param", "K=0.001", "--param", "B=1", "--param", "T=0.001", "--param", "b=2.5",
        "--delay-margin", "--deadline", "10"],
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--output", default=str(RESULTS))
    parser.add_argument("--only", action="append", default=[], help="run the commands whose name contains this")
    args = parser.parse_args()
    exe = shutil.which("hapticproof") or sys.exit("hapticproof is not on PATH (pip install -e .)")
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for name, argv in COMMANDS.items():
        if args.only and not any(o in name for o in args.only):
            continue
        times, cpu, text = [], [], ""
        for _ in range(args.repeat):
            start = time.perf_counter()
            before = os.times()
            proc = subprocess.run([exe, *argv], capture_output=True, text=True, check=False)
            after = os.times()
            times.append(time.perf_counter() - start)
            cpu.append((after.children_user - before.children_user) + (after.children_system - before.children_system))
            text = proc.stdout
            if proc.returncode:
                sys.exit(f"{name}: exit {proc.returncode}: {proc.stderr.strip()[:400]}")
        verdicts = [line.strip() for line in text.splitlines() if line.startswith(("verdict:", "delay margin:"))]
        rows.append({"name": name, "command": "hapticproof " + " ".join(argv), "median_seconds": statistics.median(times),
                     "seconds": times, "median_cpu_seconds": statistics.median(cpu), "printed": verdicts})
        print(f"{name:62s} median {statistics.median(times):6.2f} s wall, {statistics.median(cpu):6.2f} s CPU  "
              f"{verdicts[-1][:90] if verdicts else ''}")
    data = {"rows": rows, "repeat": args.repeat, "load_average": os.getloadavg(), "cpus": os.cpu_count()}
    (out / "cli.json").write_text(json.dumps(data, indent=1))
    print(f"wrote {out / 'cli.json'}", file=sys.stderr)


if __name__ == "__main__":
    main()
