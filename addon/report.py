"""Text the nodes and the sidebar show for a hull: one formatter for fl.Hydrostatics, so every
place that shows hydrostatics shows the engine's numbers the same way."""

# (label, attribute, format, unit) of the rows shown; LCB and LCF from the AP.
ROWS = (("Volume", "volume", "%.1f", "m3"), ("Displacement", "displacement", "%.1f", "t"),
        ("LCB", "lcb", "%.3f", "m"), ("VCB", "vcb", "%.3f", "m"), ("Awp", "waterplane_area", "%.1f", "m2"),
        ("LCF", "lcf", "%.3f", "m"), ("Am", "midship_area", "%.2f", "m2"), ("Wetted", "wetted_surface", "%.1f", "m2"),
        ("Cb", "cb", "%.4f", ""), ("Cp", "cp", "%.4f", ""), ("Cm", "cm", "%.4f", ""), ("Cwp", "cwp", "%.4f", ""),
        ("KMt", "kmt", "%.3f", "m"))


def rows(h):
    """[(label, text)] of an fl.Hydrostatics, in ROWS order."""
    out = []
    for label, attr, fmt, unit in ROWS:
        out.append((label, (fmt % float(getattr(h, attr))) + (" " + unit if unit else "")))
    return out


def compact(h):
    """Four lines for a node body: volume and centres, areas, coefficients. LCB also as % Lpp
    from the midship section the engine used (h.midship_x)."""
    lcb_pct = 100.0 * (h.lcb - h.midship_x) / h.length
    return ("V %.6g m3, LCB %.4g m (%+.2f %% Lpp)\nVCB %.4g m, Awp %.6g m2, LCF %.4g m\n"
            "Am %.5g m2, S %.6g m2\nCb %.4f Cp %.4f Cm %.4f Cwp %.4f") % (
        h.volume, h.lcb, lcb_pct, h.vcb, h.waterplane_area, h.lcf, h.midship_area, h.wetted_surface,
        h.cb, h.cp, h.cm, h.cwp)
