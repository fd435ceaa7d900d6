"""A complete, fair first-draft hull from principal particulars, the way a designer starts a ship.

``fl.design_hull(lpp=..., breadth=..., draft=..., depth=..., cb=..., lcb=...)`` returns a
:class:`fairlines.Hull` whose description (every value editable) meets the volume Cb Lpp B T,
the LCB and the waterplane area Cwp Lpp B on the built surface. Optional particulars take
textbook defaults when left out (each named in the description's notes):

* Cm from Kerlen's regression, Cm = 1.006 - 0.0056 Cb^-3.56 (at most CM_MAX);
* Cwp = sqrt(Cb) + 0.01 (a vertical prismatic coefficient Cb / Cwp of 0.70 at Cb 0.5 to 0.92
  at Cb 0.87), 0.015 fuller when a full ship's ends cannot hold its LCB with it;
* the LCF 1.5 % Lpp aft of the LCB;
* a parallel middle body of 1.6 (Cp - 0.62) Lpp (none below Cp 0.62), centred a little
  forward of the LCB's offset from midships;
* a transom stern 2.5 % Lpp aft of the AP, its lower edge 5 % of T above the waterline above
  Cb 0.6 (dry) and 12 % of T below it otherwise, an immersed one 0.7 B/2 wide at the waterline,
  narrowed in steps of 0.1 B/2 (to 0.2 B/2) until the waterline is convex from the transom to its
  widest, else the widest with which it widens all the way (and to 0.5 B/2 when a fine ship's
  ends cannot hold its LCB with the wider one),
  upright unless transom_rake is given (deg, the top aft; ends.transom_rake); a stem raked
  20 deg above the waterline;
* the keel rising aft from its flat over 0.9 of Holtrop and Mennen's run (over 0.4, then 0.25
  of it when a full body's ends cannot hold its volume under a fine waterplane);
* a flat of bottom (a straight floor from the keel) of FLAT_BOTTOM_DEFAULT of the waterline's
  half-breadth over the parallel body (at midships without one); none on a hull where any
  section would be too fine to hold it whole (the notes say so);
* with bulb=True, a bulb of the engine's default Kracht coefficients (the lateral area fitted to
  the ship), made smaller (BULB_SCALE_RETRIES, the notes say how much) where no aft length lets
  it meet a fine ship's short entrance in one seam.

The particulars become basic curves (fairlines.description): the centre profile, the design
waterline with Cwp and the LCF, the deck line, and the sectional area curve with the volume and
LCB, kept near a natural section fullness (Cm over the parallel body, falling toward the ends
by the two amounts that give the volume and the LCB; without a parallel body, left free within
SAC_FREE_NEAR_PEAK Lpp of where the waterline is at B/2). The hull is built, and the SAC's volume
and LCB and the waterline's area are corrected by what the skinned surface holds (a rebuild
or two), so the surface meets the request to MATCH_TOL; with a bulb by what the ship holds,
the bare hull plus the bulb and blend's share measured on the composed hull, so the composed
ship meets the volume and LCB to MATCH_TOL_BULB (the bare hull's SAC then holds less).
"""

from __future__ import annotations

import copy
import json
import math
from dataclasses import asdict, dataclass, field, replace
from functools import lru_cache

import numpy as np

from . import _native
from ._options import fill_options
from .basic_curves import immersed_range, solve_curve, tersely
from .bulb import KRACHT_NAMES
from .description import TRANSOM_RAKE_RANGE, BasicCurveSpec, HullDescription
from .hull import FLAT_BOTTOM_BOUNDS, Hull

__all__ = ["Particulars", "design_hull", "design_description", "match_targets", "RANGES"]

#: Ranges the designer is built and tested for; values outside are refused with the range named.
RANGES = {"cb": (0.45, 0.9), "lcb_pct": (-5.0, 5.0), "l_over_b": (3.5, 10.0), "b_over_t": (1.8, 5.0)}
STEM_RAKE = 20.0            # stem rake above the waterline, deg from the vertical
TRANSOM_AFT = 0.025         # transom aft of the AP, fraction of Lpp
LCF_AFT_OF_LCB = 0.015      # default LCF aft of the LCB, fraction of Lpp
COUNTER_ANGLE = 12.0        # rise of the counter at the transom, deg from the horizontal
TRANSOM_FULL_CB = 0.6       # the transom's lower edge TRANSOM_IMMERSION_FULL of T below the waterline
TRANSOM_IMMERSION_FULL = -0.05  # from this Cb (< 0: above it, a dry transom), TRANSOM_IMMERSION_FINE below it
TRANSOM_IMMERSION_FINE = 0.12
# A flat of bottom by default: without one the two halves of the run meet at the keel at the
# floor's angle (section splines arriving 17 / 10 / 4 deg at 0.18 / 0.25 / 0.33 Lpp on the
# container ship), a crease zebra stripes break at; this much flattens it (3 / 0.3 / 0 deg).
FLAT_BOTTOM_DEFAULT = 0.15
FLAT_KEPT_TOL = 1e-6        # a section keeping less of its flat than 1 - this narrowed it
FLAT_BOTTOM_AFT = 0.7       # a flat of bottom starts this share of the keel's rise aft of the keel's flat
FLAT_BOTTOM_FADE = 0.05     # ... and fades out at least this fraction of Lpp forward of its full part
# The keel rises over this fraction of the run (Holtrop and Mennen's L_R). Over 0.65 of it the keel
# reached the base well before the sections' bilges filled, and the lowest waterlines grew, slowed
# where the keel landed and grew again (a hollow of 21 deg on average in the 0.06 T waterline's aft
# half over bench_fairness_space's hulls 0-99; 13.8 deg at 0.9).
KEEL_RISE = 0.9
MIN_KEEL_RISE, MAX_KEEL_RISE = 0.06, 0.3  # ... kept within these fractions of Lpp
# A ship whose ends cannot hold its volume (a full body under a fine waterplane, Cb / Cwp over
# about 0.92) is tried again with the keel rising over less of the run: its flat runs further
# aft and the run's sections get deeper boxes. Tried last, so no design that builds changes.
KEEL_RISE_RETRIES = (0.4, 0.25)
PARALLEL_SLOPE = 1.6        # parallel body length / Lpp per unit Cp above PARALLEL_CP
PARALLEL_CP = 0.62
CM_MAX = 0.99              # the fullest midship section the regression gives (fuller ones leave the SAC no room)
PARALLEL_RETRIES, PARALLEL_STEP = 3, 0.05  # a SAC the ends cannot hold: parallel body + 5 % Lpp, 3 times
EDGE_STEPS = 7              # bisections of a given particular toward one that builds (1/128 of the gap)
TYPICAL_DEPTH = 1.6         # D / T a deeper hull's refusal tries: its sections' knot spans below the waterline are
                            # fewer, and a full ship's (Cm 0.99) cannot hold its near-box sections there
FINE_ENDS_CP = 0.45         # ends finer than this (prismatic outside the parallel body) ask for a shorter one
CWP_MAX = 0.97              # the fullest default waterplane
CWP_RETRY = 0.015           # a full ship's ends cannot hold its LCB: the default Cwp this much fuller
LCF_RETRIES = (0.0, 0.015, -0.03)  # LCF - LCB (fraction of Lpp) tried when the default LCF leaves the SAC no room
PARALLEL_SPAN = (0.2, 0.8)  # the default parallel body lies within these fractions of Lpp ...
PARALLEL_SPAN_GIVEN = (0.15, 0.9)  # ... one placed by its centre within these
PARALLEL_SHIFT_RETRY = 3.0  # a SAC the ends cannot hold: the parallel body's centre moves this many times the LCB's offset
PARALLEL_SHIFT = 1.5        # the parallel body's centre moves this many times the LCB's offset
DECK_CLEAR = 0.97           # the deck stays flat aft at least to where the waterline narrows to this fraction of B/2 ...
DECK_FROM_MIN = 0.02        # ... but starts it at least this fraction of Lpp forward of the stern
DECK_FLAT_CHECKS = 101      # points of that check
DECK_FLARE_END = 0.12       # forward, the deck's flare over the waterline (fraction of B/2) where the waterline ends ...
DECK_FOLLOW_TO = 0.7        # ... followed to where the waterline narrows to this fraction of B/2 (the stem head is free)
DECK_FLARE_POINTS = 40      # fit points of the forward deck over the waterline's forward run
# ... the share followed rising as this power of the smoothstep (1: the smoothstep): a flare growing
# as fast as the waterline narrows at the forward shoulder leaves the topside just above T straight
# along the bilge's lean, and the outer buttocks turn back there, 1-6 deg at 1.0-1.1 T. A deck this close
# to the waterline needs the sections' top corner held inside its edge (sections.cpp inside_deck_edge), or
# the bow's frames tumble home (up to 2 % B/2 before).
DECK_FOLLOW_POWER = 0.4
DECK_TRANSOM = 0.92         # deck half-breadth at the transom, fraction of B/2 ...
# ... but over a dry transom (the waterline closing on the centre plane forward of it) no wider
# than the sections near the waterline's end lean: a section of the wedge's fullness leans b / d
# (half-breadth over immersed depth) up to T, and a topside flaring more than that to the deck is
# hollow above T, an S. So the deck at the transom is at most (1 - DRY_TRANSOM_LEAN_MARGIN) of
# the least b + (D - T) b / d over DRY_TRANSOM_LEAN_REACH (fractions of Lpp forward of the
# waterline's end, DRY_TRANSOM_LEAN_POINTS of them), and at least DRY_TRANSOM_DECK_LEAST B/2.
# bench_fairness_space's first reading, hulls 0-199 / 200-399: every mark 85 / 71 -> 86 / 78 of
# 200, with the frames aft of 5 % Lpp too 65 / 53 -> 80 / 63, S frames at 5-95 % Lpp 30 -> 19 /
# 48 -> 32 hulls, buttocks over two sign changes 48 / 58 -> 51 / 63. With no least the deck
# narrowed to 0.51 B/2 and the buttocks at 0.5-0.9 B/2 took lobes of 0.3-0.4 deg at 1.1-1.4 T
# (every mark 82, with the aft frames 82, on hulls 0-199); 0.8: 89 / 81, with the aft frames 74 /
# 62, but the tanker's aft frames kept an S of 0.3-0.4 deg. A margin of 0.1 left it 0.2-0.3 deg.
DRY_TRANSOM_LEAN_MARGIN = 0.15
DRY_TRANSOM_DECK_LEAST = 0.75
DRY_TRANSOM_LEAN_REACH = (0.002, 0.03)
DRY_TRANSOM_LEAN_POINTS = 15
TRANSOM_FLARE = 20.0        # ... at an immersed transom at most this far (deg) outboard of its waterline over the freeboard
DECK_FLAT_TOL = 1e-3        # ... the deck over it flat from where it comes within this fraction of B/2
DWL_TRANSOM = 0.7           # waterline half-breadth at an immersed transom, fraction of B/2 ...
TRANSOM_WIDTHS = (DWL_TRANSOM, 0.6, 0.5, 0.4, 0.3, 0.2)  # ... narrowed through these until the run is convex to the peak
MONOTONE_CHECKS = 101       # points of that check
MONOTONE_TOL = 1e-6         # narrowing by less than this fraction of B/2 counts as widening
RUN_HOLLOW_TOL = 1e-4       # y'' B/2 (y'' in 1/m) up to this counts as convex: no hollow in the run
DWL_TRANSOM_RETRY = 0.5     # ... and when a fine ship's ends cannot hold its LCB with that wide a transom
FULLNESS_POINTS = 81        # points of the natural fullness the SAC stays near
FULLNESS_LIMITS = (0.52, 0.97)  # natural end fullness kept inside these
FIT_END = 0.06              # no fullness points this close (fraction of the waterline's length) to its ends
# Without a parallel body, no fullness points within this fraction of Lpp of where the waterline
# is at B/2: there the box 2 y_dwl d ends its curvature at once (the waterline held at its peak),
# and a SAC fitted to fullness times it bent upward at the peak. Free there, the SAC is the
# fairest that meets volume and LCB (bench_fairness_space, 0.03-0.25 tried; 0.12 best).
SAC_FREE_NEAR_PEAK = 0.12
KEEL_LANDING_TOL = 1e-6     # a keel landing this close (fraction of Lpp) to the parallel body leaves the run no convex range
# Just forward of where the keel lands the run's section fullness f rises through the section
# family's turn: at a quarter of the depth the family's half-breadth is convex in f below about
# 0.83 (and concave above), so with the keel's fall over and f rising at a steady rate the low
# waterlines took a hollow of 0.1-2.7 deg there between the round end and the run's shoulder (and
# the outer buttocks a matching lobe). The SAC holds f'' <= -LANDING_BEND / Lpp^2 (f against x in
# m) over LANDING_BEND_SPAN of Lpp from the landing, where the volume and LCB allow it (with the
# run's convex range, convex_where_met): the fullness's rise slows there, as the family needs.
# bench_hull's hulls 0-99 / 100-199 of 200: T/4 waterlines with more than two sign changes whose
# smallest inner lobe lies at 0.05-0.2 Lpp 14 -> 2 / 14 -> 2; hulls with a waterline over two
# 57 -> 52 / 55 -> 45, a buttock over two 53 -> 53 / 44 -> 43, S frames 24 / 17 unchanged, every
# mark 26 -> 27 / 34 -> 36; waterlines clean as a lines plan, lower 252 -> 252 / 240 -> 250, upper
# 276 -> 277 / 270 -> 269 of 300; the 0.06 / 0.12 T waterlines' largest aft hollow 11.7 / 3.9 ->
# 10.1 / 2.3 deg (hulls 0-99). Bends 7, 10, 12, 17, 20: every mark 26, 26, 26, 25, 25 on hulls
# 0-99 (40: 6); spans 0.035 / 0.07 Lpp: 27 / 25. bench_design_options: 495 of 500 build as before;
# its 148 bulbed blends fold no more (largest normal turn 58.6 deg), none crosses itself.
LANDING_BEND = 14.0
LANDING_BEND_SPAN = 0.05
PEAK_CHECKS = 2001          # points of the waterline searched for where it is at B/2
MATCH_TOL = 1e-6            # relative tolerance of volume, LCB (on Lpp) and waterplane area on the surface
MATCH_ITERATIONS = 6
MATCH_REFUSE = 1e-4         # a design still this far off (relative) after them is refused, not returned
# With a bulb the ship's volume and LCB are the bare hull's plus the bulb's share (_bulb_share),
# measured on the first build that composes, scaled with the bare hull's volume, and measured
# again on the hull that meets the asked. The scaled share is good to about 3e-5, so a closer mark costs a rebuild
# and a composition more (2e-5: the container ship 65 -> 128 ms under load, 30 bulbed designs
# 71 -> 118 ms median); the issue's is 1e-4.
MATCH_TOL_BULB = 5e-5
MATCH_GAUSS = 4             # Gauss points per span of the matching hydrostatics: 1e-11 of the 8-point volume, twice as fast
# The skin's aft end keeps the curvature its stations give it (not-a-knot): the natural end's
# zero curvature left a hollow lobe where a waterline ends over a transom (the container ship's
# 15 m one, 0.12 deg); bench_fairness_space's upper waterlines 230 -> 237 clean of 300. The fore
# end stays natural: not-a-knot there changed none of the sampled hulls.
SKIN_AFT_END = "not_a_knot"
# The sections' top corner (basic curve top_corner, a fraction of the freeboard; the description's
# default is 0.5) sits a little higher: the top then turns less of its way just above the
# waterline, where a run's fine sections under a flared top turned most (a broad peak of their
# curvature at T) and the buttocks crossing T took a hollow there. bench_fairness_space's reading
# by hand, hulls 0-299 / held-out 300-599, 0.5 -> 0.55: sign changes a buttock 1.90 -> 1.82 /
# 1.96 -> 1.86, hulls meeting every mark 72 -> 78 / 68 -> 78. 0.6: buttocks alike, every mark 73 /
# 66 (the upper waterlines' aft ends wobble); 0.65: 48 (hulls 0-299).
TOP_CORNER = 0.55
PROFILE_SPANS = (30, 60, 120)  # knot spans of the profile, tried in turn
# The design waterline's fairness weighs its change of curvature too (basic curve e3): with the
# curvature's square alone it bent where its flat part, its peak and its area left it room, and the
# sections read off it turned S-shaped there (bench_fairness_space).
DWL_E3 = 3.0
_GAUSS8 = np.polynomial.legendre.leggauss(8)  # the natural fullness's quadrature
BULB_FULLNESS_MARGIN = 0.1  # the designer's bulb sections keep this fraction of their fullness range from its ends
BULB_AFT_LENGTH = 2.6       # the bulb runs on into the hull this many times L_PR + B_B (the bulb's own default is 2) ...
MIN_ENTRANCE_ANGLE = 7.0    # deg: a waterline ending finer meets the stem in a cusp, its stem sections a knife
                            # millimetres thick (no stem bar is) that a bulb's top grazes
#: deg: a design waterline closing on the centre plane aft (a dry transom's, a cruiser stern's) that
#: would end blunter is solved again with this run half-angle. A blunt end rounds the waterlines
#: about T within 1-2 % Lpp, and the buttocks crossing T there read that round as a convex lobe
#: just above T over a hollow under it (bench_fairness_space, hulls 0-99: a buttock over two 53 ->
#: 48 hulls; 65 deg: 50, 70: 53; lower caps bend the rest of a full waterline harder: docs/sections.md).
MAX_RUN_ANGLE = 60.0
BULB_AFT_RETRIES = (3.0, 3.5, 4.0)  # ... or these when it leaves a fine forefoot again (meets the hull in two curves)
# The designer's bulb (bulb=True) that meets the hull in no one seam at any of those aft lengths
# is tried at these fractions of its size (a fine ship's short entrance behind a long parallel
# body: the bulb's aft part wider than the forefoot, or a seam turning back round it); Kracht's
# coefficients scale as lengths, areas and volume (c_zb, a height over T, is kept).
BULB_SCALE_RETRIES = (0.85, 0.7, 0.55)
BULB_SCALE_POWERS = {"c_lpr": 1, "c_bb": 1, "c_abt": 2, "c_abl": 2, "c_vpr": 3}
# A single screw in an aperture aft of a skeg. Propeller diameter by default a fraction of T;
# its plane a fraction of Lpp forward of the AP (room for the rudder aft of it); clearances as
# fractions of the diameter, as class societies recommend for single screws: blade tip to the
# hull above, to the baseline below, and the disc to the skeg's aft edge.
# The fraction of T is PROPELLER_DIAMETER up to Cb PROPELLER_FULL_CB[0], falling linearly to
# PROPELLER_DIAMETER_FULL at PROPELLER_FULL_CB[1] and above: a container ship's screw is about
# 0.7 T (KCS 7.9 m at 10.8 m), a tanker's or bulk carrier's, deep for its power, 0.5-0.6 T. At
# 0.7 T the skegged tanker's keel rose 10.4 m over its last 14 m, a cliff in every buttock
# (fairness_report's buttock sign changes 35; 14 at 0.55 T).
PROPELLER_DIAMETER = 0.7
PROPELLER_DIAMETER_FULL = 0.55
PROPELLER_FULL_CB = (0.7, 0.8)
PROPELLER_PLANE = 0.035
TIP_CLEARANCE = 0.25
HEEL_CLEARANCE = 0.04
SKEG_CLEARANCE = 0.15
# The profile over the blades is asked this much more (fraction of the diameter): the skinned surface
# passes up to 0.0022 D under the designed profile between stations (the skegged tanker 1.8 cm).
TIP_CLEARANCE_SKIN = 0.01
PROPELLER_HALF_WIDTH = 0.1  # half the blades' axial extent, fraction of the diameter
PROPELLER_ROOM = 0.97       # the hull over the blades stays below this fraction of the transom's lower edge
PROPELLER_RETRIES = (0.6, 0.5)  # smaller default propellers (fractions of T) when the run cannot hold the first
SKEG_HALF_THICKNESS = 0.1   # the skeg's half thickness, fraction of the propeller diameter (it houses the shaft)
SKEG_END = 0.8              # its bottom rises to the hull over this many propeller diameters forward of its aft edge
SKEG_FILLET = 1.0           # the hollow fillet to the hull body, fraction of the propeller diameter
SKEG_SECTION_CONTROLS = 32  # control points per section of a ship with a skeg (its side and fillet are short)
APERTURE_COUNTER_ANGLE = 4.0   # deg: the counter's rise at the transom where it must clear a propeller
# A sonar dome under the keel's forward end (a frigate's, DTMB 5415's proportions): its length
# (fraction of Lpp), depth below the keel (of T) and half-breadth (of B); by default its nose where
# the keel's flat ends forward (with a bulb, DOME_BLEND_CLEARANCE).
DOME_LENGTH = 0.11
DOME_DEPTH = 0.4
DOME_HALF_BREADTH = 0.12
# With a bulb too, the dome's nose is put this fraction of Lpp aft of where the blend of the same
# ship without a dome starts on the hull: under the blend the blend runs down the dome's side to
# its keel and folds, or the bulb cannot meet hull and dome in one seam; and the dome draws the
# hull's keel in forward of its nose, so a closer nose still folded one of bench_design_options'
# 18 ships with both (0.01 and 0.02 Lpp).
DOME_BLEND_CLEARANCE = 0.03
# A blend boundary this fraction of T below the base lies on the dome (a hundredth of its depth): one
# running onto it reaches metres down its side; a dome 5 m aft of a blend starting on the flat keel
# still drew the keel 2 mm under the base there (a 166 m ship of bench_design_options).
DOME_ON_BLEND_TOL = 0.01 * DOME_DEPTH


#: Particulars a design cannot start without (fl.design_hull raises InvalidInput naming those missing).
REQUIRED_PARTICULARS = ("lpp", "breadth", "draft", "depth", "cb", "lcb")


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
    parallel_centre: float | None = None  # middle of the parallel body (m from the AP)
    stern: str = "transom"
    transom_immersion: float | None = None  # transom lower edge below the waterline (m); < 0 dry
    transom_breadth: float | None = None  # waterline half-breadth at an immersed transom (m)
    bulb: bool | dict = False
    skeg: bool = False  # a single screw: a skeg under the run and a propeller aperture aft of it
    sonar_dome: bool = False  # a sonar dome under the keel's forward end
    sonar_dome_nose: float | None = None  # with sonar_dome: its nose (m from the AP); None: where the keel's flat
                                          # ends forward, or aft of a bulb's blend (DOME_BLEND_CLEARANCE)
    propeller_diameter: float | None = None  # with skeg (m); default 0.55-0.7 T (default_propeller_diameter)
    stem_rake: float = STEM_RAKE
    transom_rake: float = 0.0  # the transom's plane from the vertical (deg), its top aft when positive; a transom stern only
    flat_bottom: float | None = None  # flat of bottom over the parallel body, fraction of the waterline half-breadth;
                                      # None: FLAT_BOTTOM_DEFAULT (none on a hull any section of which would narrow it); 0: none
    name: str = "designed hull"
    notes: list[str] = field(default_factory=list)

    @property
    def volume(self) -> float:
        """The ship's displaced volume asked, Cb Lpp B T (m^3), its bulb included."""
        return self.cb * self.lpp * self.breadth * self.draft

    def check(self) -> None:
        """Raises InvalidInput naming a value outside the designer's range."""
        for key in ("lpp", "breadth", "draft", "depth", "cb", "lcb"):
            v = getattr(self, key)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise _native.InvalidInput(f"{key} is {v!r}; expected a finite number")
        if not 1.0 <= self.lpp <= 600.0:
            raise _native.InvalidInput(f"lpp is {self.lpp}; expected 1 to 600 m" + (" (millimetres? divide by 1000)" if self.lpp > 1000 else ""))
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
        rake = self.stem_rake
        if isinstance(rake, bool) or not isinstance(rake, (int, float)) or not 5.0 <= rake <= 45.0:
            raise _native.InvalidInput(f"stem_rake is {rake!r}; expected 5 to 45 deg from the vertical")
        lo, hi = TRANSOM_RAKE_RANGE
        rake = self.transom_rake
        if isinstance(rake, bool) or not isinstance(rake, (int, float)) or not lo <= rake <= hi:
            raise _native.InvalidInput(f"transom_rake is {rake!r}; expected {lo:g} to {hi:g} deg from the vertical "
                                       "(positive: the top aft)")
        if rake and self.stern != "transom":
            raise _native.InvalidInput(f"transom_rake is {rake:g} deg with stern={self.stern!r}; expected 0 (a cruiser "
                                       "stern has no transom) or stern='transom'")
        for key in ("cm", "cwp"):
            v = getattr(self, key)
            if v is not None and not (self.cb < v <= 1.0):
                raise _native.InvalidInput(f"{key} is {v}; expected between Cb = {self.cb} and 1")
        limits = {"lcf": (0.0, self.lpp, "an LCF between the AP and the FP (m from the AP)"),
                  "parallel_length": (0.0, 0.8 * self.lpp, "a parallel body from 0 to 0.8 Lpp (m)"),
                  "parallel_centre": (0.1 * self.lpp, 0.9 * self.lpp, "a parallel body centred 0.1 to 0.9 Lpp from the AP (m)"),
                  "transom_immersion": (-self.depth, self.draft, "an immersion between -D and T (m; < 0 dry)"),
                  "sonar_dome_nose": (DOME_LENGTH * self.lpp, self.lpp, f"a dome nose {DOME_LENGTH:g} Lpp or more forward of "
                                      "the AP, under the flat keel (m from the AP)"),
                  "transom_breadth": (0.0, 0.5 * self.breadth, "a waterline half-breadth at the transom from 0 to B/2 (m)"),
                  "flat_bottom": (*FLAT_BOTTOM_BOUNDS, f"a flat of bottom of 0 to {FLAT_BOTTOM_BOUNDS[1]:g} of the waterline's half-breadth"),
                  "propeller_diameter": (0.2 * self.draft, 0.95 * self.draft / (1 + HEEL_CLEARANCE),
                                         "a propeller diameter from 0.2 T to what fits under T with its clearances (m)")}
        for key, (lo, hi, what) in limits.items():
            v = getattr(self, key)
            if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float)) or not lo <= v <= hi):
                raise _native.InvalidInput(f"{key} is {v!r}; expected {what}")
        if not isinstance(self.bulb, (bool, dict)):
            raise _native.InvalidInput(f"bulb is {self.bulb!r}; expected true, false, its Kracht coefficients "
                                       "or a whole 'bulb' section (a dict)")
        if not isinstance(self.sonar_dome, bool):
            raise _native.InvalidInput(f"sonar_dome is {self.sonar_dome!r}; expected true or false")
        if self.sonar_dome_nose is not None and not self.sonar_dome:
            raise _native.InvalidInput(f"sonar_dome_nose is {self.sonar_dome_nose}; expected it only with sonar_dome=True")
        if not isinstance(self.skeg, bool):
            raise _native.InvalidInput(f"skeg is {self.skeg!r}; expected true or false (a single screw aft of a skeg)")
        if self.propeller_diameter is not None and not self.skeg:
            raise _native.InvalidInput(f"propeller_diameter is {self.propeller_diameter}; expected it only with skeg=True "
                                       "(the designer places a single screw in an aperture aft of the skeg)")


def _coefficients(p: Particulars) -> dict:
    """Coefficients and lengths the particulars leave open."""
    L = p.lpp
    cm = p.cm if p.cm is not None else min(1.006 - 0.0056 * p.cb ** -3.56, CM_MAX)
    cp = p.cb / cm
    cwp = p.cwp if p.cwp is not None else min(math.sqrt(p.cb) + 0.01, CWP_MAX)
    lcf = p.lcf if p.lcf is not None else p.lcb - LCF_AFT_OF_LCB * L
    lp = p.parallel_length if p.parallel_length is not None else max(0.0, PARALLEL_SLOPE * (cp - PARALLEL_CP) * L)
    lp = min(lp, 0.6 * L)
    if p.parallel_centre is not None:
        lo, hi = PARALLEL_SPAN_GIVEN
        centre = p.parallel_centre
    else:
        lo, hi = PARALLEL_SPAN
        centre = L / 2 + PARALLEL_SHIFT * (p.lcb - L / 2)
    centre = float(np.clip(centre, lo * L + lp / 2, hi * L - lp / 2)) if lp > 0 else centre
    imm = p.transom_immersion if p.transom_immersion is not None else \
        (TRANSOM_IMMERSION_FULL if p.cb >= TRANSOM_FULL_CB else TRANSOM_IMMERSION_FINE) * p.draft
    fine = min(1.0, max(0.0, (0.85 - p.cb) / 0.35))  # 0 full, 1 fine
    return {"cm": cm, "cp": cp, "cwp": cwp, "lcf": lcf, "fine": fine, "parallel": (centre - lp / 2, centre + lp / 2),
            "transom_z": p.depth if p.stern == "cruiser" else p.draft - imm}


def _ends(p: Particulars) -> tuple[float, float]:
    return -TRANSOM_AFT * p.lpp, p.lpp + (p.depth - p.draft) * math.tan(math.radians(p.stem_rake))


def _profile(p: Particulars, c: dict, x_aft: float, x_fore: float, keel_rise: float = KEEL_RISE) -> dict:
    """Keel on the baseline, rising aft over keel_rise of Holtrop and Mennen's run to the
    transom's lower edge (or up the cruiser stern to the deck) and forward through the forefoot
    to T at the FP and on up the raked stem."""
    L, T, D = p.lpp, p.draft, p.depth
    z_t = c["transom_z"]
    lcb_pct = 100 * (p.lcb - L / 2) / L
    run = L * (1 - c["cp"] + 0.06 * c["cp"] * lcb_pct / (4 * c["cp"] - 1))  # Holtrop and Mennen's run length
    keel_aft = x_aft + float(np.clip(keel_rise * run, MIN_KEEL_RISE * L, MAX_KEEL_RISE * L))
    keel_fore = L - (0.04 + 0.10 * c["fine"]) * L
    if c["parallel"][1] > c["parallel"][0]:
        keel_aft, keel_fore = min(keel_aft, c["parallel"][0]), max(keel_fore, c["parallel"][1])
    slope_aft = -math.tan(math.radians(COUNTER_ANGLE if p.stern == "transom" else 70.0))
    stem = 1.0 / math.tan(math.radians(p.stem_rake))
    return {"flat_from": keel_aft, "flat_to": keel_fore, "value": 0.0, "yB": z_t, "slopeB": slope_aft,
            "yE": D, "slopeE": stem, "points": [[L, T]], "slopes": [[L, stem]], "monotone": True, "spans": 30}


def default_propeller_diameter(p: Particulars) -> float:
    """PROPELLER_DIAMETER T on ships up to Cb PROPELLER_FULL_CB[0], PROPELLER_DIAMETER_FULL T
    from PROPELLER_FULL_CB[1] (linear between), or less where the counter must stay below a low
    (immersed) transom's edge: the hull over the blades (HEEL_CLEARANCE + 1 + TIP_CLEARANCE
    diameters above base) at most PROPELLER_ROOM of the transom's height."""
    room = PROPELLER_ROOM * _coefficients(p)["transom_z"] / (HEEL_CLEARANCE + 1.0 + TIP_CLEARANCE)
    share = float(np.interp(p.cb, PROPELLER_FULL_CB, (PROPELLER_DIAMETER, PROPELLER_DIAMETER_FULL)))
    return min(share * p.draft, room)


@dataclass(frozen=True)
class Propeller:
    """The single screw of a ship with a skeg, in metres (x from the AP, heights above base)."""

    diameter: float      # of the disc
    x: float             # the propeller plane
    shaft_height: float  # the shaft's axis
    hull_above: float    # the least height of the hull over the disc (tip clearance kept)
    skeg_aft: float      # the skeg's aft edge


def propeller(p: Particulars) -> Propeller | None:
    """The single screw of a ship with a skeg (:class:`Propeller`); None without a skeg."""
    if not p.skeg:
        return None
    dp = p.propeller_diameter if p.propeller_diameter is not None else default_propeller_diameter(p)
    x = max(PROPELLER_PLANE * p.lpp, dp)
    shaft = (HEEL_CLEARANCE + 0.5) * dp
    return Propeller(diameter=dp, x=x, shaft_height=shaft, hull_above=shaft + (0.5 + TIP_CLEARANCE) * dp,
                     skeg_aft=x + SKEG_CLEARANCE * dp)


def _aperture(p: Particulars, prof: dict, profile, x_aft: float, x_fore: float):
    """With a skeg: the profile (the hull body's bottom) passing over the propeller disc with
    its tip clearance (a profile point where it would pass lower), and the skeg (its aft edge
    SKEG_CLEARANCE D forward of the disc, its forward end where the keel's flat starts).
    Returns (profile, skeg section or None)."""
    pr = propeller(p)
    if pr is None:
        return profile, None
    fore = pr.x + PROPELLER_HALF_WIDTH * pr.diameter  # the profile falls forward: the blades' forward edge
    asked = pr.hull_above + TIP_CLEARANCE_SKIN * pr.diameter
    if float(profile(fore)[0]) < asked:  # a flatter counter over the propeller, then a steeper run
        lifted = {**prof, "points": sorted(prof["points"] + [[fore, asked]])}
        tries = [{**lifted, "slopeB": -math.tan(math.radians(APERTURE_COUNTER_ANGLE))}] if p.stern == "transom" else []
        for trial in tries + [lifted]:
            for spans in PROFILE_SPANS:
                try:
                    profile = solve_curve("profile", BasicCurveSpec.from_dict("profile", {**trial, "spans": spans},
                                                                              "basic_curves.profile"),
                                          x_aft, x_fore, lower=-p.draft, upper=p.depth, maximum=False)
                    prof.clear()
                    prof.update(trial, spans=spans)
                    break
                except _native.InfeasibleFormParameters:
                    continue
            else:
                continue
            break
        else:
            raise _native.InfeasibleFormParameters(
                f"basic_curves.profile: no fair centre profile passes {asked:.4g} m above base over the "
                f"propeller (diameter {pr.diameter:.3g} m at x = {pr.x:.4g} m) and meets the keel's flat at "
                f"{prof['flat_from']:.4g} m: give a smaller propeller_diameter or a longer run (a lower cb)")
    dp = pr.diameter
    end = min(SKEG_END * dp, 0.5 * (prof["flat_from"] - pr.skeg_aft))
    skeg = {"x_aft": pr.skeg_aft, "x_fore": prof["flat_from"], "half_thickness": SKEG_HALF_THICKNESS * dp,
            "fillet": SKEG_FILLET * dp, "end_length": end}
    return profile, skeg


def _midship_place(p: Particulars) -> float:
    """Where a ship without parallel body has its largest section: midships, where Cm is measured."""
    return 0.5 * p.lpp


def _cm_note(p: Particulars, c: dict) -> str:
    if p.cm is None and c["parallel"][1] <= c["parallel"][0]:
        return f"free (no parallel body; Kerlen's {c['cm']:.4f} not imposed)"
    return f"{c['cm']:.4f}"


def _smoothstep(r):
    r = np.clip(r, 0.0, 1.0)
    return r * r * r * (10.0 - 15.0 * r + 6.0 * r * r)


def _fullness_shape(x: np.ndarray, par: tuple[float, float], xa: float, xf: float) -> tuple[np.ndarray, np.ndarray]:
    """How far (0 .. 1) each x lies from the parallel body toward the aft and the forward end."""
    aft = _smoothstep((par[0] - x) / max(par[0] - xa, 1e-9))
    fore = _smoothstep((x - par[1]) / max(xf - par[1], 1e-9))
    return aft, fore


def natural_fullness(p: Particulars, c: dict, dwl, profile, xa: float, xf: float) -> tuple[np.ndarray, np.ndarray]:
    """Section fullness Cm - (Cm - s_aft) g_aft(x) - (Cm - s_fore) g_fore(x) with the end
    fullness s_aft, s_fore that give the volume and the LCB (two linear conditions on the
    box 2 y_dwl (T - z_keel)), kept inside FULLNESS_LIMITS. Returns (x, fullness)."""
    g, w = _GAUSS8
    br = np.linspace(xa, xf, 161)
    a, b = br[:-1, None], br[1:, None]
    x = (0.5 * (a + b) + 0.5 * (b - a) * g).ravel()
    wq = (0.5 * (b - a) * w).ravel()
    box = 2.0 * dwl(x) * np.maximum(p.draft - profile(x), 0.0)
    ga, gf = _fullness_shape(x, c["parallel"], xa, xf)
    cm = c["cm"]
    # V = int box (cm - (cm - sa) ga - (cm - sf) gf) = V0 + ka (sa - cm) + kf (sf - cm), same with x for the moment
    v0, m0 = np.sum(wq * box * cm), np.sum(wq * x * box * cm)
    ka, kf = np.sum(wq * box * ga), np.sum(wq * box * gf)
    ma, mf = np.sum(wq * x * box * ga), np.sum(wq * x * box * gf)
    vol = p.volume
    rhs = np.array([vol - v0, vol * p.lcb - m0])
    try:
        da, df = np.linalg.solve(np.array([[ka, kf], [ma, mf]]), rhs)
    except np.linalg.LinAlgError:
        da = df = (vol - v0) / max(ka + kf, 1e-12)
    s_aft, s_fore = (float(np.clip(cm + v, *FULLNESS_LIMITS)) for v in (da, df))
    xs = np.linspace(xa, xf, FULLNESS_POINTS)
    ga, gf = _fullness_shape(xs, c["parallel"], xa, xf)
    return xs, cm - (cm - s_aft) * ga - (cm - s_fore) * gf


def _solve_dwl(p: Particulars, dwl: dict, xa: float, xf: float):
    """The design waterline solved from `dwl` (which keeps what it was solved with): without a
    given LCF when the default one does not suit it, with the run half angle lowered to
    MAX_RUN_ANGLE where the fairest waterline closing aft would end blunter (_finer_run), and with
    the entrance half angle raised to MIN_ENTRANCE_ANGLE where it would end finer."""
    half = p.breadth / 2

    def solve(spec: dict):
        return solve_curve("dwl", BasicCurveSpec.from_dict("dwl", spec, "basic_curves.dwl"), xa, xf, lower=0.0, upper=half)

    try:
        curve = solve(dwl)
    except _native.InfeasibleFormParameters:
        if p.lcf is not None or "lcf" not in dwl:
            raise
        del dwl["lcf"]  # the default LCF does not suit this waterline: let it fall where it is fairest
        curve = solve(dwl)
    curve = _finer_run(p, dwl, curve, solve, xa)
    if "entrance_angle" in dwl or math.degrees(math.atan(abs(curve.derivative(xf, 1)))) >= MIN_ENTRANCE_ANGLE:
        return curve
    try:
        sharper = solve({**dwl, "entrance_angle": MIN_ENTRANCE_ANGLE})
    except _native.InfeasibleFormParameters:
        return curve
    dwl["entrance_angle"] = MIN_ENTRANCE_ANGLE
    return sharper


def _finer_run(p: Particulars, dwl: dict, curve, solve, xa: float):
    """The design waterline with its run half-angle capped at MAX_RUN_ANGLE where it closes on the
    centre plane aft (yB 0) and the fairest one would end blunter: with the default LCF, else
    without it (as _solve_dwl lets a default LCF go); kept as it is where neither solves or where
    the run angle is given. `dwl` keeps what it was solved with."""
    if dwl.get("yB", 0.0) != 0.0 or "run_angle" in dwl:
        return curve
    if math.degrees(math.atan(abs(curve.derivative(xa, 1)))) <= MAX_RUN_ANGLE:
        return curve
    trials = [{**dwl, "run_angle": MAX_RUN_ANGLE}]
    if p.lcf is None and "lcf" in dwl:
        trials.append({k: v for k, v in trials[0].items() if k != "lcf"})
    for trial in trials:
        try:
            finer = solve(trial)
        except _native.InfeasibleFormParameters:
            continue
        dwl.clear()
        dwl.update(trial)
        return finer
    return curve


def _waterline(p: Particulars, dwl: dict, xa: float, xf: float, peak: float, immersed_transom: bool):
    """The design waterline; at an immersed transom not given a breadth, the widest of
    TRANSOM_WIDTHS whose waterline is convex from the transom to its peak (a wider transom on a
    fine waterplane hollows the run: its hollow carries down into the waterlines below T, a
    wobble at mid-draught and an inflection at the transom's end of those just under T); failing
    that, the widest whose waterline widens all the way (a wide transom on a fine waterplane
    otherwise pinches the run into a waist); failing that, the narrowest that solves."""
    half = p.breadth / 2
    if not immersed_transom:
        dwl["yB"] = 0.0
        return _solve_dwl(p, dwl, xa, xf)
    widths = [p.transom_breadth] if p.transom_breadth is not None else [f * half for f in TRANSOM_WIDTHS]
    xs = np.linspace(xa, peak, MONOTONE_CHECKS)
    solved, widening, convex = None, None, None
    for yb in widths:
        trial = {**dwl, "yB": yb}
        try:
            curve = _solve_dwl(p, trial, xa, xf)
        except _native.InfeasibleFormParameters:
            if solved is None:
                raise
            break
        solved = curve, trial
        y = curve(xs)
        if np.all(np.diff(y, 2) <= RUN_HOLLOW_TOL * (xs[1] - xs[0]) ** 2 / half):
            convex = solved
            break
        if widening is None and np.all(np.diff(y) >= -MONOTONE_TOL * half):
            widening = solved
    best = convex or widening or solved
    dwl.clear()
    dwl.update(best[1])  # the description keeps the transom breadth (and LCF) the waterline was solved with
    return best[0]


def _flat_share(p: Particulars) -> float:
    """The flat of bottom's share of the waterline's half-breadth the designer draws."""
    return FLAT_BOTTOM_DEFAULT if p.flat_bottom is None else p.flat_bottom


def _flat_bottom_spec(p: Particulars, prof: dict, par: tuple, x_aft: float) -> dict:
    """The flat of bottom: _flat_share(p) of the waterline's half-breadth over the parallel body (at
    midships without one), none from FLAT_BOTTOM_AFT of the keel's rise aft of its flat (a flat of
    keel there: one starting where the keel meets the base put a hollow in the low buttocks) and
    at the forefoot, at least FLAT_BOTTOM_FADE Lpp forward of its full part (a parallel body
    reaching the forefoot left it no room to fade), value, slope and curvature 0 at both ends."""
    if par[1] > par[0]:
        full, full_end = {"flat_from": par[0], "flat_to": par[1], "value": _flat_share(p)}, par[1]
    else:
        full_end = _midship_place(p)
        full = {"points": [[full_end, _flat_share(p)]]}
    start = prof["flat_from"] - FLAT_BOTTOM_AFT * (prof["flat_from"] - x_aft)
    end = min(max(prof["flat_to"], full_end + FLAT_BOTTOM_FADE * p.lpp), p.lpp)
    return {"x_start": start, "x_end": end, "yB": 0.0, "yE": 0.0, "slopeB": 0.0, "slopeE": 0.0, "CAB": 0.0,
            "CAE": 0.0, "spans": 24, **full}


def design_description(p: Particulars, keel_rise: float = KEEL_RISE) -> dict:
    """The hull description (a dict) for the particulars (see the module docstring), the keel
    rising aft over keel_rise of the run (a fraction, KEEL_RISE by default). A sonar dome without
    p.sonar_dome_nose has its nose where the keel's flat ends, also with a bulb (design_hull
    moves it aft of the bulb's blend). Raises InvalidInput for particulars outside the
    designer's range."""
    p.check()
    c = _coefficients(p)
    L, B, T, D = p.lpp, p.breadth, p.draft, p.depth
    x_aft, x_fore = _ends(p)
    prof = _profile(p, c, x_aft, x_fore, keel_rise)
    profile, skeg = _aperture(p, prof, _solved_profile(p, prof, x_aft, x_fore), x_aft, x_fore)
    xa, xf = immersed_range(profile, T)
    immersed_transom = xa <= x_aft + 1e-9 * L
    dwl, dwl_curve = _dwl_spec(p, c, xa, xf, immersed_transom=immersed_transom)
    par = c["parallel"]
    desc = {
        "name": p.name,
        "notes": "; ".join(p.notes + [f"designed from particulars: Cm {_cm_note(p, c)}, Cp {c['cp']:.4f}, Cwp {c['cwp']:.4f}, "
                                      f"LCF {c['lcf']:.3f} m, parallel body {par[0]:.2f} .. {par[1]:.2f} m"]),
        "principal": {"Lpp": L, "B": B, "T": T, "D": D},
        "ends": {"aft": x_aft, "fore": x_fore, **({"transom_rake": float(p.transom_rake)} if p.transom_rake else {})},
        "stations": {"count": 61},
        "sections": {"n_control": 20},
        "basic_curves": {"profile": prof, "dwl": dwl, "deck": _deck_spec(p, par, dwl_curve, profile, x_aft, xa, xf, immersed_transom),
                         "sac": _sac_spec(p, c, dwl_curve, profile, prof["flat_from"], xa, xf), "top_corner": {"value": TOP_CORNER}},
        "skinning": {"aft_end": SKIN_AFT_END},
        "design": {k: v for k, v in asdict(p).items() if k != "notes"},
    }
    _add_appendages(desc, p, prof, skeg)
    if _flat_share(p):
        desc["basic_curves"]["flat_bottom"] = _flat_bottom_spec(p, prof, par, x_aft)
    if p.bulb:
        desc["bulb"] = _bulb_section(p, c)
    return desc


def _solved_profile(p: Particulars, prof: dict, x_aft: float, x_fore: float):
    """The centre profile of `prof`, with finer spans where a short stem over a low freeboard
    needs them (`prof` keeps the spans it was solved with)."""
    def solve(spans: int):
        prof["spans"] = spans
        return solve_curve("profile", BasicCurveSpec.from_dict("profile", prof, "basic_curves.profile"), x_aft,
                           x_fore, lower=-p.draft, upper=p.depth, maximum=False)

    for spans in PROFILE_SPANS[:-1]:
        try:
            return solve(spans)
        except _native.InfeasibleFormParameters:
            continue
    return solve(PROFILE_SPANS[-1])


def _dwl_spec(p: Particulars, c: dict, xa: float, xf: float, immersed_transom: bool) -> tuple[dict, object]:
    """The design waterline's spec and curve: Cwp and the LCF, flat at B/2 over the parallel
    body (or reaching B/2 at midships without one)."""
    half, par = p.breadth / 2, c["parallel"]
    dwl = {"yE": 0.0, "monotone": True, "spans": 24, "e3": DWL_E3, "waterplane_area": c["cwp"] * p.lpp * p.breadth,
           "lcf": c["lcf"]}
    if par[1] > par[0]:
        dwl.update(flat_from=par[0], flat_to=par[1], value=half)
    else:  # no parallel body: the waterline still reaches B/2, at midships
        dwl.update(upper=half, points=[[_midship_place(p), half]], slopes=[[_midship_place(p), 0.0]])
    peak = par[0] if par[1] > par[0] else _midship_place(p)
    return dwl, _waterline(p, dwl, xa, xf, peak, immersed_transom=immersed_transom)


def _sac_spec(p: Particulars, c: dict, dwl_curve, profile, keel_landing: float, xa: float, xf: float) -> dict:
    """The SAC: the volume and LCB, near the natural fullness, flat over the parallel body (without
    one, free near where the waterline is at B/2). With a parallel body the run's section fullness
    is held convex (f'' <= 0) from keel_landing (m from AP: the profile's flat_from, where the keel
    reaches the base) to the body where the volume and LCB allow it (convex_where_met): a full
    ship whose LCB lies far aft took a fullness rising, standing level (its monotone bound met)
    over 0.06-0.14 Lpp and rising again, and its buttocks landed, then stepped down (convex lobes
    of 1-12 deg at 0.3-0.7 B/2; bench_hull's hulls 41, 73 and 88 of 100). Over
    bench_fairness_space's hulls 0-299 / 300-599: sign changes a buttock 1.819 -> 1.767 / 1.868
    -> 1.823, upper waterlines clean 827 -> 827 / 819 -> 822 of 900. Held always (`convex`), it
    refused 19 of bench_design_edits' 60 volume cuts of 10 %; forward of the body it cost 92
    clean lower waterlines."""
    L, B, T = p.lpp, p.breadth, p.draft
    par = c["parallel"]
    xs, target = natural_fullness(p, c, dwl_curve, profile, xa, xf)
    near_end = FIT_END * (xf - xa)
    sac = {"volume": p.volume, "lcb": p.lcb, "spans": 24, "monotone": True,
           "fullness_fit": [[float(x), float(s)] for x, s in zip(xs, target)
                            if xa + near_end <= x <= xf - near_end]}
    if par[1] > par[0]:
        sac.update(flat_from=par[0], flat_to=par[1], value=c["cm"] * B * T)
        if par[0] - keel_landing > KEEL_LANDING_TOL * L:
            sac["convex_where_met"] = [[keel_landing, par[0], 0.0],
                                       [keel_landing, min(keel_landing + LANDING_BEND_SPAN * L, par[0]), LANDING_BEND / L ** 2]]
        return sac
    lo, hi = _at_half_breadth(dwl_curve, p, xa, xf)
    lo, hi = lo - SAC_FREE_NEAR_PEAK * L, hi + SAC_FREE_NEAR_PEAK * L
    sac["fullness_fit"] = [q for q in sac["fullness_fit"] if not lo <= q[0] <= hi]
    if p.cm is not None:  # ... and the SAC holds a given midship area there
        sac["fit"] = [[_midship_place(p), c["cm"] * B * T]]
    return sac


def _at_half_breadth(dwl_curve, p: Particulars, xa: float, xf: float) -> tuple[float, float]:
    """From where to where (m) a waterline without a parallel body is within DECK_FLAT_TOL of
    B/2: its peak at midships, or the stretch its upper bound holds it at B/2."""
    xs = np.linspace(xa, xf, PEAK_CHECKS)
    at = xs[dwl_curve(xs) >= 0.5 * p.breadth * (1.0 - DECK_FLAT_TOL)]
    peak = _midship_place(p)
    return (float(at[0]), float(at[-1])) if len(at) else (peak, peak)


def _deck_spec(p: Particulars, par: tuple, dwl_curve, profile, x_aft: float, xa: float, xf: float,
               immersed_transom: bool) -> dict:
    """The deck line: flat at B/2 from a quarter Lpp aft of the parallel body (further aft where a
    full stern keeps the waterline near B/2) to the waterline's widest, aft of it over an
    immersed transom drawn over the waterline (see _transom_deck), over a dry one no wider than
    the sections there lean (see _dry_transom_deck), and forward of it drawn over the waterline
    (see _forward_deck)."""
    L, half = p.lpp, p.breadth / 2
    deck_from = max(x_aft + 0.05 * L, par[0] - 0.25 * L)
    xs_aft = np.linspace(xa, deck_from, DECK_FLAT_CHECKS)
    full = xs_aft[dwl_curve(xs_aft) >= DECK_CLEAR * half]  # so does a full stern aft
    if len(full):
        deck_from = max(min(deck_from, float(full[0])), x_aft + DECK_FROM_MIN * L)
    deck_to = par[1] if par[1] > par[0] else _midship_place(p)
    spec = {"flat_from": deck_from, "flat_to": deck_to, "value": half, "yB": DECK_TRANSOM * half if p.stern == "transom" else 0.0,
            "yE": 0.0, "monotone": True, "spans": 24, "fit": _forward_deck(half, dwl_curve, deck_to, xf)}
    if p.stern == "transom" and immersed_transom:
        _transom_deck(spec, p, dwl_curve, x_aft, deck_to)
    elif p.stern == "transom":
        spec["yB"] = _dry_transom_deck(p, dwl_curve, profile, xa, spec["yB"])
    return spec


def _dry_transom_deck(p: Particulars, dwl_curve, profile, xa: float, y_b: float) -> float:
    """The deck's half-breadth (m) at a dry transom: y_b, or less where the sections near the
    waterline's aft end xa lean less (see DRY_TRANSOM_LEAN_MARGIN)."""
    xs = xa + np.linspace(*DRY_TRANSOM_LEAN_REACH, DRY_TRANSOM_LEAN_POINTS) * p.lpp
    b, d = np.asarray(dwl_curve(xs)), p.draft - np.asarray(profile(xs))
    wet = (b > 0) & (d > 0)
    if not wet.any():
        return y_b
    lean = float(np.min(b[wet] + (p.depth - p.draft) * b[wet] / d[wet]))
    return min(y_b, max((1.0 - DRY_TRANSOM_LEAN_MARGIN) * lean, DRY_TRANSOM_DECK_LEAST * p.breadth / 2))


def _transom_deck(spec: dict, p: Particulars, dwl_curve, x_aft: float, deck_to: float) -> None:
    """Over an immersed transom whose waterline is narrower than the deck by more than
    TRANSOM_FLARE over the freeboard, the deck aft of its flat (in `spec`, edited) follows the
    waterline b(x): y_d = b + k (B/2 - b), k the share that puts the transom's deck TRANSOM_FLARE
    outboard of its waterline; fit points, held convex in plan from the transom to the flat. A
    deck at DECK_TRANSOM B/2 over a fine ship's narrow immersed transom flared its aft sections
    out 30-40 deg over the freeboard, and they turned hollow under the waterline (an S)."""
    half = p.breadth / 2
    xs = np.linspace(x_aft, deck_to, DECK_FLAT_CHECKS)
    b = dwl_curve(xs)
    y_t = b[0] + (p.depth - p.draft) * math.tan(math.radians(TRANSOM_FLARE))
    if y_t >= spec["yB"] or b[0] >= half:
        return
    k = (y_t - b[0]) / (half - b[0])
    deck = b + k * (half - b)
    narrower = deck < half * (1.0 - DECK_FLAT_TOL)
    if narrower.any():
        spec["flat_from"] = max(spec["flat_from"], float(xs[narrower][-1]))
    keep = (xs > xs[0]) & (xs < spec["flat_from"])
    spec["fit"] = [[float(x), float(y)] for x, y in zip(xs[keep], deck[keep])] + spec["fit"]
    spec["yB"] = float(y_t)
    # a deck following the waterline's run through its hollow took it into the upper waterlines
    spec["convex"] = [[x_aft, spec["flat_from"], 0.0]]


def _forward_deck(half: float, dwl_curve, x0: float, xf: float) -> list[list[float]]:
    """Fit points of the deck forward of the waterline's widest x0: the deck follows the share
    (1 - DECK_FLARE_END) r(x) of the waterline's narrowing, r the smoothstep from x0 to the
    waterline's end xf to the power DECK_FOLLOW_POWER. So the flare (deck minus waterline
    half-breadth) grows as smoothly as the waterline narrows; a deck flat to a fixed place and
    then narrowing on its own let the flare grow fast just forward of the flat's end and level
    off soon after, and the bilge corner leaning in with it turned the outer buttocks back where
    they cross the DWL."""
    xs = np.linspace(x0, xf, DECK_FLARE_POINTS)[1:-1]
    y_dwl = dwl_curve(xs)
    xs, y_dwl = xs[y_dwl >= DECK_FOLLOW_TO * half], y_dwl[y_dwl >= DECK_FOLLOW_TO * half]
    share = (1.0 - DECK_FLARE_END) * _smoothstep((xs - x0) / (xf - x0)) ** DECK_FOLLOW_POWER
    return [[float(x), float(half - f * (half - y))] for x, f, y in zip(xs, share, y_dwl)]


def _add_appendages(desc: dict, p: Particulars, prof: dict, skeg: dict | None) -> None:
    """The sonar dome under the keel's forward end and the skeg (with its propeller in the notes)."""
    L, B, T = p.lpp, p.breadth, p.draft
    if p.sonar_dome:
        fore = prof["flat_to"] if p.sonar_dome_nose is None else p.sonar_dome_nose
        lo, hi = _least_dome_nose(prof["flat_from"], L), prof["flat_to"]
        if not lo - 1e-9 * L <= fore <= hi + 1e-9 * L:
            raise _native.InvalidInput(f"sonar_dome_nose is {fore!r}; expected {_mm_up(lo)} to {_mm_down(hi)} m from the AP "
                                       "(the dome hangs under the flat keel, from where it starts to where it leaves the base)")
        desc["dome"] = {"x_aft": fore - DOME_LENGTH * L, "x_fore": fore, "depth": DOME_DEPTH * T,
                        "half_breadth": DOME_HALF_BREADTH * B}
    if skeg is not None:
        desc["skeg"] = skeg
        desc["sections"]["n_control"] = SKEG_SECTION_CONTROLS
        pr = propeller(p)
        desc["notes"] += (f"; single screw: propeller diameter {pr.diameter:.3g} m at x = {pr.x:.4g} m, shaft "
                          f"{pr.shaft_height:.3g} m above base, hull at least {pr.hull_above:.4g} m above base over it")


def _bulb_section(p: Particulars, c: dict) -> dict:
    """The bulb section of p.bulb: True, Kracht coefficients, or a whole "bulb" section
    ({"kracht": ..., "shape": ...}); defaults the engine's, c_abl fitted to the ship."""
    given = dict(p.bulb) if isinstance(p.bulb, dict) else {}
    section = given if {"kracht", "shape"} & set(given) else {"kracht": given}
    kracht = {**_kracht_defaults(), **section.get("kracht", {})}
    if "c_abl" not in section.get("kracht", {}):
        kracht["c_abl"] = _fitting_lateral_area(p, c, kracht)
    shape = dict(section.get("shape", {}))
    # the bulb's constant aft part reaches back to where the forefoot is wide enough to take it
    shape.setdefault("aft_length", BULB_AFT_LENGTH * (kracht["c_lpr"] * p.lpp + kracht["c_bb"] * p.breadth))
    return {**section, "kracht": kracht, "shape": shape}


def _fitting_lateral_area(p: Particulars, c: dict, kracht: dict) -> float:
    """c_abl for the designer's bulb: the default, unless it asks the bulb's sections for a
    fullness A_BT / (B_B H) outside the middle of what a bulb section can have (a short, beamy
    ship or a long, slender one); then the c_abl whose height H gives the nearest fullness inside
    it. The ship is estimated from the particulars (A_MS = Cm B T, V = Cb Lpp B T)."""
    ship = fill_options(_native.BulbShip, "bulb ship", dict(
        lpp=p.lpp, beam=p.breadth, draft_fp=p.draft, midship_area=c["cm"] * p.breadth * p.draft,
        displacement_volume=p.volume))
    k = fill_options(_native.KrachtCoefficients, "bulb", kracht)
    kappa, lo, hi = _native._bulb_section_fullness(k, ship)
    margin = BULB_FULLNESS_MARGIN * (hi - lo)
    target = min(max(kappa, lo + margin), hi - margin)
    return float(kracht["c_abl"]) if target == kappa else float(kracht["c_abl"] * kappa / target)


@lru_cache(maxsize=1)
def _kracht_defaults() -> dict:
    """The engine's default Kracht coefficients (fl.KrachtCoefficients), read once."""
    engine = _native.KrachtCoefficients()
    return {k: getattr(engine, k) for k in KRACHT_NAMES}


def _particulars(kwargs: dict) -> Particulars:
    """Particulars from keywords; an unknown one is InvalidInput naming the nearest field."""
    import difflib

    known = [f for f in Particulars.__dataclass_fields__ if f != "notes"]
    for key in kwargs:
        if key not in known:
            near = difflib.get_close_matches(key, known, n=1)
            hint = f"; did you mean {near[0]!r}?" if near else ""
            raise _native.InvalidInput(f"{key} is not a particular{hint} (expected one of {', '.join(known)})")
    missing = [f for f in REQUIRED_PARTICULARS if f not in kwargs]
    if missing:
        raise _native.InvalidInput(f"{', '.join(missing)} {'is' if len(missing) == 1 else 'are'} missing; expected "
                                   "lpp, breadth, draft, depth (m), cb and lcb (m from the AP): the particulars a design "
                                   "starts from")
    return Particulars(**kwargs)


def _fallbacks(p: Particulars):
    """The particulars, then (for basic curves that cannot be met) what the designer may still
    choose -- never a value the user gave: the LCF at and forward of the LCB, the parallel body
    moved toward the LCB, a parallel body longer by PARALLEL_STEP Lpp at a time; then the same
    with an immersed transom narrowed to DWL_TRANSOM_RETRY B/2, with a waterplane fuller by
    CWP_RETRY, and (with a skeg) with the smaller propellers of PROPELLER_RETRIES."""
    yield from _choices(p)
    if p.transom_breadth is None:
        yield from _choices(replace(p, transom_breadth=DWL_TRANSOM_RETRY * p.breadth / 2))
    if p.cwp is None:
        cwp = _coefficients(p)["cwp"]
        yield from _choices(replace(p, cwp=min(cwp + CWP_RETRY, CWP_MAX)))
    if p.skeg and p.propeller_diameter is None:  # a smaller screw lifts the counter less
        for f in PROPELLER_RETRIES:
            if f * p.draft < default_propeller_diameter(p):
                yield from _choices(replace(p, propeller_diameter=f * p.draft))


def _attempts(p: Particulars):
    """(particulars, keel rise) in the order they are tried: every fallback with the keel rising
    over KEEL_RISE of the run, then the particulars' own choices with it rising over less
    (KEEL_RISE_RETRIES)."""
    for q in _fallbacks(p):
        yield q, KEEL_RISE
    for rise in KEEL_RISE_RETRIES:
        for q in _choices(p):
            yield q, rise


def _choices(p: Particulars):
    yield p
    L = p.lpp
    lp = _coefficients(p)["parallel"]
    lcfs = [None] + ([p.lcb + s * L for s in LCF_RETRIES] if p.lcf is None else [])
    centres = [None] + ([L / 2 + PARALLEL_SHIFT_RETRY * (p.lcb - L / 2)] if p.parallel_centre is None else [])
    lengths = [None] + ([(lp[1] - lp[0]) + k * PARALLEL_STEP * L for k in range(1, PARALLEL_RETRIES + 1)]
                        if p.parallel_length is None else [])
    for length in lengths:
        for centre in centres:
            for lcf in lcfs:
                change = {k: v for k, v in (("parallel_length", length), ("parallel_centre", centre), ("lcf", lcf))
                          if v is not None}
                if change:
                    yield replace(p, **change)


@tersely  # it retries what fails and names the particulars to change itself
def design_hull(particulars: Particulars | None = None, **kwargs) -> Hull:
    """A Hull designed from particulars (a Particulars, or its fields as keywords), built and
    matched: its surface holds Cb Lpp B T, the LCB and Cwp Lpp B (see the module docstring).
    Raises InvalidInput for particulars outside the designer's range, InfeasibleFormParameters
    (naming the basic curve, what to change and, for a given Cwp, LCF, LCB, parallel body or a
    depth over TYPICAL_DEPTH T, the nearest value that builds) when no fallback builds, or when
    no aft length lets its bulb meet the hull in one seam."""
    p = particulars if particulars is not None else _particulars(kwargs)
    p.check()
    p = _dome_aft_of_blend(p)
    first = None
    for q, rise in _attempts(p):
        hull, exc = _try_design(q, rise)
        if hull is not None:
            return _dome_clear_of_blend(_bulb_that_meets(hull, p), p)
        first = first or exc
    raise _explained(first, p, _feasible_edge(p)) from first


def _blend_boundary(hull: Hull) -> np.ndarray | None:
    """Points (k, 3) of the bulb's blend boundary on the hull, None without a blend."""
    if hull.description.bulb is None:
        return None
    try:
        placement = hull.blend_placement()
    except (_native.NoBlendFits, _native.InvalidInput):
        return None  # no blend: as _bulb_that_meets, the composition keeps the plain union
    uv = np.asarray(placement.boundary_a)
    return np.asarray(placement.hull.evaluate(uv[:, 0], uv[:, 1]))


def _dome_aft_of_blend(p: Particulars) -> Particulars:
    """p, with a bulb and a sonar dome whose nose is not given: its nose DOME_BLEND_CLEARANCE
    Lpp aft of where the blend of the same ship without a dome starts on the hull, when that is
    aft of the keel's flat end (the dome's own place)."""
    if not (p.sonar_dome and p.bulb) or p.sonar_dome_nose is not None:
        return p
    try:
        plain = design_hull(replace(p, sonar_dome=False))
    except (_native.InfeasibleFormParameters, _native.InvalidInput):
        return p  # designed as given: it is refused with its own reason
    boundary = _blend_boundary(plain)
    if boundary is None:
        return p
    profile = plain.description.curves["profile"]
    nose = _nose_clear_of(boundary, p)
    if nose >= profile.flat_to or nose < _least_dome_nose(profile.flat_from, p.lpp):
        return p  # clear at its own place, or no room under the flat keel: designed as given
    return replace(p, sonar_dome_nose=nose, notes=p.notes + [f"sonar dome's nose at x = {nose:.6g} m, aft of the bulb's blend"])


def _least_dome_nose(flat_from: float, lpp: float) -> float:
    """The dome's least nose (m from the AP): the whole dome under the flat keel, from flat_from."""
    return flat_from + DOME_LENGTH * lpp


def _nose_clear_of(boundary: np.ndarray, p: Particulars) -> float:
    """The dome's nose (m from the AP) DOME_BLEND_CLEARANCE Lpp aft of a blend boundary (k, 3)."""
    return _mm_down(float(boundary[:, 0].min()) - DOME_BLEND_CLEARANCE * p.lpp)


def _mm_down(x: float) -> float:
    """x (m) rounded down to the millimetre, for a limit a message names (so it never rounds past it)."""
    return math.floor(x * 1e3) / 1e3


def _mm_up(x: float) -> float:
    return math.ceil(x * 1e3) / 1e3


def _dome_clear_of_blend(hull: Hull, p: Particulars) -> Hull:
    """The hull, unless the blend between its bulb and the hull runs onto its sonar dome (its
    boundary on the hull below the base): then InfeasibleFormParameters naming what to give."""
    boundary = _blend_boundary(hull) if p.sonar_dome else None
    if boundary is None or boundary[:, 2].min() >= -DOME_ON_BLEND_TOL * p.draft:
        return hull
    nose, profile = _nose_clear_of(boundary, p), hull.description.curves["profile"]
    give = f"sonar_dome_nose at most {nose} m from the AP, " if nose >= _least_dome_nose(profile.flat_from, p.lpp) else ""
    raise _native.InfeasibleFormParameters(
        f"design_hull: the blend between bulb and hull runs onto the sonar dome (its boundary from x = "
        f"{boundary[:, 0].min():.6g} m): give {give}sonar_dome=False or bulb=False")


def _bulb_that_meets(hull: Hull, p: Particulars) -> Hull:
    """The hull, its designer-sized bulb run further aft (BULB_AFT_RETRIES) when the bulb meets
    the bare hull in more than one curve: a bulb that leaves a fine forefoot again before its
    aft end; and when no aft length lets the designer's bulb (bulb=True) meet it in one seam,
    the same bulb smaller (BULB_SCALE_RETRIES, named in the notes). A bulb whose aft length the
    user gave is left as given, one whose Kracht coefficients the user gave keeps its size.
    Raises InfeasibleFormParameters naming what to give when no variant meets the hull in one
    seam (the composition could not join them)."""
    given = p.bulb if isinstance(p.bulb, dict) else {}
    if hull.description.bulb is None:
        return hull
    fixed = "aft_length" in given.get("shape", {})
    factors = (None,) if fixed else (None, *BULB_AFT_RETRIES)
    scales = (1.0,) if given else (1.0, *BULB_SCALE_RETRIES)
    desc, asked, reason = None, None, ""
    for scale in scales:
        for factor in factors:
            if (scale, factor) != (1.0, None):
                if asked is None:  # the ship's volume and LCB; the bulb leaves the waterplane as matched
                    asked = (p.volume, p.lcb,
                             hull.hydrostatics(sac_stations=2, gauss=MATCH_GAUSS).waterplane_area)
                desc = desc or json.loads(hull.to_json())
                hull = Hull(HullDescription.from_dict(_bulb_variant(desc, p, scale, factor)))
                # the ship with this bulb matched again, then its seam checked on the hull as returned
                try:
                    _refuse_a_miss(match_targets(hull, want=asked))
                except _native.InfeasibleFormParameters as exc:
                    if len(scales) == 1:
                        raise _explained(exc, p) from exc
                    reason = reason or str(exc)  # a smaller bulb leaves the ends more of the volume
                    continue
            try:
                hull.blend_placement()  # kept: composed_hull uses it
                return hull
            except _native.NoBlendFits:  # the bulb meets the hull; the composition keeps the plain union
                return hull
            except _native.InvalidInput as e:
                if "cannot meet the hull" not in str(e):
                    return hull
                reason = reason or str(e)  # the full-size bulb's, as asked
    if p.sonar_dome:
        remedy = ("the sonar dome under the forefoot runs into the bulb's root: give a sonar_dome_nose further aft, "
                  "sonar_dome=False or bulb=False")
    elif given:
        remedy = "give bulb=False, a smaller bulb (its Kracht coefficients in bulb={'kracht': ...}) or bulb=True"
    else:
        remedy = (f"no bulb down to {min(scales):g} of the designer's size meets it: give bulb=False or a bulb's "
                  "Kracht coefficients (bulb={'kracht': ...})" + _fine_ends(p, "; "))
    if fixed:
        remedy += " or another bulb.shape.aft_length"
    raise _native.InfeasibleFormParameters(f"design_hull: the bulb cannot meet the hull in one seam ({reason}): {remedy}")


def _bulb_variant(desc: dict, p: Particulars, scale: float, factor: float | None) -> dict:
    """A copy of the designer's description `desc` whose bulb is scaled by `scale` (lengths;
    areas by its square, the volume by its cube: the same shape, a smaller size; noted) and runs
    `factor` (BULB_AFT_LENGTH when None) times L_PR + B_B into the hull."""
    out = copy.deepcopy(desc)
    k = out["bulb"]["kracht"]
    if scale != 1.0:
        for name, power in BULB_SCALE_POWERS.items():
            k[name] *= scale ** power
        out["notes"] += (f"; the bulb {scale:g} of the designer's size (Kracht coefficients "
                         + ", ".join(f"{n} {k[n]:.4g}" for n in KRACHT_NAMES)
                         + "): no aft length let the full-size bulb meet the hull in one seam")
    out["bulb"]["shape"]["aft_length"] = (factor or BULB_AFT_LENGTH) * (k["c_lpr"] * p.lpp + k["c_bb"] * p.breadth)
    return out


def _try_design(p: Particulars, keel_rise: float = KEEL_RISE) -> tuple[Hull | None, Exception | None]:
    """The hull designed from p, or the reason it is not. Where the default flat of bottom would
    narrow (its sections too fine for it: the SAC fits only the bands that narrow it, from a whole
    flat at one station to a tenth at the next) or the SAC refuses it, the hull is designed
    without one, and its notes say so."""
    try:
        hull = Hull(HullDescription.from_dict(design_description(p, keel_rise)))  # a fresh dict: no defensive copy
        _refuse_a_miss(match_targets(hull))
        if p.flat_bottom is None and min(d.flat_kept for d in hull.section_designs) < 1.0 - FLAT_KEPT_TOL:
            return _try_design(_without_flat(p, "a section would narrow it"), keel_rise)
        return hull, None
    except _native.InfeasibleFormParameters as exc:
        if p.flat_bottom is None and str(exc).startswith("basic_curves.sac"):
            return _try_design(_without_flat(p, "the SAC could not be met with it"), keel_rise)
        return None, exc


def _without_flat(p: Particulars, why: str) -> Particulars:
    note = f"no flat of bottom ({FLAT_BOTTOM_DEFAULT:g} of the waterline's half-breadth by default): {why}"
    return replace(p, flat_bottom=0.0, notes=p.notes + [note])


def _feasible_edge(p: Particulars) -> str:
    """For the first of the given Cwp, LCF, LCB, parallel body and a depth over TYPICAL_DEPTH T
    whose designer's default (the LCB: midships; the depth: TYPICAL_DEPTH T) builds with the
    others as given, the value nearest the given one that builds, by EDGE_STEPS bisections; ""
    when there is none."""
    for name in ("cwp", "lcf", "lcb", "parallel_length", "depth"):
        given = getattr(p, name)
        if given is None or (name == "depth" and given <= TYPICAL_DEPTH * p.draft):
            continue
        default = {"lcb": 0.5 * p.lpp, "depth": TYPICAL_DEPTH * p.draft}.get(name)
        good = replace(p, **{name: default})
        target = _value_of(good, name)
        if abs(given - target) < 1e-9 * p.lpp or _try_design(good)[0] is None:
            continue
        bad = given
        for _ in range(EDGE_STEPS):
            mid = 0.5 * (bad + target)
            if _try_design(replace(p, **{name: mid}))[0] is None:
                bad = mid
            else:
                target = mid
        unit = "" if name == "cwp" else " m"
        return f"; with the other particulars as given, {name} {target:.4g}{unit} builds (asked {given:.4g}{unit})"
    return ""


def _value_of(p: Particulars, name: str) -> float:
    """A particular's value as the designer takes it (given, or its default)."""
    if name in ("lcb", "depth"):
        return getattr(p, name)
    c = _coefficients(p)
    return c["parallel"][1] - c["parallel"][0] if name == "parallel_length" else c[name]


#: What to change when a basic curve designed from the particulars is infeasible.
_REMEDIES = {
    "sac": "the ends cannot hold this volume with its LCB: move lcb toward midships, lower cb, or give a "
           "longer parallel_length, a fuller cm or cwp (a deep hull: a smaller depth)",
    "dwl": "no fair waterline has this area and centroid: change cwp (or lcf), or give a parallel_length",
    "deck": "no fair deck line clears this waterline: raise depth or lower cwp",
    "profile": "no fair centre profile fits these ends: change stem_rake, depth or transom_immersion",
}


def _explained(exc: Exception, p: Particulars, edge: str = "") -> Exception:
    """The solver's message prefixed by the particulars involved and what to change."""
    curve = str(exc).split(":", 1)[0].removeprefix("basic_curves.")
    c = _coefficients(p)
    lcb_pct = 100 * (p.lcb - p.lpp / 2) / p.lpp
    said = (f"cb {p.cb:.4g}, lcb {p.lcb:.6g} m ({lcb_pct:+.2f} % Lpp from midships), cm {c['cm']:.4g}, "
            f"cwp {c['cwp']:.4g}, lcf {c['lcf']:.6g} m, parallel body {c['parallel'][1] - c['parallel'][0]:.4g} m")
    remedy = _REMEDIES.get(curve, "change the particulars")
    if curve == "profile" and "over the propeller" in str(exc):
        remedy = ("the run is too short to lift the hull over the propeller: give a smaller propeller_diameter, "
                  "move lcb forward or lower cb (a longer run)")
    fine = _fine_ends(p) if curve == "sac" else ""
    remedy = fine or remedy
    return type(exc)(f"design_hull: {said}: {remedy}{edge} ({exc})")


def _fine_ends(p: Particulars, prefix: str = "") -> str:
    """What to change, prefixed by `prefix`, when the ends outside p's parallel body would need
    a prismatic coefficient under FINE_ENDS_CP; else ""."""
    c = _coefficients(p)
    lp = (c["parallel"][1] - c["parallel"][0]) / p.lpp
    if lp <= 0 or (c["cp"] - lp) / (1 - lp) >= FINE_ENDS_CP:
        return ""
    shorter = max(0.0, (c["cp"] - FINE_ENDS_CP) / (1 - FINE_ENDS_CP)) * p.lpp  # ends of prismatic FINE_ENDS_CP
    return (f"{prefix}the ends outside this parallel body would need a prismatic coefficient of "
            f"{(c['cp'] - lp) / (1 - lp):.3f}: give a shorter parallel_length (at most {shorter:.4g} m leaves "
            f"them {FINE_ENDS_CP:g}), raise cb or move lcb toward midships")


def _refuse_a_miss(err: dict) -> None:
    """Raise InfeasibleFormParameters (naming the SAC) when match_targets' last relative errors
    `err` leave any of volume, LCB and waterplane area over MATCH_REFUSE: sections that cannot
    hold what the SAC asks stall the matching, and a hull off its particulars must not be
    returned as designed."""
    missed = {k: v for k, v in err.items() if not abs(v) <= MATCH_REFUSE}
    if missed:
        said = ", ".join(f"{k} {v:+.2e}" for k, v in missed.items())
        raise _native.InfeasibleFormParameters(f"basic_curves.sac: the surface stays off the asked {said} (relative; the "
                                               f"LCB on Lpp) after {MATCH_ITERATIONS} rebuilds: the sections cannot hold "
                                               "the sectional areas the SAC asks")


def match_targets(hull: Hull, tol: float = MATCH_TOL, want: tuple | None = None) -> dict:
    """Correct the SAC volume and LCB and the waterline's area by what the ship holds (rebuilds
    until within `tol`): the bare hull's surface, and with a bulb the bulb and blend's share of
    the volume and its moment too (_bulb_share), so the composed ship meets the volume and LCB.
    `want`: (volume m^3, LCB m, waterplane area m^2) to meet; by default the SAC's and the
    waterline's (the asked, before a first matching changes them). Returns the last relative
    errors."""
    d = hull.description
    pr = d.principal
    sac, dwl = d.curves["sac"], d.curves["dwl"]
    want_v, want_lcb, want_awp = want if want is not None else (
        sac.aliases.get("volume"), sac.aliases.get("lcb"), dwl.aliases.get("waterplane_area"))
    err, share, on = {}, (0.0, 0.0), None
    for _ in range(MATCH_ITERATIONS):
        h = hull.hydrostatics(sac_stations=2, gauss=MATCH_GAUSS)  # volume, LCB and Awp only: no SAC table
        if on is None:  # measured on the first build it can be, scaled with the bare hull's volume after it
            measured = _bulb_share(hull, h.volume)
            if measured is not None:
                share, on = measured, hull.bare_hull_surface()
        err = _ship_errors(h, share, want_v, want_lcb, want_awp, pr.lpp)
        close = max(abs(v) for v in err.values()) <= (max(tol, MATCH_TOL_BULB) if share[0] else tol)
        if close and share[0] and on is not hull.bare_hull_surface():  # verified on the hull as it is
            share, on = _bulb_share(hull, h.volume) or share, hull.bare_hull_surface()
            err = _ship_errors(h, share, want_v, want_lcb, want_awp, pr.lpp)
            close = max(abs(v) for v in err.values()) <= max(tol, MATCH_TOL_BULB)
        if close:
            break
        volume, lcb = _ship_volume_lcb(h, share)
        if want_v:
            sac.aliases["volume"] *= want_v / volume
        if want_lcb is not None:
            sac.aliases["lcb"] += want_lcb - lcb
        if want_awp:
            dwl.aliases["waterplane_area"] *= want_awp / h.waterplane_area
        hull._invalidate()
    return err


def _ship_volume_lcb(h, share: tuple) -> tuple[float, float]:
    """The ship's volume (m^3) and LCB (m): the bare hull's hydrostatics h plus the bulb's share
    (volume and moment over the bare hull's volume, see _bulb_share)."""
    return h.volume * (1.0 + share[0]), (h.lcb + share[1]) / (1.0 + share[0])


def _ship_errors(h, share: tuple, want_v, want_lcb, want_awp, lpp: float) -> dict:
    """Relative errors of the ship (_ship_volume_lcb) against the wanted volume, LCB (on Lpp)
    and waterplane area (the bulb leaves it the bare hull's)."""
    volume, lcb = _ship_volume_lcb(h, share)
    return {"volume": (volume - want_v) / want_v if want_v else 0.0,
            "lcb": (lcb - want_lcb) / lpp if want_lcb is not None else 0.0,
            "waterplane_area": (h.waterplane_area - want_awp) / want_awp if want_awp else 0.0}


def _bulb_share(hull: Hull, bare_volume: float) -> tuple[float, float] | None:
    """The bulb and blend's share of the ship below T as (volume, its moment about x = 0) over
    the bare hull's volume: the composed hull's mesh minus the bare hull's own mesh
    (fairlines.hydrostatics_composed.bulb_share); (0, 0) without a bulb. None when the bulb does
    not meet this hull in one seam: match_targets then measures it on the next build that it does
    meet (or keeps the share measured before, scaled), and _bulb_that_meets runs a bulb that meets
    none further aft and matches again. The bulb is sized from the bare hull's volume (Kracht's
    V_PR = c_vpr V), so the share keeps nearly its ratio to it as the matching changes the hull."""
    if hull.description.bulb is None:
        return 0.0, 0.0
    from .hydrostatics_composed import bulb_share

    try:
        composed, closed = hull.ship_meshes()
    except _native.InvalidInput:
        return None
    pr = hull.description.principal
    s = bulb_share(composed, closed, pr.draft, lpp=pr.lpp)
    return s["volume"] / bare_volume, s["mx"] / bare_volume
