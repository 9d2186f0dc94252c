"""ldi_frame.py PACK OUT TILE LEVEL DIRECTION FIELD VALUE...: copies the LDI pack PACK to OUT with
one field of one LDI's frame overwritten (docs/ldi-pack-format.md), as a damaged or hostile pack
would hold it. FIELD is one of FIELDS; a vector takes three values."""
import struct
import sys

# name: (offset in the 96-byte frame, struct format)
FIELDS = {"width": (0, "<I"), "height": (4, "<I"), "origin": (32, "<3f"), "right": (44, "<3f"),
          "up": (56, "<3f"), "forward": (68, "<3f"), "pixel_size": (80, "<f"), "depth_range": (84, "<f"),
          "azimuth": (88, "<f"), "elevation": (92, "<f")}

pack, out, tile, level, direction, field = sys.argv[1], sys.argv[2], *map(int, sys.argv[3:6]), sys.argv[6]
data = bytearray(open(pack, "rb").read())
levels, directions = struct.unpack_from("<2I", data, 20)
index_offset = struct.unpack_from("<Q", data, 56)[0]
entry = (tile * levels + level) * directions + direction
block = struct.unpack_from("<Q", data, index_offset + 16 * entry)[0]
at, fmt = FIELDS[field]
values = [float(v) if "f" in fmt else int(v) for v in sys.argv[7:]]
struct.pack_into(fmt, data, block + at, *values)
open(out, "wb").write(data)
