r"""``hapticproof new-paper --from`` on the three bundled transcriptions, against what
``derivations/`` registers.

A *registered display* is an equation of the registry (:func:`hapticproof.audit.registry.get_paper`)
of kind ``expression`` or ``condition`` whose ``printed`` is not empty (kind ``claim`` entries
quote prose; an empty ``printed`` marks a display the transcription lost). For each one:

found
    a display read from the transcription (:func:`hapticproof.audit.source.read_source`) whose
    ``text`` or ``original`` equals the registered ``printed`` once whitespace is normalised
    (the registered strings are not uniform: some keep ``\tag{41}`` or ``\quad (2)``);
    ``exact`` counts the byte-identical ones.
guessed kind right
    the registered kind equals the kind of the guessed claim: ``inverse-transfer`` and
    ``residue`` are expressions, the four condition claims conditions, ``hermitian-part`` a
    condition when the display has an inequality (the paper file's ``form = auto``). An
    abstention (no claim guessed) is never counted right; it is reported apart.
fine claims
    the displays of ``examples/hve-single-user.toml`` (the HVE paper's single-user part written
    as a paper file by hand): the guessed claim against the file's.
drafts
    the draft of each transcription (:func:`hapticproof.audit.source.draft`) loads, and how many
    of its entries are active.

    python benchmarks/bench_newpaper.py [--papers /path/to/papers] [--audit]

writes ``benchmarks/results/newpaper.json``; ``--audit`` also audits each draft as written
(``hapticproof audit --paper``) and reports its verdicts and time.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
import tomllib
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"
TRANSCRIPTIONS = {"hve": "000_e6b68def623c8e74.txt", "bilateral-3dof": "001_48f53b5d92944b5d.txt",
                  "teleoperator": "002_de715dde36093cfe.txt"}
COARSE = {"inverse-transfer": "expression", "residue": "expression", "passivity-condition": "condition",
          "sufficient-condition": "condition", "necessary-condition": "condition", "stability-condition": "condition"}


def norm(text: str) -> str:
    return " ".join(text.split())


def coarse(claim: str | None, text: str) -> str | None:
    from hapticproof.audit.source.guess import has_inequality

    if claim is None:
        return None
    if claim in COARSE:
        return COARSE[claim]
    return "condition" if has_inequality(text) else "expression"


def measure_paper(paper_id: str, path: Path) -> dict:
    from hapticproof.audit.registry import get_paper
    from hapticproof.audit.source import draft, read_source

    start = time.perf_counter()
    source = read_source(path)
    seconds = time.perf_counter() - start
    by_norm: dict[str, list] = {}
    for display in source.displays:
        for candidate in {norm(display.text), norm(display.original)}:
            by_norm.setdefault(candidate, []).append(display)
    start = time.perf_counter()
    result = draft(source, paper_id=f"{paper_id}-draft")
    draft_seconds = time.perf_counter() - start
    # the draft's own guesses (a display right after another shares the prose before the run)
    guesses = {id(e.display): (e.guessed, e.why, e.form) for e in result.entries}
    registered = [e for e in get_paper(paper_id).ordered() if e.kind in ("expression", "condition")]
    empty = [e.id for e in registered if not e.printed.strip()]
    registered = [e for e in registered if e.printed.strip()]
    rows = []
    for e in registered:
        hits = by_norm.get(norm(e.printed), [])
        display = next((d for d in hits if d.id == e.id), hits[0] if hits else None)
        row = {"id": e.id, "kind": e.kind, "section": e.section, "found": display is not None}
        if display is not None:
            claim, reason, form = guesses[id(display)]
            row.update(exact=e.printed in (display.text, display.original), line=display.line, display_id=display.id,
                       display_section=display.section.id if display.section else None, claim=claim, reason=reason,
                       form=form, coarse=form or coarse(claim, display.text))
        else:
            row["printed"] = e.printed[:160]
        rows.append(row)
    found = [r for r in rows if r["found"]]
    right = [r for r in found if r["coarse"] == r["kind"]]
    abstained = Counter(r["kind"] for r in found if r["claim"] is None)
    wrong = [r for r in found if r["claim"] is not None and r["coarse"] != r["kind"]]
    return {
        "paper": paper_id, "transcription": path.name, "read_seconds": round(seconds, 3),
        "displays_read": len(source.displays), "warnings": source.warnings,
        "registered": len(registered), "registered_empty": empty,
        "found": len(found), "exact": sum(r["exact"] for r in found),
        "same_id": sum(r["display_id"] == r["id"] for r in found),
        "same_section": sum(r["display_section"] == r["section"] for r in found),
        "guessed": sum(1 for r in found if r["claim"] is not None), "guessed_right": len(right),
        "abstained": dict(abstained),
        "guessed_wrong": [{k: r[k] for k in ("id", "kind", "claim", "reason")} for r in wrong],
        "not_found": [{k: r[k] for k in ("id", "kind", "printed")} for r in rows if not r["found"]],
        "draft": {"active": result.active, "commented": result.commented, "seconds": round(draft_seconds, 2),
                  "text": result.text},
        "rows": rows,
    }


def measure_example(path: Path) -> dict:
    """Fine agreement with the claims of ``examples/hve-single-user.toml``."""
    from hapticproof.audit.source import read_source
    from hapticproof.audit.source.draft import contexts
    from hapticproof.audit.source.guess import guess_claim

    data = tomllib.loads((ROOT / "examples" / "hve-single-user.toml").read_text(encoding="utf-8"))
    source = read_source(path)
    context = {id(d): c for d, c in zip(source.displays, contexts(source))}
    by_norm = {}
    for d in source.displays:
        by_norm.setdefault(norm(d.text), d)
        by_norm.setdefault(norm(d.original), d)
    rows = []
    for entry in data["equations"]:
        if entry["claim"] == "same-as":   # a relation between displays, not a display's shape
            continue
        d = by_norm.get(norm(entry["printed"]))
        claim, reason = guess_claim(d.text, context=context[id(d)]) if d else (None, "not found")
        rows.append({"id": entry["id"], "claim": entry["claim"], "found": d is not None, "guessed": claim, "reason": reason})
    return {"equations": len(rows), "found": sum(r["found"] for r in rows),
            "same_claim": sum(r["claim"] == r["guessed"] for r in rows), "rows": rows}


def audit_draft(text: str, name: str) -> dict:
    """The draft audited as written, in a fresh process (verdict counts and wall time)."""
    RESULTS.mkdir(parents=True, exist_ok=True)
    path = RESULTS / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    start = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "hapticproof", "audit", "--paper", str(path), "--format", "json"],
                         capture_output=True, text=True, env=env)
    seconds = time.perf_counter() - start
    if out.returncode not in (0, 1):
        return {"error": out.stderr.strip()[-300:], "seconds": round(seconds, 1)}
    data = json.loads(out.stdout)
    return {"seconds": round(seconds, 1), "verdicts": dict(Counter(e["verdict"] for e in data["equations"]))}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--papers", default=os.environ.get("HAPTICPROOF_PAPERS", str(ROOT.parent / "shared" / "papers")))
    parser.add_argument("--audit", action="store_true", help="also audit each draft as written")
    args = parser.parse_args(argv)
    folder = Path(args.papers)
    papers = [measure_paper(pid, folder / name) for pid, name in TRANSCRIPTIONS.items()]
    example = measure_example(folder / TRANSCRIPTIONS["hve"])
    if args.audit:
        for p in papers:
            p["draft"]["audit"] = audit_draft(p["draft"]["text"], f"{p['paper']}-draft")
    registered = sum(p["registered"] for p in papers)
    found = sum(p["found"] for p in papers)
    guessed = sum(p["guessed"] for p in papers)
    right = sum(p["guessed_right"] for p in papers)
    summary = {
        "registered": registered, "found": found, "found_fraction": round(found / registered, 4),
        "exact": sum(p["exact"] for p in papers), "same_id": sum(p["same_id"] for p in papers),
        "same_section": sum(p["same_section"] for p in papers),
        "guessed": guessed, "guessed_right": right,
        "precision": round(right / guessed, 4) if guessed else None,
        "right_of_found": round(right / found, 4) if found else None,
        "abstained_on_expression": sum(p["abstained"].get("expression", 0) for p in papers),
        "abstained_on_condition": sum(p["abstained"].get("condition", 0) for p in papers),
        "example_same_claim": f"{example['same_claim']}/{example['equations']}",
        "drafts": {p["paper"]: {k: v for k, v in p["draft"].items() if k != "text"} for p in papers},
    }
    RESULTS.mkdir(parents=True, exist_ok=True)
    out = {"summary": summary, "papers": papers, "example": example}
    (RESULTS / "newpaper.json").write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    for p in papers:
        print(f"{p['paper']:15s} registered {p['registered']:3d}  found {p['found']:3d} (exact {p['exact']:3d}, same id "
              f"{p['same_id']:3d}, same section {p['same_section']:3d})  guessed {p['guessed']:3d}, kind right "
              f"{p['guessed_right']:3d}  abstained {p['abstained']}  draft {p['draft']['active']} active / "
              f"{p['draft']['commented']} commented  [{p['read_seconds']} s]")
        for miss in p["not_found"]:
            print(f"    not found: {miss['id']} ({miss['kind']}): {miss['printed'][:90]}")
        for bad in p["guessed_wrong"]:
            print(f"    kind differs: {bad['id']} registered {bad['kind']}, guessed {bad['claim']}")
        if "audit" in p["draft"]:
            print(f"    draft audited as written: {p['draft']['audit']}")
    print(f"examples/hve-single-user.toml: same claim {summary['example_same_claim']}")
    for r in example["rows"]:
        if r["claim"] != r["guessed"]:
            print(f"    {r['id']}: file {r['claim']}, guessed {r['guessed']} ({r['reason']})")
    print(json.dumps({k: v for k, v in summary.items() if k != "drafts"}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
