"""Existing hull data: offsets import (fairlines.offsets), rebuilt fair surfaces and
hydrostatics (fairlines.preprocess). Thin wrappers: the package does the work."""

import os

import bpy

from .. import engine, ids, props, report
from .base import HYDROSTATICS, FairlinesNode, NodeError, register

_FORMATS = [("auto", "Auto", "Decide from the path (folder contents or CSV header)"),
            ("offsets", "Offsets Table", "CSV, one row per station, one column per waterline"),
            ("sections", "Section Points", "CSV x, y, z in metres"),
            ("dtmb5415", "DTMB 5415 Grids", "Folder of the DTMB 5415 grid triples"),
            ("kcs", "KCS Tecplot", "Folder with kcs_bow2.dat and kcs_stn2.dat")]


@register
class FLNodeOffsetsImport(FairlinesNode, bpy.types.Node):
    """Read an offsets table, section list or reference grid folder into the project's metres (Lpp,
    beam and draft are needed for tables and section lists; switch them off for grid folders,
    which know their own)"""
    bl_idname = ids.NODE_OFFSETS_IMPORT
    bl_label = "Offsets Import"
    category = "Input"
    bl_width_default = 260
    inputs_spec = [(ids.SOCKET_LENGTH, "Lpp", {"default": 100.0, "optional": True}),
                   (ids.SOCKET_LENGTH, "Beam", {"default": 15.0, "optional": True}),
                   (ids.SOCKET_LENGTH, "Draft", {"default": 6.0, "optional": True})]
    outputs_spec = [(ids.SOCKET_HULL_DATA, "Hull Data")]
    params = ("filepath", "fmt")
    filepath: props.text("File", "", subtype="FILE_PATH")
    fmt: props.enum("Format", _FORMATS, "auto")

    def signature(self):
        # The file's time stamp and size belong to the key: saving the file re-reads it.
        path = bpy.path.abspath(self.filepath)
        try:
            st = os.stat(path)
            stamp = (st.st_mtime_ns, st.st_size)
        except OSError:
            stamp = None
        return super().signature() + (stamp,)

    def compute(self, inputs):
        engine.require()
        from fairlines import offsets
        if not self.filepath:
            raise NodeError("Choose an offsets file or grid folder")
        data = offsets.read_hull_data(bpy.path.abspath(self.filepath), inputs["Lpp"], inputs["Beam"],
                                      inputs["Draft"], fmt=self.fmt)
        blocks = "%d sections" % len(data.sections) if data.sections else "%d grids" % len(data.grids)
        info = "%s: %s\nLpp %.3f m, B %.3f m, T %.3f m" % (data.name, blocks, data.lpp, data.beam, data.draft)
        if data.notes:
            info += "\n%d repairs noted" % len(data.notes)
        return {"Hull Data": data, "__info__": info}


@register
class FLNodeRebuildSurface(FairlinesNode, bpy.types.Node):
    """Fair surfaces through imported hull data (sections skinned, grids faired by least
    squares); outputs the block chosen by Block, with the deviation from the input points"""
    bl_idname = ids.NODE_REBUILD
    bl_label = "Rebuild Surface"
    category = "Surfaces"
    bl_width_default = 240
    inputs_spec = [(ids.SOCKET_HULL_DATA, "Hull Data", {}),
                   (ids.SOCKET_INT, "Block", {"default": 0}),
                   (ids.SOCKET_INT, "Section Points", {"default": 61})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]
    params = ("deviation",)
    deviation: props.boolean("Deviation", True, "Measure the distance of every input point")

    def compute(self, inputs):
        engine.require()
        from fairlines import preprocess
        data = inputs["Hull Data"]
        if data is None:
            raise NodeError("Connect hull data (Offsets Import)")
        rb = preprocess.rebuild(data, n_v=inputs["Section Points"], deviation=self.deviation)
        k = inputs["Block"]
        if not 0 <= k < len(rb.surfaces):
            raise NodeError("Block %d; the data has %d (%s)" % (k, len(rb.surfaces), ", ".join(rb.names)))
        info = "%s (%s), %d of %d blocks" % (rb.names[k], rb.roles[k], k + 1, len(rb.surfaces))
        if rb.deviation:
            info += "\ndeviation max %.4g m, rms %.4g m" % (rb.deviation["max"], rb.deviation["rms"])
        return {"Surface": rb.surfaces[k], "__info__": info}


@register
class FLNodeHydrostatics(FairlinesNode, bpy.types.Node):
    """Hydrostatics of a half-hull surface below the draft (fl.hydrostatics: Gauss quadrature
    on the NURBS surface, both sides), coefficients on Lpp and Beam with the midship section
    at Lpp / 2, as Hull.hydrostatics does for a designed hull"""
    bl_idname = ids.NODE_HYDROSTATICS
    bl_label = "Hydrostatics"
    category = "Analysis"
    bl_width_default = 270
    inputs_spec = [(ids.SOCKET_SURFACE, "Surface", {}),
                   (ids.SOCKET_LENGTH, "Draft", {"default": 11.0}),
                   (ids.SOCKET_LENGTH, "Lpp", {"default": 244.8}),
                   (ids.SOCKET_LENGTH, "Beam", {"default": 32.25})]
    outputs_spec = [(ids.SOCKET_FLOAT, "Volume"), (ids.SOCKET_LENGTH, "LCB"),
                    (ids.SOCKET_FLOAT, "Cb"), (ids.SOCKET_FLOAT, "Wetted Surface")]

    def compute(self, inputs):
        fl, _ = engine.require()
        s = inputs["Surface"]
        if s is None:
            raise NodeError("Connect a hull surface")
        for name in ("Draft", "Lpp", "Beam"):
            if not inputs[name] > 0:
                raise NodeError("%s is %g m; expected > 0" % (name, inputs[name]))
        lpp = float(inputs["Lpp"])
        h = fl.hydrostatics(s, float(inputs["Draft"]), length=lpp, breadth=float(inputs["Beam"]), midship_x=lpp / 2)
        return {"Volume": float(h.volume), "LCB": float(h.lcb), "Cb": float(h.cb),
                "Wetted Surface": float(h.wetted_surface), HYDROSTATICS: h, "__info__": report.compact(h)}
