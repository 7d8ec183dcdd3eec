"""Reads the VTK XML files Krug writes (docs/outputs.md): UnstructuredGrid (.vtu, quadrilateral zones)
and PolyData (.vtp, particles), raw appended data, zlib-compressed or not, UInt32 or UInt64 headers,
ASCII arrays in FieldData. Returns an object with the fields the scripts use, named as meshio names
them: points, cells_dict["quad"], point_data[name], cell_data_dict[name]["quad"], field_data[name].

Krug's own reader rather than meshio's: meshio 5.0 (Debian 12) re-encodes raw appended data and
looks each array up again by its offset; when a re-encoded offset equals the original offset of a
later array it gives the data to the wrong array, and such a snapshot fails to read. It does not
read PolyData (.vtp) at all.
"""
import xml.etree.ElementTree as ET
import zlib

import numpy as np

_TYPES = {"Float64": np.float64, "Float32": np.float32, "Int32": np.int32, "Int64": np.int64,
          "UInt8": np.uint8, "Int8": np.int8, "UInt32": np.uint32, "UInt64": np.uint64}


class VtkData:
    def __init__(self):
        self.points = np.zeros((0, 3))
        self.cells_dict = {}
        self.point_data = {}
        self.cell_data_dict = {}
        self.field_data = {}


def read(path):
    raw = open(path, "rb").read()
    start = raw.find(b"<AppendedData")
    if start < 0:
        head, data = raw, b""
    else:
        open_end = raw.index(b">", start) + 1
        underscore = raw.index(b"_", open_end) + 1
        data = raw[underscore:]
        # The XML without the appended block: everything before it, and the closing tags after it.
        close = raw.rindex(b"</AppendedData>") + len(b"</AppendedData>")
        head = raw[:start] + raw[close:]
    root = ET.fromstring(head.decode())
    header = np.uint64 if root.get("header_type", "UInt32") == "UInt64" else np.uint32
    size = np.dtype(header).itemsize
    compressed = root.get("compressor") is not None

    def array(node):
        dtype = _TYPES[node.get("type")]
        components = int(node.get("NumberOfComponents", "1") or 1)
        if node.get("format") == "ascii":
            values = np.array(node.text.split(), dtype=dtype)
        else:
            offset = int(node.get("offset"))
            if compressed:
                blocks = int(np.frombuffer(data, header, 1, offset)[0])
                sizes = np.frombuffer(data, header, 3 + blocks, offset)[3:]
                at = offset + (3 + blocks) * size
                buffer = b""
                for s in sizes:
                    buffer += zlib.decompress(data[at:at + int(s)])
                    at += int(s)
            else:
                length = int(np.frombuffer(data, header, 1, offset)[0])
                buffer = data[offset + size:offset + size + length]
            values = np.frombuffer(buffer, dtype=dtype)
        return values.reshape(-1, components) if components > 1 else values

    out = VtkData()
    for node in root.iter("FieldData"):
        for a in node.findall("DataArray"):
            out.field_data[a.get("Name")] = array(a)
    piece = root.find(".//Piece")
    points = piece.find("Points/DataArray")
    if points is not None:
        out.points = array(points)
    cells = piece.find("Cells")
    if cells is not None:
        named = {a.get("Name"): array(a) for a in cells.findall("DataArray")}
        out.cells_dict["quad"] = named["connectivity"].reshape(-1, 4)
    for a in piece.findall("PointData/DataArray"):
        out.point_data[a.get("Name")] = array(a)
    for a in piece.findall("CellData/DataArray"):
        out.cell_data_dict[a.get("Name")] = {"quad": array(a)}
    return out
