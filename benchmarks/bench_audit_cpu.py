"""CPU time of the bundled audit: a baseline commit against this checkout, side by side.

Runs ``hapticproof audit --format json`` (every bundled paper, the command as users run it:
``--jobs`` at its default, the machine's cores) and the same with ``--jobs 1``, from the
baseline commit and from this checkout, alternating (baseline, this, this, baseline, ...) so
that both see the same load, and measures the **CPU time** (user + sys of the process and its
worker processes, ``resource.getrusage(RUSAGE_CHILDREN)``) -- on a shared machine wall time
mostly measures the neighbours. Reports medians and their ratio, and per paper the CPU time of
auditing it in one process (papers in the audit's order, BLAS pinned to one thread on both
sides), also alternating. Every run's JSON is compared with
the first baseline run: everything but ``seconds`` must be identical (verdicts, details,
derived and corrected LaTeX, evidence), and every difference is listed.

The baseline is a git worktree with its own virtual environment (created when missing)::

    git worktree add /tmp/base96 96041ee
    python -m venv /tmp/base96/.venv && /tmp/base96/.venv/bin/pip install -e /tmp/base96

    python benchmarks/bench_audit_cpu.py [--baseline 96041ee] [--baseline-dir /tmp/base96] [--repeat 3]
        [--modes default 1] [--env OPENBLAS_NUM_THREADS=1]

``--env NAME=VALUE`` sets a variable for both sides (e.g. ``OPENBLAS_NUM_THREADS=1`` pins
NumPy's BLAS to one thread in the baseline too, which this checkout does by itself for the
audit). Writes ``benchmarks/results/audit_cpu.json`` and ``audit_cpu.png``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results"


def ensure_baseline(commit: str, where: Path) -> Path:
    """The baseline's Python (a worktree of ``commit`` at ``where`` with its own venv)."""
    python = where / ".venv" / "bin" / "python"
    if not where.exists():
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(where), commit], check=True)
    head = subprocess.run(["git", "-C", str(where), "rev-parse", "HEAD"], capture_output=True, text=True, check=True).stdout
    wanted = subprocess.run(["git", "-C", str(ROOT), "rev-parse", commit], capture_output=True, text=True, check=True).stdout
    if head.strip() != wanted.strip():
        raise SystemExit(f"{where} is at {head.strip()[:10]}, not the baseline {commit}")
    if not python.exists():
        subprocess.run([sys.executable, "-m", "venv", str(where / ".venv")], check=True)
        subprocess.run([str(python), "-m", "pip", "install", "-q", "-e", str(where)], check=True)
    return python


def run_audit(python: Path, jobs: str, env: dict[str, str], out: Path) -> tuple[float, float]:
    """CPU seconds (user + sys, this process's children: the audit and its workers) and wall seconds."""
    cmd = [str(python), "-m", "hapticproof", "audit", "--format", "json", "-o", str(out)]
    if jobs != "default":
        cmd += ["--jobs", jobs]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=tempfile.gettempdir())
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall


#: Run in each side's interpreter: CPU seconds (this process only) of registering the papers
#: and of auditing each one, in order, in one process (caches shared as in the audit).
PER_PAPER = """
import json, time
t0 = time.process_time()
from hapticproof.audit.registry import papers
from hapticproof.audit.runner import audit_paper
found = papers()
out = {"import and registration": time.process_time() - t0}
for pid, paper in found.items():
    t = time.process_time()
    audit_paper(paper)
    out[pid] = time.process_time() - t
print(json.dumps(out))
"""


def run_per_paper(python: Path, env: dict[str, str]) -> dict[str, float]:
    """CPU seconds per paper in one process (BLAS pinned to one thread on both sides: this
    part measures the algebra, not the thread settings of the command line)."""
    env = {**env, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    out = subprocess.run([str(python), "-c", PER_PAPER], check=True, env=env, capture_output=True, text=True,
                         cwd=tempfile.gettempdir()).stdout
    return json.loads(out.strip().splitlines()[-1])


def differences(a: Any, b: Any, path: str = "") -> list[str]:
    """Every difference between two audit JSON documents except the ``seconds`` timings."""
    out: list[str] = []
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if key == "seconds":
                continue
            if key not in a or key not in b:
                out.append(f"{path}/{key}: only in {'the baseline' if key in a else 'this checkout'}")
            else:
                out += differences(a[key], b[key], f"{path}/{key}")
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} vs {len(b)} items")
        for i, (x, y) in enumerate(zip(a, b)):
            label = x.get("id", x.get("paper", i)) if isinstance(x, dict) else i
            out += differences(x, y, f"{path}[{label}]")
    elif a != b:
        out.append(f"{path}: {json.dumps(a)[:200]} vs {json.dumps(b)[:200]}")
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--baseline", default="96041ee", help="baseline commit")
    parser.add_argument("--baseline-dir", type=Path, default=Path("/tmp/base96"), help="its worktree (created when missing)")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--modes", nargs="+", default=["default", "1"], help="--jobs values ('default': not given)")
    parser.add_argument("--env", action="append", default=[], metavar="NAME=VALUE", help="set for both sides")
    parser.add_argument("--out", default="audit_cpu", help="name of the JSON and PNG in benchmarks/results/")
    parser.add_argument("--no-per-paper", dest="per_paper", action="store_false",
                        help="skip the per-paper CPU runs (one process per side and repeat, papers in order)")
    args = parser.parse_args()
    sides = {"baseline": ensure_baseline(args.baseline, args.baseline_dir), "this": Path(sys.executable)}
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)   # both sides with Python's bytecode cache, as users run them
    for item in args.env:
        name, _, value = item.partition("=")
        env[name] = value
    RESULTS.mkdir(parents=True, exist_ok=True)
    runs: dict[str, dict[str, list]] = {mode: {side: [] for side in sides} for mode in args.modes}
    per_paper: dict[str, dict[str, list]] = {side: {} for side in sides}
    reference = None
    found: list[str] = []
    compared = 0
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(args.repeat):
            order = list(sides) if r % 2 == 0 else list(sides)[::-1]
            for mode in args.modes:
                for side in order:
                    out = Path(tmp) / f"{side}-{mode}-{r}.json"
                    cpu, wall = run_audit(sides[side], mode, env, out)
                    report = json.loads(out.read_text())
                    runs[mode][side].append({"cpu": cpu, "wall": wall})
                    if reference is None and side == "baseline":
                        reference = report
                    if reference is not None:
                        diff = differences(reference, report)
                        compared += 1
                        found += [f"{side} --jobs {mode} run {r}: {d}" for d in diff]
                    print(f"run {r} --jobs {mode:7s} {side:8s}: cpu {cpu:6.2f} s, wall {wall:6.2f} s", flush=True)
            if args.per_paper:
                for side in order:
                    for paper, sec in run_per_paper(sides[side], env).items():
                        per_paper[side].setdefault(paper, []).append(sec)
                    print(f"run {r} per paper {side:8s}: " + ", ".join(f"{p} {v[-1]:.2f}" for p, v in per_paper[side].items()),
                          flush=True)
    summary: dict[str, Any] = {"baseline_commit": args.baseline, "env": args.env, "repeat": args.repeat,
                               "machine": {"cpus": os.cpu_count(), "python": sys.version.split()[0],
                                           "load_average_at_end": os.getloadavg()}, "modes": {}}
    for mode, by_side in runs.items():
        med = {side: statistics.median(x["cpu"] for x in v) for side, v in by_side.items()}
        summary["modes"][mode] = {
            "cpu_median": med, "ratio_this_over_baseline": med["this"] / med["baseline"],
            "wall_median": {side: statistics.median(x["wall"] for x in v) for side, v in by_side.items()},
            "runs": by_side}
        print(f"--jobs {mode}: baseline {med['baseline']:.2f} s CPU, this {med['this']:.2f} s CPU "
              f"(ratio {med['this'] / med['baseline']:.3f}, {med['baseline'] / med['this']:.2f}x less)")
    summary["per_paper_cpu_median"] = {side: {p: statistics.median(v) for p, v in d.items()} for side, d in per_paper.items()}
    summary["per_paper_cpu_runs"] = per_paper
    for paper in summary["per_paper_cpu_median"].get("baseline", {}):
        a, b = (summary["per_paper_cpu_median"][s].get(paper, float("nan")) for s in ("baseline", "this"))
        print(f"  {paper:24s} baseline {a:6.2f} s CPU  this {b:6.2f} s CPU  ratio {b / a:.3f}")
    summary["json_comparison"] = {"reports_compared": compared, "differences_besides_seconds": found}
    print(f"JSON: {compared} reports compared with the first baseline run, {len(found)} differences besides seconds")
    for line in found[:50]:
        print("   ", line)
    (RESULTS / f"{args.out}.json").write_text(json.dumps(summary, indent=2))
    plot(summary, RESULTS / f"{args.out}.png")


def plot(summary: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4.2), gridspec_kw={"width_ratios": [1, 1.4]})
    modes = list(summary["modes"])
    colors = {"baseline": "#999999", "this": "#1f77b4"}
    for k, mode in enumerate(modes):
        data = summary["modes"][mode]
        for j, side in enumerate(("baseline", "this")):
            x = k + (j - 0.5) * 0.36
            ax.bar(x, data["cpu_median"][side], width=0.34, color=colors[side], label=side if k == 0 else None)
            ax.scatter([x] * len(data["runs"][side]), [r["cpu"] for r in data["runs"][side]], color="black", s=8, zorder=3)
        ax.text(k, max(data["cpu_median"].values()) * 1.02, f"this / baseline = {data['ratio_this_over_baseline']:.2f}",
                ha="center", fontsize=9)
    ax.set_xticks(range(len(modes)), [f"--jobs {m}" for m in modes])
    ax.set_ylabel("CPU seconds (user + sys), median")
    ax.set_title(f"bundled audit, baseline {summary['baseline_commit']} vs this")
    ax.axhline(0, color="black", lw=0.5)
    ax.legend()
    medians = summary["per_paper_cpu_median"]
    papers = list(medians.get("baseline", {}))
    for j, side in enumerate(("baseline", "this")):
        vals = [medians[side].get(p, 0) for p in papers]
        bx.bar([i + (j - 0.5) * 0.36 for i in range(len(papers))], vals, width=0.34, color=colors[side], label=side)
    for i, p in enumerate(papers):
        top = max(medians["baseline"][p], medians["this"][p])
        bx.text(i, top * 1.02 + 0.1, f"{medians['this'][p] / medians['baseline'][p]:.2f}", ha="center", fontsize=8)
    bx.set_xticks(range(len(papers)), [p.replace(" and ", "\n& ") for p in papers], rotation=20, fontsize=8)
    bx.set_ylabel("CPU seconds, median (one process, BLAS 1 thread)")
    bx.set_title("per paper (label: this / baseline)")
    bx.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    main()
