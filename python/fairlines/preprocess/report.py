"""Text table comparing the hydrostatics of the input and of the rebuilt surfaces."""

from __future__ import annotations


def comparison_table(report) -> str:
    """Text table: input, surface, mesh of the surface, published, for the main particulars."""
    h = report["hydrostatics"]
    pub = report.get("published", {})
    rows = [("volume", "volume", "m3", "{:.6g}"), ("LCB % Lpp fwd of midship", "lcb_pct", "%", "{:+.3f}"),
            ("Cb", "cb", "", "{:.4f}"), ("Cp", "cp", "", "{:.4f}"), ("Cm", "cm", "", "{:.4f}"),
            ("Cwp", "cwp", "", "{:.4f}"), ("wetted surface (no deck)", "wetted_surface", "m2", "{:.6g}")]
    lines = [f"{'':28s}{'input':>12s}{'surface':>12s}{'mesh':>12s}{'published':>12s}"]
    for label, key, _, fmt in rows:
        def cell(d):
            v = d.get(key) if d else None
            return f"{fmt.format(v):>12s}" if v is not None else f"{'-':>12s}"
        lines.append(f"{label:28s}" + cell(h["input"]) + cell(h["surface"]) + cell(h["surface_mesh"]) + cell(pub))
    d = report["deviation"]
    if d:
        m = d["max_at"]
        lines.append(f"deviation of the surface from {d['n_points']} input points: max {d['max']:.4g} m at "
                     f"({m['x']:.4g}, {m['y']:.4g}, {m['z']:.4g}) [{m['block']}], RMS {d['rms']:.4g} m "
                     f"= {d['rms_pct_B']:.4f} % of B")
    return "\n".join(lines)
