"""``hapticproof check REPORT.json``: re-verify the certificates of a saved JSON report.

The report is what ``hapticproof audit --format json`` or ``hapticproof derive ... --format json``
wrote. Every certificate in it is re-checked by the independent checker
(:mod:`hapticproof.exact.checker`: Sturm sequences, exact evaluation of the original transfer
function, Routh-Hurwitz); every verdict that carries its original object (``G^{-1}(z)``, the
printed display as given, the scene at the witness) is judged against the definition
(:mod:`hapticproof.exact.judge`); and what the report *displays* -- a verdict, a witness -- is
re-derived from what it carries: a tampered verdict, witness or certificate number is refused
with a line saying what does not match. Every certificate and judge object must be bound to
what its verdict is about (:mod:`hapticproof.exact.acceptance`: the same transfer function, the
whole range of ``c``, a known kind, one point of the circle). Exit code 0 only when the report
is **accepted** -- every verdict that claims something backed by evidence that was re-verified
and bound to it --, 1 when something fails or is refused, when a verdict carries no
certificate or judge object, or when a certificate could not be re-verified (a limit): an
unverifiable ``proved`` is never success; 2 for a file that cannot be read or is not a report
(its shape is checked first: :mod:`hapticproof.core.shapes`).
"""

from __future__ import annotations

import argparse
import sys

from hapticproof.core.escape import for_terminal
from hapticproof.core.files import read_json, read_text
from hapticproof.core.shapes import check_report as check_shape

__all__ = ["register"]


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "check",
        help="re-verify the certificates in a saved JSON report (audit or derive)",
        description="Re-verify every certificate in a JSON report written by 'audit --format json' or "
        "'derive ... --format json', with the independent checker (Sturm sequences, exact evaluation, "
        "Routh-Hurwitz), judge every verdict carrying its original object against the definition, and "
        "re-derive the displayed verdicts and witnesses (a report whose display its evidence does not give is "
        "refused). Lists the entries that carry no certificate. Use - to read standard input.",
    )
    parser.add_argument("report", help="the JSON report (a file, or - for standard input)")
    parser.add_argument("--quiet", action="store_true", help="print only the summary line")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from hapticproof.exact.checker import check_report

    name = "<stdin>" if args.report == "-" else args.report
    report = read_json(read_text(args.report, name), name)
    check_shape(report, name)      # a number, null or a table of another form is no report
    result = check_report(report)
    lines = [for_terminal(line) for line in result.summary().splitlines()]     # names from the report, escaped
    print("\n".join(lines[-1:] if args.quiet else lines))
    if not result.accepted:                     # one line saying why; every verdict must be backed
        order = ("display", "binding", "certificate", "judge")
        failed = sorted(result.failed, key=lambda item: order.index(item[1].source) if item[1].source in order else 0)
        if failed:
            name, first = failed[0]
            more = f" (and {len(failed) - 1} more)" if len(failed) > 1 else ""
            print(f"report refused: {for_terminal(name)}: {for_terminal(first.reason)}{more}", file=sys.stderr)
        elif not result.not_verified:
            print("report not accepted: no certificate or judge object in it was re-verified", file=sys.stderr)
        else:
            missing = result.not_verified
            name, first = next(((n, r) for n, r in missing if r.source != "unbacked"), missing[0])
            what = first.reason if first.source == "unbacked" else f"not re-verified: {first.reason}"
            more = f" (and {len(missing) - 1} more)" if len(missing) > 1 else ""
            print(f"report not accepted: {for_terminal(name)}: {for_terminal(what)}{more}", file=sys.stderr)
    return 0 if result.accepted else 1
