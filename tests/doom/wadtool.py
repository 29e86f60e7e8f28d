#!/usr/bin/env python3
"""Doom WAD files for the node-builder tests, until bspbench reads WADs itself.

  wadtool.py maps WAD                  the map names, one a line
  wadtool.py extract WAD MAP OUT.wad   MAP's lumps alone as a PWAD
  wadtool.py counts WAD [MAP ...]      per map: the node format and, when vanilla,
                                       the NODES, SEGS and SSECTORS counts

Python standard library only, so it runs wherever the tests do.
"""
import re
import struct
import sys

# The lumps that belong to a map, in the order the engine expects after its marker; the GL_ lumps
# are glBSP's and ZDBSP's additions, kept so an extracted map keeps what a builder wrote.
MAP_LUMPS = ("THINGS", "LINEDEFS", "SIDEDEFS", "VERTEXES", "SEGS", "SSECTORS", "NODES", "SECTORS",
             "REJECT", "BLOCKMAP", "BEHAVIOR", "SCRIPTS")
MAP_NAME = re.compile(r"^(MAP\d\d|E\dM\d)$")
NODE_SIZE, SEG_SIZE, SSECTOR_SIZE = 28, 12, 4
# A NODES lump starting with one of these holds ZDoom's extended nodes, which vanilla cannot load.
EXTENDED_MAGIC = {b"XNOD": "extended", b"ZNOD": "compressed", b"XGLN": "extended-gl",
                  b"ZGLN": "compressed-gl", b"XGL2": "extended-gl2", b"ZGL2": "compressed-gl2"}


class WadError(Exception):
    pass


def read_wad(path):
    """(kind, [(name, bytes)]) in directory order."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 12 or data[:4] not in (b"IWAD", b"PWAD"):
        raise WadError(f"{path}: not a WAD file (no IWAD/PWAD header)")
    count, table = struct.unpack_from("<ii", data, 4)
    if count < 0 or table < 0 or table + 16 * count > len(data):
        raise WadError(f"{path}: directory of {count} lumps at {table} lies outside the file")
    lumps = []
    for i in range(count):
        pos, size, raw = struct.unpack_from("<ii8s", data, table + 16 * i)
        if pos < 0 or size < 0 or pos + size > len(data):
            raise WadError(f"{path}: lump {i} lies outside the file")
        lumps.append((raw.split(b"\0")[0].decode("ascii", "replace").upper(), data[pos:pos + size]))
    return data[:4].decode(), lumps


def write_wad(path, lumps, kind="PWAD"):
    header_size = 12
    body = b"".join(data for _, data in lumps)
    directory, pos = [], header_size
    for name, data in lumps:
        directory.append(struct.pack("<ii8s", pos, len(data), name.encode("ascii")))
        pos += len(data)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sii", kind.encode(), len(lumps), header_size + len(body)))
        f.write(body)
        f.write(b"".join(directory))


def is_map_lump(name):
    return name in MAP_LUMPS or name.startswith("GL_")


def map_names(lumps):
    return [name for name, _ in lumps if MAP_NAME.match(name)]


def map_lumps(lumps, map_name):
    """The marker and the lumps after it that belong to the map; WadError when it is absent."""
    for i, (name, _) in enumerate(lumps):
        if name == map_name:
            end = i + 1
            while end < len(lumps) and is_map_lump(lumps[end][0]):
                end += 1
            return lumps[i:end]
    raise WadError(f"no map {map_name}")


def lump(map_part, name):
    return next((data for n, data in map_part if n == name), None)


def node_counts(map_part):
    """{"format", "nodes", "segs", "ssectors"}; the counts only for vanilla nodes."""
    nodes = lump(map_part, "NODES") or b""
    magic = EXTENDED_MAGIC.get(nodes[:4])
    if magic:
        return {"format": magic}
    return {"format": "vanilla", "nodes": len(nodes) // NODE_SIZE,
            "segs": len(lump(map_part, "SEGS") or b"") // SEG_SIZE,
            "ssectors": len(lump(map_part, "SSECTORS") or b"") // SSECTOR_SIZE}


def main(argv):
    if len(argv) < 3 or argv[1] not in ("maps", "extract", "counts"):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    try:
        _, lumps = read_wad(argv[2])
        if argv[1] == "maps":
            print("\n".join(map_names(lumps)))
        elif argv[1] == "extract":
            if len(argv) != 5:
                raise WadError("extract needs WAD MAP OUT.wad")
            write_wad(argv[4], map_lumps(lumps, argv[3].upper()))
        else:
            for name in [m.upper() for m in argv[3:]] or map_names(lumps):
                counts = node_counts(map_lumps(lumps, name))
                print(name, " ".join(f"{k}={v}" for k, v in counts.items()))
    except (OSError, WadError) as e:
        print(f"wadtool: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
