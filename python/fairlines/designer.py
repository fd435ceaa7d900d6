"""A complete, fair first-draft hull from principal particulars, the way a designer starts a ship.

``fl.design_hull(lpp=..., breadth=..., draft=..., depth=..., cb=..., lcb=...)`` returns a
:class:`fairlines.Hull` whose description (every value editable) meets the volume Cb Lpp B T,
the LCB and the waterplane area Cwp Lpp B on the built surface. Optional particulars take
textbook defaults when left out (each named in the description's notes):

* Cm from Kerlen's regression, Cm = 1.006 - 0.0056 Cb^-3.56;
* Cwp = sqrt(Cb) + 0.01 (a vertical prismatic coefficient Cb / Cwp of 0.70 at Cb 0.5 to 0.92
  at Cb 0.87, inside what fair sections hold);
* the LCF 1 % Lpp aft of the LCB;
* a parallel middle body of (Cp - 0.62) x 1.3 Lpp (none below Cp 0.62) about the LCB;
* a transom stern (dry above Cb 0.6, immersed below), a stem raked 20 deg above the DWL.

The particulars become basic curves (fairlines.description) and the hull is built; the SAC's
volume and LCB and the DWL's area are then corrected by what the skinned surface holds (two or
three rebuilds), so the surface meets the request to about 1e-6.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from . import _native
from .hull import Hull

__all__ = ["Particulars", "design_hull", "design_description", "match_targets"]

# Ranges the designer is built and tested for; values outside are refused with the range named.
RANGES = {"cb": (0.45, 0.9), "lcb_pct": (-5.0, 5.0), "l_over_b": (3.5, 10.0), "b_over_t": (1.8, 5.0)}
STEM_RAKE = 20.0          # stem rake above the DWL, deg from the vertical
TRANSOM_AFT = 0.02        # transom aft of the AP, fraction of Lpp
LCF_AFT_OF_LCB = 0.01     # default LCF aft of the LCB, fraction of Lpp
COUNTER_ANGLE = 12.0      # rise of the counter at the transom, deg from the horizontal
FLARE_STEM = 0.4          # flare at the stem head, fraction of the top's lean
FLARE_TRANSOM = 0.2       # flare at the transom
CONVEX_FRACTION = 0.15    # least curvature of the DWL's entrance / run, fraction of a parabola's
FULLNESS_END = 0.7        # section fullness at the waterline's ends the coordination starts from
FULLNESS_POINTS = 41      # points of the fullness the SAC stays near
COORDINATION_ITERATIONS = 12
COORDINATION_TOL = 1e-6
MATCH_TOL = 1e-6          # relative tolerance of volume, LCB (on Lpp) and waterplane area on the surface
MATCH_ITERATIONS = 4


@dataclass
class Particulars:
    """Principal particulars of a new ship (metres; lcb and lcf from the AP)."""

    lpp: float
    breadth: float
    draft: float
    depth: float
    cb: float
    lcb: float
    cm: float | None = None
    cwp: float | None = None
    lcf: float | None = None
    parallel_length: float | None = None
    stern: str = "transom"
    transom_immersion: float | None = None  # transom lower edge below the DWL (m); < 0 dry
    bulb: bool | dict = False
    name: str = "designed hull"
    notes: list[str] = field(default_factory=list)

    def check(self) -> None:
        for key in ("lpp", "breadth", "draft", "depth", "cb", "lcb"):
            v = getattr(self, key)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise _native.InvalidInput(f"{key} is {v!r}; expected a finite number")
        if not 1.0 <= self.lpp <= 600.0:
            raise _native.InvalidInput(f"lpp is {self.lpp}; expected 1 to 600 m" + (" (millimetres?)" if self.lpp > 1000 else ""))
        if not 0 < self.draft < self.depth:
            raise _native.InvalidInput(f"draft is {self.draft}; expected 0 < T < D = {self.depth} m")
        checks = {"cb": self.cb, "lcb_pct": 100 * (self.lcb - self.lpp / 2) / self.lpp,
                  "l_over_b": self.lpp / self.breadth, "b_over_t": self.breadth / self.draft}
        for key, v in checks.items():
            lo, hi = RANGES[key]
            if not lo <= v <= hi:
                raise _native.InvalidInput(f"{key} is {v:.4g}; expected {lo} to {hi} (the designer's range)")
        if self.stern not in ("transom", "cruiser"):
            raise _native.InvalidInput(f"stern is {self.stern!r}; expected 'transom' or 'cruiser'")


def _coefficients(p: Particulars) -> dict:
    """Coefficients and lengths the particulars leave open."""
    L = p.lpp
    cm = min(p.cm if p.cm is not None else 1.006 - 0.0056 * p.cb ** -3.56, 0.995)
    cp = p.cb / cm
    cwp = p.cwp if p.cwp is not None else min(math.sqrt(p.cb) + 0.01, 0.97)
    lcf = p.lcf if p.lcf is not None else p.lcb - LCF_AFT_OF_LCB * L
    lp = p.parallel_length if p.parallel_length is not None else max(0.0, (cp - 0.62) * 1.3 * L)
    xc = L / 2 + (p.lcb - L / 2)
    imm = p.transom_immersion if p.transom_immersion is not None else (-0.06 * p.draft if p.cb >= 0.6 else 0.12 * p.draft)
    fine = min(1.0, max(0.0, (0.85 - p.cb) / 0.35))  # 0 full, 1 fine
    return {"cm": cm, "cp": cp, "cwp": cwp, "lcf": lcf, "fine": fine, "parallel": (xc - lp / 2, xc + lp / 2),
            "transom_z": p.depth if p.stern == "cruiser" else p.draft - imm}


def _ends(p: Particulars) -> tuple[float, float]:
    return -TRANSOM_AFT * p.lpp, p.lpp + (p.depth - p.draft) * math.tan(math.radians(STEM_RAKE))


def _profile(p: Particulars, c: dict, x_aft: float, x_fore: float) -> dict:
    """Keel on the baseline, rising aft to the transom's lower edge (or the cruiser stern's end
    at the deck) and forward through the forefoot to T at the FP and on up the raked stem."""
    L, T, D = p.lpp, p.draft, p.depth
    keel_aft = min(x_aft + (0.12 + 0.10 * c["fine"]) * L, c["parallel"][0])
    keel_fore = max(L - (0.03 + 0.07 * c["fine"]) * L, c["parallel"][1])
    slope_aft = -math.tan(math.radians(COUNTER_ANGLE if p.stern == "transom" else 60.0))
    return {"flat_from": keel_aft, "flat_to": keel_fore, "value": 0.0, "yB": c["transom_z"], "slopeB": slope_aft,
            "yE": D, "slopeE": 1.0 / math.tan(math.radians(STEM_RAKE)), "points": [[L, T]], "monotone": True,
            "spans": 24}


def _smoothstep(r):
    r = np.clip(r, 0.0, 1.0)
    return r * r * r * (10.0 - 15.0 * r + 6.0 * r * r)


def fullness_target(x, par: tuple[float, float], xa: float, xf: float, cm: float, s_aft: float, s_fore: float) -> np.ndarray:
    """The section fullness a designed hull keeps near: Cm over the parallel body, passing
    smoothly to s_aft / s_fore at the waterline's ends."""
    x = np.asarray(x, dtype=float)
    out = np.full(x.shape, cm)
    fore, aft = x > par[1], x < par[0]
    out[fore] = cm + (s_fore - cm) * _smoothstep((x[fore] - par[1]) / max(xf - par[1], 1e-9))
    out[aft] = cm + (s_aft - cm) * _smoothstep((par[0] - x[aft]) / max(par[0] - xa, 1e-9))
    return out


class _Coordinator:
    """Finds the waterplane (Cwp, LCF) and the end fullness that let sections of natural
    fullness carry the volume at the LCB: V = int 2 y_dwl (T - z_keel) s dx with s the
    fullness target, and its centroid the LCB. Two of {LCF, Cwp, fullness at the ends} are
    solved for (those the particulars leave open) by Newton's method on a finite-difference
    Jacobian; each evaluation designs the DWL once."""

    def __init__(self, p: Particulars, c: dict, prof_spec: dict, ends: tuple[float, float], dwl_base: dict):
        from .basic_curves import immersed_range, solve_curve
        from .description import BasicCurveSpec

        self.p, self.c, self.dwl_base = p, c, dwl_base
        self._solve, self._spec = solve_curve, BasicCurveSpec
        self.profile = solve_curve("profile", BasicCurveSpec.from_dict("profile", prof_spec, "profile"), ends[0], ends[1],
                                   lower=-p.draft, upper=p.depth, maximum=False)
        self.xa, self.xf = immersed_range(self.profile, p.draft)
        g = np.polynomial.legendre.leggauss(8)
        br = np.linspace(self.xa, self.xf, 121)
        a, b = br[:-1, None], br[1:, None]
        self.x = (0.5 * (a + b) + 0.5 * (b - a) * g[0]).ravel()
        self.w = (0.5 * (b - a) * g[1]).ravel()
        self.depth = p.draft - self.profile(self.x)

    def moments(self, lcf: float, cwp: float, s_aft: float, s_fore: float) -> tuple[float, float]:
        p, c = self.p, self.c
        spec = dict(self.dwl_base, lcf=lcf, waterplane_area=cwp * p.lpp * p.breadth)
        dwl = self._solve("dwl", self._spec.from_dict("dwl", spec, "basic_curves.dwl"), self.xa, self.xf, lower=0.0, upper=p.breadth / 2)
        s = fullness_target(self.x, c["parallel"], self.xa, self.xf, c["cm"], s_aft, s_fore)
        area = 2.0 * dwl(self.x) * self.depth * s
        v = float(np.sum(self.w * area))
        return v, float(np.sum(self.w * self.x * area)) / v

    def solve(self, lcf: float, cwp: float, s_end: float) -> dict:
        p = self.p
        fixed_cwp, fixed_lcf = p.cwp is not None, p.lcf is not None
        if not fixed_lcf and not fixed_cwp:
            names, u = ("lcf", "cwp"), np.array([lcf, cwp])
        elif fixed_cwp and not fixed_lcf:
            names, u = ("lcf", "s"), np.array([lcf, s_end])
        elif fixed_lcf and not fixed_cwp:
            names, u = ("cwp", "d"), np.array([cwp, 0.0])
        else:
            names, u = ("s_aft", "s_fore"), np.array([s_end, s_end])
        v_want = p.cb * p.lpp * p.breadth * p.draft

        def unpack(u):
            k = dict(lcf=lcf, cwp=cwp, s_aft=s_end, s_fore=s_end)
            for n_, v in zip(names, u):
                if n_ == "s":
                    k["s_aft"] = k["s_fore"] = v
                elif n_ == "d":
                    k["s_aft"], k["s_fore"] = s_end - v, s_end + v
                else:
                    k[n_] = v
            return k

        def residual(u):
            v, lcb = self.moments(**unpack(u))
            return np.array([(v - v_want) / v_want, (lcb - p.lcb) / p.lpp])

        steps = np.array([1e-3 * p.lpp if n_ in ("lcf",) else 1e-3 for n_ in names])
        for _ in range(COORDINATION_ITERATIONS):
            r = residual(u)
            if np.max(np.abs(r)) < COORDINATION_TOL:
                break
            J = np.column_stack([(residual(u + np.eye(2)[k] * steps[k]) - r) / steps[k] for k in range(2)])
            du = np.linalg.lstsq(J, -r, rcond=None)[0]
            u = u + np.clip(du, -20 * steps, 20 * steps)
        return unpack(u)


def design_description(p: Particulars) -> dict:
    """The hull description (a dict) for the particulars (see the module docstring)."""
    p.check()
    c = _coefficients(p)
    L, B, T, D = p.lpp, p.breadth, p.draft, p.depth
    half = B / 2
    x_aft, x_fore = _ends(p)
    prof = _profile(p, c, x_aft, x_fore)
    par = c["parallel"]
    dwl = {"flat_from": par[0], "flat_to": par[1], "value": half, "yE": 0.0, "monotone": True, "spans": 20}
    dwl["yB"] = (0.75 if c["transom_z"] < T else 0.55) * half if p.stern == "transom" else 0.0
    # Waterlines that bulge outward all along the entrance (a definite curvature, a fraction of
    # a parabola's), so no stretch is left straight enough to wobble.
    entrance = L - par[1]
    dwl["convex"] = [[par[1] + 0.1 * entrance, L, CONVEX_FRACTION * B / entrance**2]]
    coord = _Coordinator(p, c, prof, (x_aft, x_fore), dwl)
    k = coord.solve(c["lcf"], c["cwp"], FULLNESS_END)
    dwl.update(lcf=k["lcf"], waterplane_area=k["cwp"] * L * B)
    xs = np.linspace(coord.xa, coord.xf, FULLNESS_POINTS)
    target = fullness_target(xs, par, coord.xa, coord.xf, c["cm"], k["s_aft"], k["s_fore"])
    sac = {"flat_from": par[0], "flat_to": par[1], "value": c["cm"] * B * T, "volume": p.cb * L * B * T, "lcb": p.lcb,
           "spans": 20, "fullness_fit": [[float(x), float(s)] for x, s in zip(xs, target) if not par[0] <= x <= par[1]]}
    deck_from = max(x_aft + 0.05 * L, par[0] - 0.2 * L)
    deck_to = par[1] + 0.35 * (L - par[1])
    deck = {"flat_from": deck_from, "flat_to": deck_to, "value": half, "yB": 0.92 * half if p.stern == "transom" else 0.0,
            "yE": 0.0, "alphaE": -70.0, "monotone": True, "spans": 20}
    flare = {"flat_from": deck_from, "flat_to": deck_to, "value": 0.0, "yB": FLARE_TRANSOM, "yE": FLARE_STEM,
             "monotone": True, "spans": 12}
    return {
        "name": p.name,
        "notes": "; ".join(p.notes + [f"designed from particulars: Cm {c['cm']:.4f}, Cp {c['cp']:.4f}, Cwp {k['cwp']:.4f}, "
                                      f"LCF {k['lcf']:.3f} m, end fullness {k['s_aft']:.3f} aft / {k['s_fore']:.3f} fore"]),
        "principal": {"Lpp": L, "B": B, "T": T, "D": D},
        "ends": {"aft": x_aft, "fore": x_fore},
        "stations": {"count": 61},
        "sections": {"n_control": 20},
        "basic_curves": {"profile": prof, "dwl": dwl, "deck": deck, "sac": sac, "flare": flare},
        "design": {k_: v for k_, v in asdict(p).items() if k_ != "notes"},
    }


def design_hull(particulars: Particulars | None = None, **kwargs) -> Hull:
    """A Hull designed from particulars (a Particulars, or its fields as keywords), built and
    matched: its surface holds Cb Lpp B T, the LCB and Cwp Lpp B (see the module docstring)."""
    p = particulars if particulars is not None else Particulars(**kwargs)
    hull = Hull.from_json(design_description(p))
    match_targets(hull)
    return hull


def match_targets(hull: Hull) -> None:
    """Correct the SAC volume and LCB and the DWL area by what the surface holds (rebuilds)."""
    d = hull.description
    pr = d.principal
    sac, dwl = d.curves["sac"], d.curves["dwl"]
    want_v, want_lcb = sac.aliases.get("volume"), sac.aliases.get("lcb")
    want_awp = dwl.aliases.get("waterplane_area")
    for _ in range(MATCH_ITERATIONS):
        h = hull.hydrostatics()
        err_v = (h.volume - want_v) / want_v if want_v else 0.0
        err_lcb = (h.lcb - want_lcb) / pr.lpp if want_lcb is not None else 0.0
        err_awp = (h.waterplane_area - want_awp) / want_awp if want_awp else 0.0
        if max(abs(err_v), abs(err_lcb), abs(err_awp)) <= MATCH_TOL:
            return
        if want_v:
            sac.aliases["volume"] *= want_v / h.volume
        if want_lcb is not None:
            sac.aliases["lcb"] += want_lcb - h.lcb
        if want_awp:
            dwl.aliases["waterplane_area"] *= want_awp / h.waterplane_area
        hull._invalidate()
