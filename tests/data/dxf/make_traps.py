"""Writes the small DXF trap files next to this script, once (they are committed; rerun only
to change them): `.venv/bin/python tests/data/dxf/make_traps.py`.

Each file holds one trap; tests/drawings/test_dxf.py checks it against hand-computed
coordinates.
"""

from __future__ import annotations

import math
from pathlib import Path

import ezdxf

HERE = Path(__file__).parent


def mirrored_insert() -> ezdxf.document.Drawing:
    """Block B: LINE (0,0)-(2,0) and ARC centre (1,0) r 1 from 0° to 90°; INSERT at (10,0)
    with xscale −1."""
    doc = ezdxf.new("R2000", units=4)
    block = doc.blocks.new("B")
    block.add_line((0, 0), (2, 0))
    block.add_arc((1, 0), 1, 0, 90)
    doc.modelspace().add_blockref("B", (10, 0), dxfattribs={"xscale": -1})
    return doc


def extrusion_arc() -> ezdxf.document.Drawing:
    """ARC centre (10,5) r 2 from 0° to 90° in the OCS of extrusion (0,0,−1)."""
    doc = ezdxf.new("R2000", units=4)
    doc.modelspace().add_arc((10, 5), 2, 0, 90, dxfattribs={"extrusion": (0, 0, -1)})
    return doc


def nonuniform_circle() -> ezdxf.document.Drawing:
    """Block C: CIRCLE centre (0,0) r 1; INSERT at (5,5) with xscale 3, yscale 1."""
    doc = ezdxf.new("R2000", units=4)
    doc.blocks.new("C").add_circle((0, 0), 1)
    doc.modelspace().add_blockref("C", (5, 5), dxfattribs={"xscale": 3, "yscale": 1})
    return doc


def nested_insert() -> ezdxf.document.Drawing:
    """INNER (base (1,0)): LINE (1,0)-(2,0). OUTER (base (1,1)): INSERT INNER at (0,0)
    rotated 90°. Modelspace: INSERT OUTER at (10,10), scale 2, rotated 180°."""
    doc = ezdxf.new("R2000", units=4)
    inner = doc.blocks.new("INNER", base_point=(1, 0))
    inner.add_line((1, 0), (2, 0))
    outer = doc.blocks.new("OUTER", base_point=(1, 1))
    outer.add_blockref("INNER", (0, 0), dxfattribs={"rotation": 90})
    doc.modelspace().add_blockref(
        "OUTER", (10, 10), dxfattribs={"xscale": 2, "yscale": 2, "rotation": 180}
    )
    return doc


def minsert() -> ezdxf.document.Drawing:
    """Block L: LINE (0,0)-(1,0); MINSERT at (0,0) rotated 90°, 2 columns × 3 rows,
    column spacing 10, row spacing 5."""
    doc = ezdxf.new("R2000", units=4)
    doc.blocks.new("L").add_line((0, 0), (1, 0))
    ref = doc.modelspace().add_blockref("L", (0, 0), dxfattribs={"rotation": 90})
    ref.grid(size=(3, 2), spacing=(5, 10))  # (rows, columns), (row spacing, column spacing)
    return doc


def bulge_lwpolyline() -> ezdxf.document.Drawing:
    """Closed LWPOLYLINE (0,0) bulge 1 → (2,0) → (2,2) bulge −tan(22.5°) → (4,4)... see
    the test: a half circle, a line, a clockwise quarter arc, the closing line."""
    doc = ezdxf.new("R2000", units=4)
    doc.modelspace().add_lwpolyline(
        [(0, 0, 0, 0, 1), (2, 0, 0, 0, 0), (2, 2, 0, 0, -math.tan(math.pi / 8)), (4, 4, 0, 0, 0)],
        format="xyseb",
        close=True,
    )
    return doc


def inches() -> ezdxf.document.Drawing:
    """$INSUNITS 1 (inches); LINE (0,0)-(1,2)."""
    doc = ezdxf.new("R2000", units=1)
    doc.modelspace().add_line((0, 0), (1, 2))
    return doc


def frozen_layer() -> ezdxf.document.Drawing:
    """LINE on layer 0; LINE on frozen layer HIDDEN; LINE and CIRCLE on layer OFF (off)."""
    doc = ezdxf.new("R2000", units=4)
    doc.layers.add("HIDDEN").freeze()
    doc.layers.add("OFF").off()
    msp = doc.modelspace()
    msp.add_line((0, 0), (1, 0))
    msp.add_line((0, 1), (1, 1), dxfattribs={"layer": "HIDDEN"})
    msp.add_line((0, 2), (1, 2), dxfattribs={"layer": "OFF"})
    msp.add_circle((0, 0), 1, dxfattribs={"layer": "OFF"})
    return doc


def quarter_circle_spline() -> ezdxf.document.Drawing:
    """Rational quadratic SPLINE (1,0), (1,1), (0,1), weights 1, √½, 1: the unit quarter
    circle."""
    doc = ezdxf.new("R2000", units=4)
    doc.modelspace().add_rational_spline(
        [(1, 0), (1, 1), (0, 1)], [1.0, math.sqrt(0.5), 1.0], degree=2
    )
    return doc


def r12() -> ezdxf.document.Drawing:
    """R12 ASCII: LINE (0,0)-(3,4), ARC centre (0,0) r 1 from 270° to 90° (crossing 0°),
    CIRCLE centre (5,5) r 2, 2D POLYLINE (0,0) bulge 1 → (2,0)."""
    doc = ezdxf.new("R12")
    msp = doc.modelspace()
    msp.add_line((0, 0), (3, 4))
    msp.add_arc((0, 0), 1, 270, 90)
    msp.add_circle((5, 5), 2)
    polyline = msp.add_polyline2d([(0, 0), (2, 0)])
    polyline.vertices[0].dxf.bulge = 1.0
    return doc


TRAPS = {
    "mirrored_insert.dxf": mirrored_insert,
    "extrusion_arc.dxf": extrusion_arc,
    "nonuniform_circle.dxf": nonuniform_circle,
    "nested_insert.dxf": nested_insert,
    "minsert.dxf": minsert,
    "bulge_lwpolyline.dxf": bulge_lwpolyline,
    "inches.dxf": inches,
    "frozen_layer.dxf": frozen_layer,
    "quarter_circle_spline.dxf": quarter_circle_spline,
    "r12.dxf": r12,
}

if __name__ == "__main__":
    for name, make in TRAPS.items():
        make().saveas(HERE / name)
        print("wrote", HERE / name)
