"""Paper Table 2: the devices' physical values, recomputed (μ, β, σ) and the printed ones.

Run: python examples/table2_devices.py [--out DIR]
"""

import os

import dfa
from dfa.formatting import markdown_table, number


def _per_stiffness(dev) -> tuple[list[str], str]:
    """(μ, β, σ) cells of a device the paper gives no single K for: each is a constant over K (Table 1), and the
    disagreement cell says why nothing is compared."""
    k_unit = dev.units["stiffness"]
    cells = [
        f"{number(c, 4)}/K" for c in (dev.mass / dev.period**2, dev.damping / dev.period, dev.coulomb / dev.resolution)
    ]
    note = f"nothing printed to compare: the paper varies K (cells: K in {k_unit})"
    return cells, note


def main(out: str, quick: bool = False) -> dict:
    rows = []
    for e in dfa.catalogue():
        p = e.params
        pr = dict(e.printed)
        rows.append(
            dict(
                name=e.name,
                mu=p.mu if p else None,
                beta=p.beta if p else None,
                sigma=p.sigma if p else None,
                printed=pr,
                discrepancies=[str(d) for d in e.discrepancies],
                incomplete=e.incomplete,
            )
        )
    body = []
    for e, r in zip(dfa.catalogue(), rows, strict=True):
        printed = ", ".join(r["printed"].get(k, "–") for k in ("mu", "beta", "sigma")) if r["printed"] else "–"
        note = "; ".join(r["discrepancies"]) or ("incomplete row" if r["incomplete"] else "none")
        cells = [number(r["mu"], 5), number(r["beta"], 3), number(r["sigma"])]
        if e.params is None and not e.incomplete and e.stiffness is None:  # known device, no single K (the RE35)
            cells, note = _per_stiffness(e.device)
        body.append([r["name"], *cells, printed, note])
    head = ["device", "μ", "β", "σ", "printed μ, β, σ", "disagreement"]
    table = markdown_table(head, body, align="lrrrll")
    with open(os.path.join(out, "table2_devices.md"), "w", encoding="utf-8") as fh:
        fh.write(table + "\n")
    print(table)
    return dict(rows=rows, table=table)


if __name__ == "__main__":
    from _common import parse

    a = parse(__doc__)
    main(a.out, a.quick)
