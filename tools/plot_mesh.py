#!/usr/bin/python3
"""Quick look at a loom frame: draws the cells of a .vtu (as loom writes them: appended raw, zlib
compressed, UInt32 headers) in the deformed configuration, coloured by a cell field, with the straight
corner edges of every cell and, for TRI6 cells, the curved edges through their mid-nodes.

  /usr/bin/python3 tools/plot_mesh.py FRAME.vtu [FRAME2.vtu ...] --out mesh.png [--field pressure]
        [--window x0 x1 y0 y1] [--title TEXT]

Several frames are drawn side by side. Python 3 with Debian's numpy and matplotlib (no VTK module needed).
"""
import argparse
import re
import struct
import zlib

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

VTK_TRIANGLE, VTK_QUADRATIC_TRIANGLE = 5, 22


def read_vtu(path):
    """Returns {name: array} for every DataArray (point, cell and geometry arrays) of a loom .vtu."""
    raw = open(path, "rb").read()
    head_end = raw.index(b"<AppendedData")
    data_start = raw.index(b"_", head_end) + 1
    head = raw[:head_end].decode()
    dtypes = {"Float64": "<f8", "Int64": "<i8", "UInt8": "u1", "Int32": "<i4", "UInt32": "<u4"}
    arrays = {}
    for m in re.finditer(r"<DataArray ([^>]*)>", head):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        pos = data_start + int(attrs["offset"])
        n_blocks, block, last = struct.unpack_from("<3I", raw, pos)
        sizes = struct.unpack_from(f"<{n_blocks}I", raw, pos + 12)
        pos += 12 + 4 * n_blocks
        chunks = []
        for s in sizes:
            chunks.append(zlib.decompress(raw[pos:pos + s]))
            pos += s
        a = np.frombuffer(b"".join(chunks), dtype=dtypes[attrs["type"]])
        nc = int(attrs.get("NumberOfComponents", "1"))
        arrays[attrs["Name"]] = a.reshape(-1, nc) if nc > 1 else a
    return arrays


def draw(ax, path, field, window, title):
    a = read_vtu(path)
    x = a["Points"][:, :2]
    conn, offs, types = a["connectivity"], a["offsets"], a["types"]
    starts = np.concatenate([[0], offs[:-1]])
    polys, straight, curved = [], [], []
    for s, e, t in zip(starts, offs, types):
        n = conn[s:e]
        corners = x[n[:3]]
        if t == VTK_QUADRATIC_TRIANGLE:
            # VTK order: corners 0 1 2, mid-nodes 01 12 20; each edge drawn as the parabola through its mid-node.
            outline = []
            for k in range(3):
                p0, pm, p1 = x[n[k]], x[n[3 + k]], x[n[(k + 1) % 3]]
                s_ = np.linspace(0, 1, 9)[:, None]
                outline.append((1 - s_) * (1 - 2 * s_) * p0 + 4 * s_ * (1 - s_) * pm + s_ * (2 * s_ - 1) * p1)
            outline = np.vstack(outline)
            polys.append(outline)
            curved.append(outline)
        else:
            polys.append(corners)
        straight.append(np.vstack([corners, corners[:1]]))
    values = a[field] if field in a and len(a[field]) == len(types) else None
    pc = PolyCollection(polys, array=values, cmap="coolwarm", edgecolors="none")
    ax.add_collection(pc)
    if values is not None:
        plt.colorbar(pc, ax=ax, shrink=0.8, label=field)
    if curved:
        ax.add_collection(LineCollection(curved, colors="k", linewidths=0.6))
        ax.add_collection(LineCollection(straight, colors="0.5", linewidths=0.4, linestyles=":"))
    else:
        ax.add_collection(LineCollection(straight, colors="k", linewidths=0.5))
    ax.plot(x[:, 0], x[:, 1], ".", ms=1.5, color="k")
    if window:
        ax.set_xlim(window[0], window[1])
        ax.set_ylim(window[2], window[3])
    else:
        ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_title(title or path.split("/")[-1], fontsize=9)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("frames", nargs="+")
    ap.add_argument("--out", required=True)
    ap.add_argument("--field", default="pressure")
    ap.add_argument("--window", type=float, nargs=4)
    ap.add_argument("--title", nargs="*")
    a = ap.parse_args()
    n = len(a.frames)
    fig, axes = plt.subplots(1, n, figsize=(6 * n, 5), squeeze=False)
    for k, (ax, f) in enumerate(zip(axes[0], a.frames)):
        draw(ax, f, a.field, a.window, a.title[k] if a.title and k < len(a.title) else None)
    fig.tight_layout()
    fig.savefig(a.out, dpi=130)


if __name__ == "__main__":
    main()
