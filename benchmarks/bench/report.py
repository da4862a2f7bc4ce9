"""The suite's tables, as Markdown, in the form of the paper's: per scene, every method's relMSE at
equal samples and at equal time, its gains over the two baselines, and its time per sample."""


def ratio(base, value):
    return f"{base / value:.2f}x" if base and value and value > 0 else "-"


def scene_table(rows, methods):
    lines = ["| method | relMSE, equal spp | gain vs pt-uniform | gain vs pt-power | relMSE, equal time | spp reached "
             "| equal-time gain vs pt-uniform | equal-time gain vs pt-power | ms per sample | time overhead vs pt-uniform |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    uni, pow_ = rows.get("pt-uniform", {}), rows.get("pt-power", {})
    for m in methods:
        r = rows[m]
        overhead = (r["ms_per_sample"] / uni["ms_per_sample"] - 1.0) * 100.0 if uni else 0.0
        lines.append(f"| {m} | {r['relmse_spp']:.4g} | {ratio(uni.get('relmse_spp'), r['relmse_spp'])} | "
                     f"{ratio(pow_.get('relmse_spp'), r['relmse_spp'])} | {r['relmse_time']:.4g} | {r['spp_time']:.0f} | "
                     f"{ratio(uni.get('relmse_time'), r['relmse_time'])} | {ratio(pow_.get('relmse_time'), r['relmse_time'])} | "
                     f"{r['ms_per_sample']:.1f} | {overhead:+.0f} % |")
    return "\n".join(lines)


def summary_table(results, methods):
    """One line per scene: the equal-time winner and cms's three numbers of the paper's table."""
    lines = ["| scene | cms gain, equal spp (vs pt-uniform / pt-power) | cms gain, equal time (vs pt-uniform / pt-power) "
             "| cms time overhead | fastest to a given error (equal time) | runner-up |",
             "|---|---|---|---|---|---|"]
    for scene, result in results.items():
        rows = result["rows"]
        if "cms" not in rows:
            continue
        c, u, p = rows["cms"], rows.get("pt-uniform", {}), rows.get("pt-power", {})
        ranked = sorted((m for m in methods if m in rows), key=lambda m: rows[m]["relmse_time"])
        overhead = (c["ms_per_sample"] / u["ms_per_sample"] - 1.0) * 100.0 if u else 0.0
        lines.append(f"| {scene} | {ratio(u.get('relmse_spp'), c['relmse_spp'])} / {ratio(p.get('relmse_spp'), c['relmse_spp'])} | "
                     f"{ratio(u.get('relmse_time'), c['relmse_time'])} / {ratio(p.get('relmse_time'), c['relmse_time'])} | "
                     f"{overhead:+.0f} % | {ranked[0]} | {ranked[1] if len(ranked) > 1 else '-'} |")
    return "\n".join(lines)


def breakdown_table(breakdown, groups):
    lines = ["| method | " + " | ".join(groups) + " | total |", "|---|" + "---|" * (len(groups) + 1)]
    for m, b in breakdown.items():
        lines.append(f"| {m} | " + " | ".join(f"{b.get(g, 0.0):.2f}" for g in groups) + f" | {sum(b.values()):.2f} |")
    return "\n".join(lines)


def knob_table(knob):
    """One knob's settings. Where each setting has its own reference (max depth), errors of
    different settings do not compare: the table shows cms's gain over pt-uniform instead of a best."""
    points = knob["points"]
    by_gain = any("gain_vs_pt_uniform" in p for p in points)
    last = "cms gain over pt-uniform (same depth)" if by_gain else "relMSE x time (lower is better)"
    lines = [f"| {knob['flag']} | relMSE | ms per sample | {last} |", "|---|---|---|---|"]
    best = None if by_gain else min(points, key=lambda p: p["relmse"] * p["ms_per_sample"])
    for p in points:
        mark = " (best)" if p is best else ""
        value = f"{p['gain_vs_pt_uniform']:.2f}x" if by_gain else f"{p['relmse'] * p['ms_per_sample']:.4g}"
        lines.append(f"| {p['value']}{mark} | {p['relmse']:.4g} | {p['ms_per_sample']:.1f} | {value} |")
    return "\n".join(lines)
