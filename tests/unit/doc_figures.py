#!/usr/bin/env python3
"""The figures of docs/accuracy.md's trade-off table come from one measured source,
docs/accuracy-summary.csv (written by `vkraycast tradeoff`, tools/tradeoff.sh): every row
of the table must be a row of the CSV, to the digits the table shows, and every CSV row
must be in the table. And docs/accuracy.csv (the per-point rows) must add up to the
summary. A page edited by hand, or a CSV refreshed without its page, fails here.

Usage: doc_figures.py SOURCE_DIR
"""
import csv
import math
import re
import sys


def close(shown, value):
    """`shown` is `value` as the table prints it (%.1f, %.4g, %.3g, %.2f)."""
    if value is None or math.isnan(value):
        return False
    if shown == value:
        return True
    digits = shown.replace("-", "").lstrip("0.").replace(".", "")
    # Half a unit of the last digit shown.
    decimals = len(shown.split(".")[1]) if "." in shown else 0
    if "e" not in shown:
        return abs(float(shown) - value) <= 0.5 * 10 ** -decimals + 1e-12
    return math.isclose(float(shown), value, rel_tol=10 ** -(len(digits) - 1))


def number(text):
    return float("nan") if text == "" else float(text)


def main(root):
    problems = []
    checks = 0
    with open(f"{root}/docs/accuracy-summary.csv") as f:
        summary = {(r["variant"], r["spp"]): r for r in csv.DictReader(f)}
    with open(f"{root}/docs/accuracy.csv") as f:
        points = list(csv.DictReader(f))
    page = open(f"{root}/docs/accuracy.md").read()
    rows = re.findall(r"^\| ([a-z0-9-]+) \| (\d+) \| ([\d.]+) \| ([\d.e-]+) \(([\d.e-]+) / ([\d.e-]+) / ([\d.e-]+)\) \| "
                      r"([\d.]+|exact) \| (yes)? \|$", page, re.M)
    if not rows:
        problems.append("docs/accuracy.md has no trade-off table rows")
    seen = set()
    for variant, spp, ms, mismatch, hit, obj, shadow, psnr, _ in rows:
        r = summary.get((variant, spp))
        if r is None:
            problems.append(f"table row {variant} {spp} spp is not in accuracy-summary.csv")
            continue
        seen.add((variant, spp))
        pairs = [("time", ms, number(r["render_ms_sum"])), ("mismatch", mismatch, number(r["decision_mismatch_pct_mean"])),
                 ("hit", hit, number(r["hit_mismatch_pct_mean"])), ("object", obj, number(r["object_mismatch_pct_mean"])),
                 ("shadow", shadow, number(r["shadow_mismatch_pct_mean"]))]
        if psnr != "exact":
            pairs.append(("PSNR", psnr, number(r["psnr_db_of_mean_mse"])))
        for what, shown, value in pairs:
            checks += 1
            if not close(shown, value):
                problems.append(f"{variant} {spp} spp: the table says {what} {shown}, the CSV {value}")
    for key in summary:
        if key not in seen:
            problems.append(f"accuracy-summary.csv row {key} is not in the table")
    # The summary is the per-point rows added up: times summed, shares averaged.
    for (variant, spp), r in summary.items():
        mine = [p for p in points if p["variant"] == variant and p["spp"] == spp and p["status"] == "ok"]
        if not mine:
            problems.append(f"accuracy.csv has no measured point for {variant} {spp} spp")
            continue
        checks += 2
        total = sum(float(p["render_ms"]) for p in mine)
        mean = sum(float(p["decision_mismatch_pct"]) for p in mine) / len(mine)
        if not math.isclose(total, float(r["render_ms_sum"]), rel_tol=1e-6):
            problems.append(f"{variant} {spp} spp: points sum to {total} ms, the summary says {r['render_ms_sum']}")
        if not math.isclose(mean, float(r["decision_mismatch_pct_mean"]), rel_tol=1e-6, abs_tol=1e-12):
            problems.append(f"{variant} {spp} spp: points average {mean} %, the summary says "
                            f"{r['decision_mismatch_pct_mean']}")
    for p in problems:
        print("FAIL:", p)
    print(f"{max(checks - len(problems), 0)} passed, {len(problems)} failed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
