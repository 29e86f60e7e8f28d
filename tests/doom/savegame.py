"""The game state in a Chocolate Doom (vanilla v1.9 format) savegame, as comparable records.

A savegame stores raw 32-bit pointers (thinker links, mobj targets, the player's message), which
differ between two runs of the same game, so two saves are compared record by record with those
fields masked. Of the specials (moving floors, doors, lights) only the kind and the sector are
kept: vanilla leaves some of their fields uninitialised (a floor's newspecial and texture unless it
changes them), and what they do to their sector is in the world record anyway. The layout is Chocolate Doom's p_saveg.c, which writes vanilla's structures field
by field: header, players, world (sectors, lines), mobjs, then specials.
"""
import struct

HEADER_SIZE = 24 + 16 + 3 + 4 + 3   # description, version, skill/episode/map, players, leveltime
PLAYER_SIZE = 280
PLAYER_POINTERS = ((0, 4), (216, 4), (228, 4))   # mo, message, attacker
MOBJ_SIZE = 154
# thinker links and function, snext/sprev, bnext/bprev/subsector, info, target, tracer
MOBJ_POINTERS = ((0, 12), (24, 8), (44, 12), (92, 4), (120, 4), (150, 4))
# class: (size, offset of the sector index) of ceiling, door, floor, plat, flash, strobe, glow
SPECIALS = {0: (48, 16), 1: (40, 16), 2: (42, 20), 3: (56, 12), 4: (36, 12), 5: (36, 12), 6: (28, 12)}
SPECIAL_END, MOBJ_CLASS, THINKERS_END, SAVE_EOF = 7, 1, 0, 0x1D
SECTOR_RECORD, LINE_RECORD, SIDE_RECORD = 14, 6, 10


class SaveError(Exception):
    pass


def masked(data, pointers):
    out = bytearray(data)
    for offset, size in pointers:
        out[offset:offset + size] = bytes(size)
    return bytes(out)


def world_size(sectors_lump, linedefs_lump):
    """Bytes of P_ArchiveWorld for the map: fixed per sector, per line and per present side."""
    size = len(sectors_lump) // 26 * SECTOR_RECORD
    for i in range(0, len(linedefs_lump) - 13, 14):
        sides = struct.unpack_from("<hh", linedefs_lump, i + 10)
        size += LINE_RECORD + SIDE_RECORD * sum(1 for s in sides if s != -1)
    return size


class Reader:
    def __init__(self, data):
        self.data, self.pos = data, 0

    def take(self, n):
        if self.pos + n > len(self.data):
            raise SaveError(f"savegame ends at byte {len(self.data)}, inside a record")
        chunk = self.data[self.pos:self.pos + n]
        self.pos += n
        return chunk

    def pad(self):
        self.take(-self.pos & 3)


def records(data, world_bytes):
    """[(name, bytes)] of the state in the savegame, pointers zeroed."""
    r = Reader(data)
    header = r.take(HEADER_SIZE)
    out = [("header (skill, map, players, leveltime)", header[40:])]
    for player in range(4):
        if header[43 + player]:
            r.pad()
            out.append((f"player {player + 1}", masked(r.take(PLAYER_SIZE), PLAYER_POINTERS)))
    out.append(("world (sector heights, lights, line specials, textures)", r.take(world_bytes)))
    index = 0
    while (tclass := r.take(1)[0]) != THINKERS_END:
        if tclass != MOBJ_CLASS:
            raise SaveError(f"unknown thinker class {tclass} at byte {r.pos - 1}")
        r.pad()
        out.append((f"mobj {index}", masked(r.take(MOBJ_SIZE), MOBJ_POINTERS)))
        index += 1
    index = 0
    while (tclass := r.take(1)[0]) != SPECIAL_END:
        if tclass not in SPECIALS:
            raise SaveError(f"unknown special class {tclass} at byte {r.pos - 1}")
        r.pad()
        size, sector = SPECIALS[tclass]
        out.append((f"special {index} (class, sector)", bytes([tclass]) + r.take(size)[sector:sector + 4]))
        index += 1
    if r.take(1)[0] != SAVE_EOF:
        raise SaveError("no end-of-savegame marker")
    return out


# The fields where a record starts differing, by their first byte, for the messages.
PLAYER_FIELDS = {4: "playerstate", 8: "cmd", 16: "viewz", 20: "viewheight", 24: "deltaviewheight",
                 28: "bob", 32: "health", 36: "armorpoints", 40: "armortype", 44: "powers", 68: "cards",
                 92: "backpack", 96: "frags", 112: "readyweapon", 116: "pendingweapon", 120: "weaponowned",
                 156: "ammo", 172: "maxammo", 188: "attackdown", 192: "usedown", 196: "cheats",
                 200: "refire", 204: "killcount", 208: "itemcount", 212: "secretcount", 220: "damagecount",
                 224: "bonuscount", 232: "extralight", 236: "fixedcolormap", 240: "colormap",
                 244: "psprites", 276: "didsecret"}
MOBJ_FIELDS = {12: "x", 16: "y", 20: "z", 32: "angle", 36: "sprite", 40: "frame", 56: "floorz",
               60: "ceilingz", 64: "radius", 68: "height", 72: "momx", 76: "momy", 80: "momz",
               84: "validcount", 88: "type", 96: "tics", 100: "state", 104: "flags", 108: "health",
               112: "movedir", 116: "movecount", 124: "reactiontime", 128: "threshold", 132: "player",
               136: "lastlook", 140: "spawnpoint"}


def differing_fields(a, b, fields):
    starts = sorted(fields)
    names = []
    for i in (i for i in range(min(len(a), len(b))) if a[i] != b[i]):
        name = fields[max(s for s in starts if s <= i)]
        if name not in names:
            names.append(name)
    return ", ".join(names)


def describe_mobj(record):
    x, y, z = (v / 65536 for v in struct.unpack_from("<iii", record, 12))
    return f"type {struct.unpack_from('<i', record, 88)[0]} at ({x:.0f}, {y:.0f}, {z:.0f})"


def first_difference(expected, actual):
    """None when the two record lists hold the same state, else one line saying where they part."""
    for (name, a), (other, b) in zip(expected, actual):
        if name != other:
            return f"the rebuilt run has {other} where the shipped run has {name}"
        if a != b:
            if name.startswith("mobj"):
                return f"{name} ({describe_mobj(a)}) differs in {differing_fields(a, b, MOBJ_FIELDS)}"
            if name.startswith("player"):
                return f"{name} differs in {differing_fields(a, b, PLAYER_FIELDS)}"
            return f"{name} differs"
    if len(expected) != len(actual):
        return f"the rebuilt run has {len(actual)} records, the shipped run {len(expected)}"
    return None
