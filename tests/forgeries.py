"""Forged reports (issue 30): genuine reports of the toolkit edited the way a hostile author
would, each forgery claiming ``proved`` (or ``confirmed``) for an object that is not passive, or
showing evidence that is not about what it claims. Used by ``test_forged_reports.py`` and by
the fuzz test (``test_fuzz_inputs.py``).

Every function takes a genuine report (a JSON value) and returns ``(what, forged, expected)``
triples: what was done, the forged report, and a piece of the line ``check`` must refuse it
with.
"""

from __future__ import annotations

import copy
import json
from collections.abc import Iterator
from typing import Any

#: A virtual wall that is not passive: Re G^-1(c) = c/1000 + 1/2000 < 0 for c < -1/2.
NOT_PASSIVE = ["derive", "single-user", "--param", "K=2", "--param", "T=1/1000", "--param", "b=3/2000",
               "--param", "B=1/1000", "--format", "json"]
#: The same wall with enough damping: passive.
PASSIVE = ["derive", "single-user", "--param", "K=2", "--param", "T=1/1000", "--param", "b=1",
           "--param", "B=1/1000", "--format", "json"]

SIGN = "Re G^-1 >= 0 for all w"


def _certificates(node: Any) -> Iterator[dict]:
    if isinstance(node, dict):
        if isinstance(node.get("certificate"), str):
            yield node
            return
        for value in node.values():
            yield from _certificates(value)
    elif isinstance(node, list):
        for value in node:
            yield from _certificates(value)


def _sign_condition(report: dict) -> dict:
    return next(c for c in report["conditions"] if c["name"] == SIGN)


def _claim_proved(report: dict, keep_definition: bool = False) -> dict:
    """Every decision, the verdict and the definition say ``proved``; no witness is shown."""
    for cond in report["conditions"]:
        cond["decision"] = "proved"
        cond.get("evidence", {}).pop("witness", None)
    report["verdict"], report["witness"] = "proved", None
    if keep_definition and isinstance(report.get("definition"), dict):
        report["definition"]["decision"] = "proved"
        report["definition"].pop("witness", None)
    else:
        report.pop("definition", None)
    return report


def forged_walls(not_passive: dict, passive: dict) -> list[tuple[str, dict, str]]:
    """Forgeries of a ``derive`` report of a wall that is not passive, each claiming ``proved``."""
    out = []

    # a genuine sign certificate whose interval was shrunk to where the polynomial is positive
    for keep in (False, True):
        r = _claim_proved(copy.deepcopy(not_passive), keep_definition=keep)
        cert = _sign_condition(r)["evidence"]["facts"]["certificate"]
        cert.update(interval=["0", "1"], points=["0", "1"], roots=[], holds=True)
        for key in ("witness", "witness_point"):
            cert.pop(key, None)
        out.append((f"interval shrunk to [0, 1]{' (definition kept)' if keep else ''}", r,
                    "does not cover the whole range"))

    # the definition object with a misspelt judge kind (was counted as passing)
    r = _claim_proved(copy.deepcopy(not_passive), keep_definition=True)
    r["definition"]["judge"] = "positive-reel"
    out.append(("misspelt judge kind", r, "unknown judge kind"))
    r = copy.deepcopy(not_passive)
    _sign_condition(r)["evidence"]["facts"]["certificate"]["certificate"] = "sgin"
    out.append(("misspelt certificate kind", r, "unknown certificate kind"))

    # a certificate not linked to the transfer function it claims to decide
    r = _claim_proved(copy.deepcopy(not_passive), keep_definition=True)
    cert = _sign_condition(r)["evidence"]["facts"]["certificate"]
    for key in ("transfer", "numerator", "denominator", "witness", "witness_point"):
        cert.pop(key, None)
    cert.update(polynomial=["1"], holds=True, points=["-1", "1"], roots=[])
    out.append(("sign certificate unlinked from G^-1", r, "not tied to Re G^-1"))
    r = _claim_proved(copy.deepcopy(not_passive), keep_definition=True)
    _sign_condition(r)["evidence"]["facts"]["certificate"] = copy.deepcopy(
        _sign_condition(passive)["evidence"]["facts"]["certificate"])           # a passive wall's genuine proof
    out.append(("another wall's sign certificate", r, "another transfer function"))
    r = copy.deepcopy(passive)                                                   # the passive wall's report ...
    r["G_inverse"] = not_passive["G_inverse"]                                    # ... shown as the other wall
    out.append(("G^-1 shown is not the one decided", r, "the G^-1 shown"))
    r = _claim_proved(copy.deepcopy(not_passive), keep_definition=True)
    roots = r["conditions"][0]["evidence"]["facts"]["certificate"]
    roots["polynomial"] = ["-1", "0", "1"]
    roots["boundary"], roots["boundary_count"] = [{"multiplicity": 1, "root": "-1"}, {"multiplicity": 1, "root": "1"}], 2
    out.append(("roots certificate of another polynomial", r, "roots certificate"))

    # a false certificate above the checker's degree limit (was "not re-verified", exit 0)
    r = _claim_proved(copy.deepcopy(not_passive))
    cert = _sign_condition(r)["evidence"]["facts"]["certificate"]
    for key in ("transfer", "numerator", "denominator", "witness", "witness_point"):
        cert.pop(key, None)
    cert.update(polynomial=["1", "0", "-3"] + ["0"] * 697 + ["3"], holds=True, points=["-1", "1"], roots=[])  # 1 - 3c^2 + 3c^700
    out.append(("false certificate of degree 700", r, "not re-verified"))

    # every certificate stripped and every decision flipped
    r = _claim_proved(copy.deepcopy(not_passive))
    for cond in r["conditions"]:
        cond["evidence"] = {"method": "root-isolation"}
    out.append(("certificates stripped, decisions flipped", r, "no positive-real definition object"))
    r2 = copy.deepcopy(r)
    r2.pop("G_inverse")
    out.append(("certificates stripped, decisions flipped, G^-1 not shown", r2, "carries no certificate"))

    # a witness whose omega_T contradicts its c and z
    r = copy.deepcopy(not_passive)
    r["witness"]["omega_T"] = "pi/3"
    _sign_condition(r)["evidence"]["witness"]["omega_T"] = "pi/3"
    r["definition"]["witness"]["omega_T"] = "pi/3"
    out.append(("omega_T contradicts c and z", r, "omega_T = pi/3"))
    # a worst case moved to where Re G^-1 is positive (consistent with the Re G^-1 shown)
    r = copy.deepcopy(not_passive)
    for where in (r, _sign_condition(r)):
        where["minimiser"], where["minimum"] = "1", "3/2000"
    out.append(("worst case moved", r, "the minimum shown 3/2000"))
    r = copy.deepcopy(not_passive)
    r["witness"]["c"] = "1/2"
    r["definition"]["witness"]["c"] = "1/2"
    _sign_condition(r)["evidence"]["witness"]["c"] = "1/2"
    out.append(("c contradicts z", r, "is not Re z"))
    return out


def forged_audits(audit: dict) -> list[tuple[str, dict, str]]:
    """Forgeries of an audit (one paper): an entry with a judged counterexample relabelled
    ``confirmed`` with its judge object edited to match, an entry with an exact recheck
    relabelled, every certificate stripped."""
    out = []
    entries = audit["equations"]
    judged = next(k for k, e in enumerate(entries) if (e["evidence"].get("facts") or {}).get("judge", {}).get("claim")
                  == "holds-not-passive")
    sample = next(e["evidence"]["facts"]["judge"] for e in entries
                  if (e["evidence"].get("facts") or {}).get("judge", {}).get("claim") == "holds-passive")

    r = copy.deepcopy(audit)
    entry = r["equations"][judged]
    entry["verdict"] = "confirmed"
    entry["evidence"]["facts"]["judge"]["claim"] = "holds-passive"
    out.append(("counterexample relabelled confirmed, judge claim edited", r, "counterexample"))

    r = copy.deepcopy(audit)
    entry = r["equations"][judged]
    entry["verdict"] = "confirmed"
    obj = entry["evidence"]["facts"]["judge"]
    obj.update(claim="holds-passive", values=sample["values"], samples=sample["samples"])
    out.append(("relabelled confirmed, judge moved to passive points", r, "counterexample"))

    r = copy.deepcopy(audit)
    entry = r["equations"][judged]
    entry["verdict"] = "confirmed"
    entry["evidence"]["method"] = "canonical-form"
    entry["evidence"].pop("witness", None)
    obj = entry["evidence"]["facts"]["judge"]
    obj.update(claim="holds-passive", values=sample["values"], samples=sample["samples"])
    if "recheck" in entry["evidence"]["facts"]:
        out.append(("relabelled confirmed, witness removed, judge moved", r, "recheck"))

    r = copy.deepcopy(audit)
    r["equations"][judged]["evidence"]["facts"]["judge"]["claim"] = "holds-nicely"
    out.append(("unknown judge claim", r, "claim"))

    r = copy.deepcopy(audit)
    for entry in r["equations"]:
        entry["evidence"] = {"method": "canonical-form"}
        entry["verdict"] = "confirmed"
    out.append(("every certificate stripped, every verdict confirmed", r, "carries no certificate"))
    return out


def saved(report: Any) -> str:
    return json.dumps(report)
