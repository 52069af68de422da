"""``hapticproof audit [PAPER ...]``: audit the printed equations of the registered papers.

Exit status: 0 when the audit ran; :data:`FAIL_STATUS` (1) when ``--fail-on VERDICTS`` names a
verdict that some equation got (and, with ``--mutate``, when a mutant survived or crashed);
2 for a mistake on the command line or in an input file; 130 when interrupted. A paper's
repository runs ``hapticproof audit --paper paper.toml --fail-on wrong,typo,inconsistent`` in CI.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import time

from hapticproof.cli.common import check_output, input_files, write_text
from hapticproof.core.escape import for_terminal
from hapticproof.cli.terminal import colour_verdict, progress_bar, summary_line, use_colour

__all__ = ["register", "FAIL_STATUS", "fail_on_verdicts", "failing"]

FORMATS = ("table", "markdown", "json", "tex", "latex", "html")     # (latex: derive's word for tex)
#: The exit status of an audit that found a verdict ``--fail-on`` names (2 is a user's mistake).
FAIL_STATUS = 1


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "audit",
        help="audit the printed equations of the bundled papers or of your paper files (--paper)",
        description="Parse every printed equation of a paper verbatim, re-derive it and give a "
        "verdict with evidence. With no paper (or --all), audit every registered paper and the "
        "cross-paper checks.",
    )
    parser.add_argument("papers", nargs="*", metavar="PAPER", help="paper ids (e.g. hve); default: all")
    parser.add_argument("--paper", "-p", action="append", default=[], metavar="FILE",
                        help="audit your own paper from a paper file (TOML; repeatable; "
                        "hapticproof new-paper FILE writes a template)")
    parser.add_argument("--all", action="store_true", help="audit every registered paper")
    parser.add_argument("--equation", "-e", action="append", default=[], metavar="ID",
                        help="audit only this equation (repeatable; needs one PAPER)")
    parser.add_argument("--section", "-s", action="append", default=[], metavar="S",
                        help="audit only equations of section S and its subsections (repeatable; "
                        "e.g. -s 1 -s 2 -s 3.1 for the HVE paper's single-user part)")
    parser.add_argument("--format", "-f", choices=FORMATS, default="table",
                        help="table (default), markdown, json, tex or latex (a LaTeX document) or html (one "
                        "self-contained page)")
    parser.add_argument("--output", "-o", metavar="FILE", help="write to FILE instead of stdout (- is stdout)")
    parser.add_argument("--wide", action="store_true", help="table: full details instead of one shortened line each")
    parser.add_argument("--jobs", "-j", type=int, metavar="N",
                        help="worker processes (default: the machine's cores, 1 with --mutate; 1: serial); the output is the same")
    parser.add_argument("--fail-on", action="append", default=[], metavar="VERDICTS",
                        help="exit with status 1 when any equation gets one of these verdicts, comma-separated "
                        "(e.g. wrong,typo,inconsistent; repeatable); the report is written as usual. Exit status "
                        "2 is kept for mistakes on the command line or in an input file")
    mutation = parser.add_argument_group("mutation testing (--mutate)")
    mutation.add_argument("--mutate", action="store_true",
                          help="mutation-test the audit: change each printed display (flip a sign, scale or drop a "
                          "term, swap indices, reverse an inequality, replace a symbol), audit every mutant with the "
                          "same check and print the mutation score per paper (killed / (total - proved equivalent)), "
                          "crashes and survivors")
    mutation.add_argument("--sample", type=int, metavar="N", help="run N mutants per paper (default: all)")
    mutation.add_argument("--seed", type=int, default=0, help="seed of the --sample draw (default 0)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from hapticproof.audit.pool import audit_reports
    from hapticproof.audit.registry import get_paper, papers

    if args.format == "latex":
        args.format = "tex"
    check_output(args.output, "--output", inputs=input_files(args))     # before any work
    fail_on = fail_on_verdicts(args.fail_on)
    if fail_on and args.mutate:
        raise_usage("--fail-on reads the audit's verdicts; --mutate reports mutants (it exits 1 on survivors)")
    files = _paper_files(args.paper)
    if args.all or not (args.papers or files):
        selected = list(papers().values())
    else:
        selected = [get_paper(name) for name in args.papers]
    selected += files
    if args.equation and len(selected) != 1:
        raise_usage("--equation needs exactly one PAPER")
    if args.equation and args.section:
        raise_usage("use --equation or --section, not both")
    if args.jobs is not None and args.jobs < 1:
        raise_usage("--jobs must be at least 1")
    if args.section and len(selected) > 1:      # several papers: those with equations in the sections
        chosen = [(p, _section_ids(p, args.section)) for p in selected]
        if not any(ids for _, ids in chosen):
            raise_usage(f"no equation in section(s) {', '.join(args.section)} in any selected paper")
        selected = [p for p, ids in chosen if ids]
    if args.mutate:
        return _mutate(args, selected)
    if args.sample is not None:
        raise_usage("--sample needs --mutate")
    selection = [args.equation or _in_sections(p, args.section) or None for p in selected]
    total = sum(len(only) if only else len(p.equations) for p, only in zip(selected, selection))
    bar, start = progress_bar(sys.stderr, "audit"), time.perf_counter()
    reports = audit_reports(selected, {p.id: only for p, only in zip(selected, selection)}, jobs=args.jobs,
                            progress=(lambda k, _n: bar(k, total)) if bar else None)
    seconds = time.perf_counter() - start
    if args.format == "json":
        if len(reports) == 1 and len(args.papers) + len(args.paper) == 1 and not args.all:
            text = json.dumps(reports[0].to_json(), indent=2)
        else:
            text = json.dumps({"papers": [r.to_json() for r in reports]}, indent=2)
    elif args.format == "tex":
        from hapticproof.report import latex as tex

        text = tex.audit_document(reports)
    elif args.format == "html":
        from hapticproof.report.html import report_html

        text = report_html(reports)
    elif args.format == "table":
        from hapticproof.report.tables import audit_table

        terminal = sys.stdout.isatty() and not args.output
        style = colour_verdict if use_colour(sys.stdout) and not args.output else None
        width = shutil.get_terminal_size((120, 24)).columns if terminal else 120
        text = "\n\n".join(audit_table(r, width=width, wide=args.wide, style=style) for r in reports)
    else:
        from hapticproof.report.tables import audit_markdown

        text = "\n\n".join(audit_markdown(r) for r in reports)
    if args.output:
        path = write_text(args.output, text)
        if path is not None:  # "-" is standard output
            print(f"wrote {path}", file=sys.stderr)
    else:
        print(text)
    counts: dict[str, int] = {}
    for report in reports:
        for verdict, n in report.counts().items():
            counts[verdict] = counts.get(verdict, 0) + n
    print(summary_line(counts, use_colour(sys.stderr), len(reports), seconds), file=sys.stderr)
    found = failing(counts, fail_on)
    if found:
        print(f"hapticproof: --fail-on {','.join(fail_on)}: " + ", ".join(f"{v} {n}" for v, n in found.items()),
              file=sys.stderr)
        return FAIL_STATUS
    return 0


def fail_on_verdicts(items: list[str]) -> tuple[str, ...]:
    """The verdicts of ``--fail-on`` options (comma-separated, repeatable), checked by name.

    >>> fail_on_verdicts(["wrong,typo", " inconsistent"])
    ('wrong', 'typo', 'inconsistent')
    >>> fail_on_verdicts(["wrong,wrongg"])
    Traceback (most recent call last):
    ...
    hapticproof.core.errors.InputFormatError: --fail-on: unknown verdict 'wrongg' (did you mean 'wrong'?); verdicts: confirmed, conservative, typo, wrong, needs-assumption, inconsistent, malformed, undecided
    """
    import difflib

    from hapticproof.core.errors import InputFormatError
    from hapticproof.core.evidence import Verdict

    known = [v.value for v in Verdict]
    out: list[str] = []
    for item in items:
        for word in item.split(","):
            word = word.strip()
            if not word:
                raise InputFormatError(f"--fail-on expects verdicts separated by commas, got {item!r}")
            if word not in known:
                close = difflib.get_close_matches(word, known, n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                raise InputFormatError(f"--fail-on: unknown verdict {word!r}{hint}; verdicts: {', '.join(known)}")
            if word not in out:
                out.append(word)
    return tuple(out)


def failing(counts: dict[str, int], verdicts: tuple[str, ...]) -> dict[str, int]:
    """The counts of the ``verdicts`` an audit gave at least once (empty: the audit passes).

    >>> failing({"confirmed": 12, "typo": 2, "wrong": 0}, ("wrong", "typo"))
    {'typo': 2}
    """
    return {v: counts[v] for v in verdicts if counts.get(v)}


def _paper_files(paths: list[str]) -> list:
    """The registered papers of ``--paper`` files (their mistakes are one-line errors)."""
    if not paths:
        return []
    from hapticproof.audit.paperfile import read_paper

    return [read_paper(path).paper for path in paths]


def _section_ids(paper, sections: list[str]) -> list[str]:
    return [eq.id for eq in paper.ordered()
            if any(eq.section == s or eq.section.startswith(s + ".") for s in sections)]


def _mutate(args: argparse.Namespace, selected: list) -> int:
    """``--mutate``: the mutation score of each selected paper (exit 1 on survivors or crashes)."""
    from hapticproof.audit.mutate import mutate_paper

    if args.sample is not None and args.sample < 1:
        raise_usage(f"--sample must be a positive number of mutants, got {args.sample}")
    if args.format not in ("table", "json"):
        raise_usage("--mutate writes a table or JSON (--format table|json)")
    reports = []
    for paper in selected:
        only = args.equation or _in_sections(paper, args.section) or None
        report = mutate_paper(paper, only, count=args.sample, seed=args.seed, jobs=args.jobs or 1)
        reports.append(report)
        if args.format == "table" and not args.output:
            print(for_terminal(report.to_text(), multiline=True), flush=True)
    if args.format == "json":
        text = json.dumps({"papers": [r.to_json() for r in reports]}, indent=2)
    else:
        text = "\n".join(for_terminal(r.to_text(), multiline=True) for r in reports)
    if args.output:
        path = write_text(args.output, text)
        print(f"wrote {path}", file=sys.stderr)
    elif args.format == "json":
        print(text)
    failed = any(r.survivors() or r.crashes() for r in reports)
    return 1 if failed else 0


def _in_sections(paper, sections: list[str]) -> list[str]:
    """Ids of the equations in the given sections (``3.1`` takes ``3.1``, ``3.1.2``, not ``3.10``)."""
    if not sections:
        return []
    ids = [eq.id for eq in paper.ordered()
           if any(eq.section == s or eq.section.startswith(s + ".") for s in sections)]
    if not ids:
        known = sorted({eq.section for eq in paper.ordered() if eq.section})
        raise_usage(f"no equation of {paper.id} in section(s) {', '.join(sections)}; sections: {', '.join(known)}")
    return ids


def raise_usage(message: str) -> None:
    from hapticproof.core.errors import InputFormatError

    raise InputFormatError(message)
