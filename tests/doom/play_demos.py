#!/usr/bin/env python3
"""Plays an IWAD's demos on rebuilt maps and checks that the game runs exactly as on the shipped ones.

  play_demos.py --iwad freedoom2.wad --pwad REBUILT.wad [--demo DEMO1 ...] [--timeout S] [--draw]

For each DEMOn lump of the IWAD (or each --demo), Chocolate Doom plays the demo with -timedemo twice:
on the IWAD alone (the shipped nodes) and with -file REBUILT.wad. The two runs must count the same
gametics and reach the same game state. The gametic count alone proves little: the engine reads one
command per tic until the demo's end marker whatever happens in the game, so it only changes when
the engine crashes. The state is compared through savegames that the demo itself asks for: the
commands of 8 tics spread over the demo (the last one included) are replaced by the "save game"
special (vanilla lets any player's command carry it, and plays it back from demos), so each run
writes 8 snapshots of every mobj, player, sector and line, compared with pointers masked
(savegame.py). Vanilla reads the save special's bits as "use" for a dead player, so a snapshot at a
tic where the player lies dead restarts the level instead; both runs do the same when in sync.

Prints one line per demo; exits 0 only when every demo's map is in the PWAD and every demo matched,
1 when any did not, 2 on bad arguments or files. Chocolate Doom runs headless on SDL's dummy video
driver with -nodraw (the game logic walks the nodes in R_PointInSubsector and P_CheckSight; --draw
also renders every frame, about three times slower), with HOME, its config files and its save
directory in a temporary directory, so it never touches the user's files.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import savegame
import wadtool

SNAPSHOTS = 8   # the save special has 3 bits of slot
BT_SPECIAL, BTS_SAVEGAME, BTS_SAVESHIFT = 0x80, 0x02, 2
DEMO_MARKER = 0x80
TIMED = re.compile(r"timed (\d+) gametics in (\d+) realtics")


class HarnessError(Exception):
    pass


def find_engine():
    # Debian installs the engines in /usr/games, which a non-login PATH may lack.
    path = os.environ.get("PATH", "") + os.pathsep + "/usr/games"
    return shutil.which("chocolate-doom", path=path)


class Demo:
    """A vanilla demo lump: v1.9 (4-byte tics) or Doom 1.91 longtics (5-byte tics)."""

    def __init__(self, name, data, commercial):
        if len(data) < 14 or data[0] not in (109, 111):
            raise HarnessError(f"{name}: demo version {data[0] if data else None} is not 109 or 111")
        self.name, self.data = name, data
        skill, episode, game_map = data[1:4]
        self.map = f"MAP{game_map:02d}" if commercial else f"E{episode}M{game_map}"
        self.players = [i for i in range(4) if data[9 + i]]
        self.tic_size = (5 if data[0] == 111 else 4) * len(self.players)
        self.tics = self._count_tics()

    def _count_tics(self):
        pos = 13
        while pos < len(self.data) and self.data[pos] != DEMO_MARKER:
            pos += self.tic_size
        return (pos - 13) // self.tic_size

    def snapshot_tics(self):
        return sorted({max(0, self.tics * (k + 1) // SNAPSHOTS - 1) for k in range(SNAPSHOTS)})

    def probe(self):
        """The demo with the first player's command at each snapshot tic replaced by a save."""
        data = bytearray(self.data)
        for slot, tic in enumerate(self.snapshot_tics()):
            buttons = 13 + tic * self.tic_size + self.tic_size // len(self.players) - 1
            data[buttons] = BT_SPECIAL | BTS_SAVEGAME | (slot << BTS_SAVESHIFT)
        return bytes(data)


class Run:
    def __init__(self, gametics, snapshots, seconds, failure):
        self.gametics, self.snapshots, self.seconds, self.failure = gametics, snapshots, seconds, failure


def play(engine, iwad, pwad, demo, world_bytes, timeout, draw):
    with tempfile.TemporaryDirectory(prefix="play_demos.") as tmp:
        lmp, saves = os.path.join(tmp, "probe.lmp"), os.path.join(tmp, "saves")
        os.mkdir(saves)
        with open(lmp, "wb") as f:
            f.write(demo.probe())
        for name, text in (("default.cfg", ""), ("extra.cfg", "vanilla_savegame_limit 0\n")):
            with open(os.path.join(tmp, name), "w") as f:
                f.write(text)
        cmd = [engine, "-iwad", iwad, *(["-file", pwad] if pwad else []), "-nosound", "-nomusic",
               "-nogui", "-config", os.path.join(tmp, "default.cfg"), "-extraconfig",
               os.path.join(tmp, "extra.cfg"), "-savedir", saves, "-timedemo", lmp,
               *([] if draw else ["-nodraw"])]
        env = dict(os.environ, HOME=tmp, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy")
        start = time.monotonic()
        try:
            proc = subprocess.run(cmd, env=env, cwd=tmp, stdin=subprocess.DEVNULL, capture_output=True,
                                  timeout=timeout)
        except subprocess.TimeoutExpired:
            return Run(None, {}, time.monotonic() - start, f"no end within {timeout:g} s")
        seconds = time.monotonic() - start
        output = (proc.stdout + proc.stderr).decode("latin-1")
        timed = TIMED.search(output)
        if not timed:
            if proc.returncode < 0:
                return Run(None, {}, seconds, f"crashed (signal {-proc.returncode})")
            last = [line for line in output.splitlines() if line.strip()][-1:] or ["no output"]
            return Run(None, {}, seconds, f"no gametic count (exit {proc.returncode}): {last[0].strip()}")
        return Run(int(timed.group(1)), read_snapshots(saves, world_bytes), seconds, None)


def read_snapshots(saves, world_bytes):
    snapshots = {}
    for slot in range(SNAPSHOTS):
        path = os.path.join(saves, f"doomsav{slot}.dsg")
        if os.path.exists(path):
            with open(path, "rb") as f:
                snapshots[slot] = savegame.records(f.read(), world_bytes)
    return snapshots


def compare(demo, shipped, rebuilt):
    """(ok, message) for the two runs of one demo."""
    if shipped.failure:
        return False, f"the shipped nodes' run failed: {shipped.failure}"
    if rebuilt.failure:
        return False, rebuilt.failure
    if rebuilt.gametics != shipped.gametics:
        return False, f"{rebuilt.gametics} gametics, the shipped nodes {shipped.gametics}"
    if not shipped.snapshots:
        return False, "the shipped nodes' run wrote no snapshot to compare with"
    tics = demo.snapshot_tics()
    for slot in sorted(set(shipped.snapshots) | set(rebuilt.snapshots)):
        if (slot in shipped.snapshots) != (slot in rebuilt.snapshots):
            return False, f"desync: only one run saved at tic {tics[slot]}"
        difference = savegame.first_difference(shipped.snapshots[slot], rebuilt.snapshots[slot])
        if difference:
            return False, f"desync by tic {tics[slot]}: {difference}"
    return True, f"{shipped.gametics} gametics, {len(shipped.snapshots)} snapshots identical"


def world_bytes_of(lumps, map_name):
    part = wadtool.map_lumps(lumps, map_name)
    return savegame.world_size(wadtool.lump(part, "SECTORS") or b"", wadtool.lump(part, "LINEDEFS") or b"")


def demo_lumps(iwad_lumps, wanted):
    names = [n for n, _ in iwad_lumps if re.fullmatch(r"DEMO\d+", n)]
    missing = [w for w in wanted if w not in names]
    if missing:
        raise HarnessError(f"no demo {', '.join(missing)} in the IWAD (it has {', '.join(names) or 'none'})")
    return [n for n in names if not wanted or n in wanted]


def check_demo(args, engine, iwad_lumps, pwad_lumps, name):
    demo = Demo(name, wadtool.lump(iwad_lumps, name), "MAP01" in wadtool.map_names(iwad_lumps))
    if demo.map not in wadtool.map_names(pwad_lumps):
        return False, f"{name} {demo.map}: FAIL: the PWAD has no {demo.map}"
    shipped = play(engine, args.iwad, None, demo, world_bytes_of(iwad_lumps, demo.map), args.timeout, args.draw)
    rebuilt = play(engine, args.iwad, args.pwad, demo, world_bytes_of(pwad_lumps, demo.map), args.timeout,
                   args.draw)
    ok, message = compare(demo, shipped, rebuilt)
    return ok, (f"{name} {demo.map}: {'ok' if ok else 'FAIL'}: {message} "
                f"(shipped {shipped.seconds:.1f} s, rebuilt {rebuilt.seconds:.1f} s)")


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--iwad", required=True)
    parser.add_argument("--pwad", required=True, help="a PWAD with the rebuilt maps")
    parser.add_argument("--demo", action="append", default=[], help="play only this demo lump (repeatable)")
    parser.add_argument("--timeout", type=float, default=120, help="seconds per engine run")
    parser.add_argument("--draw", action="store_true", help="render every frame too")
    args = parser.parse_args(argv[1:])
    # The engine runs in a temporary directory.
    args.iwad, args.pwad = os.path.abspath(args.iwad), os.path.abspath(args.pwad)
    engine = find_engine()
    try:
        if not engine:
            raise HarnessError("chocolate-doom is not installed (not on PATH nor in /usr/games)")
        _, iwad_lumps = wadtool.read_wad(args.iwad)
        _, pwad_lumps = wadtool.read_wad(args.pwad)
        names = demo_lumps(iwad_lumps, [d.upper() for d in args.demo])
        if not names:
            raise HarnessError(f"{args.iwad}: no DEMOn lumps")
        results = []
        for name in names:
            ok, line = check_demo(args, engine, iwad_lumps, pwad_lumps, name)
            print(line, flush=True)
            results.append(ok)
    except (OSError, wadtool.WadError, savegame.SaveError, HarnessError) as e:
        print(f"play_demos: {e}", file=sys.stderr)
        return 2
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
