"""How far two blind readings of the same files agree, rule by rule.

    python tools/label_agreement.py FIRST.json SECOND.json [--rules R1,R2] [--certain]

Both files map a file id to its labels ({"rule", "lines", "why", "certainty"}), as the
labellers write them. Two labels agree when they name the same rule and share a line (a
missing-comment label is the run [first, last], so two runs agree when they overlap); labels
are paired one to one (maximum matching). Prints, per rule and overall, the labels of each
reading, the pairs, and agreement = 2 * pairs / (first + second) (Dice / F1: 1.0 when both
readings deduct the same, whichever is taken as the reference). It also scores the second
reading as `real_lint.py score` scores the linter against the first (recall = pairs / first,
precision = pairs / second): what a second careful reader reaches, the ceiling to read the
linter's figures against.
"""

from __future__ import annotations

import argparse
import json
from collections import Counter


def lines_of(label: dict) -> set[int]:
    lines = label["lines"]
    if label["rule"] == "missing-comment" and len(lines) == 2:
        return set(range(lines[0], lines[1] + 1))
    return set(lines)


def pairs(a: list[dict], b: list[dict]) -> list[tuple[int, int]]:
    """A maximum one-to-one matching of labels of `a` with labels of `b` (augmenting paths)."""
    can = [
        [i for i, y in enumerate(b) if y["rule"] == x["rule"] and lines_of(x) & lines_of(y)]
        for x in a
    ]
    owner: dict[int, int] = {}

    def augment(j: int, seen: set[int]) -> bool:
        for i in can[j]:
            if i not in seen:
                seen.add(i)
                if i not in owner or augment(owner[i], seen):
                    owner[i] = j
                    return True
        return False

    for j in range(len(a)):
        augment(j, set())
    return [(j, i) for i, j in owner.items()]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("first")
    ap.add_argument("second")
    ap.add_argument("--rules", help="only these rules (comma-separated)")
    ap.add_argument("--certain", action="store_true", help="only labels marked certain")
    args = ap.parse_args()
    first, second = (json.load(open(p, encoding="utf-8")) for p in (args.first, args.second))
    rules = set(args.rules.split(",")) if args.rules else None

    def keep(label: dict) -> bool:
        if rules is not None and label["rule"] not in rules:
            return False
        return not args.certain or label.get("certainty") == "certain"

    na, nb, np_ = Counter(), Counter(), Counter()
    for fid in sorted(set(first) | set(second)):
        a = [x for x in first.get(fid, []) if keep(x)]
        b = [x for x in second.get(fid, []) if keep(x)]
        na.update(x["rule"] for x in a)
        nb.update(x["rule"] for x in b)
        np_.update(a[j]["rule"] for j, _ in pairs(a, b))
    print(
        f"{'rule':28} {'first':>6} {'second':>6} {'pairs':>6} {'agreement':>9}"
        f"   second against first: {'recall':>6} {'precision':>9}"
    )
    for rule in [*sorted(set(na) | set(nb)), "overall"]:
        x, y, p = (
            (sum(na.values()), sum(nb.values()), sum(np_.values()))
            if rule == "overall"
            else (na[rule], nb[rule], np_[rule])
        )
        agree = f"{2 * p / (x + y):.2f}" if x + y else "-"
        recall, precision = (f"{p / n:.2f}" if n else "-" for n in (x, y))
        print(f"{rule:28} {x:6d} {y:6d} {p:6d} {agree:>9}   {'':22}{recall:>6} {precision:>9}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
