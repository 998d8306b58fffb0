#!/usr/bin/env python3
"""Write the example drawings of sim/paths/ with ezdxf (docs/dxf2path.md):

- seed002_straight.dxf, seed002_two_segment.dxf, seed002_three_segment.dxf: the three test
  paths of seed 002 (its chapter 6; Path #1 from (2.5, 2) to (2.5, 7), Path #3 through (4, 2),
  (2.5, 4), (2.5, 7), Path #2 through (4, 2), (2.5, 4), (4, 6), (3, 7); metres, i.e. the
  seed's centimetres / 100), drawn as in its Appendix A: DXF R12, one old-style POLYLINE with
  VERTEX entities on layer "LAYER1".
- aisle_loop.dxf: a closed LWPOLYLINE (DXF R2010) around two racks with U-turns drawn as
  bulges (true semicircles, radius 1.5 m) and square corners left to the blending.

  sim/paths/make_paths.py [DIR]      (default: the directory of this script)
"""
import os
import sys

import ezdxf

SEED_PATHS = {
    "seed002_straight": [(2.5, 2.0), (2.5, 7.0)],
    "seed002_two_segment": [(4.0, 2.0), (2.5, 4.0), (2.5, 7.0)],
    "seed002_three_segment": [(4.0, 2.0), (2.5, 4.0), (4.0, 6.0), (3.0, 7.0)],
}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, pts in SEED_PATHS.items():
        doc = ezdxf.new("R12")
        doc.layers.add("LAYER1")
        doc.modelspace().add_polyline2d(pts, dxfattribs={"layer": "LAYER1"})
        doc.saveas(os.path.join(out, name + ".dxf"))
    doc = ezdxf.new("R2010")
    # (x, y, bulge): bulge 1 = a half circle counter-clockwise to the next vertex.
    loop = [(0.0, 0.0, 0.0), (12.0, 0.0, 1.0), (12.0, 3.0, 0.0), (3.0, 3.0, 0.0),
            (3.0, 6.0, 0.0), (12.0, 6.0, 1.0), (12.0, 9.0, 0.0), (0.0, 9.0, 0.0)]
    doc.modelspace().add_lwpolyline(loop, format="xyb", close=True)
    doc.saveas(os.path.join(out, "aisle_loop.dxf"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
