"""Wall time and peak memory of a rendered clip, through the CLI as a user runs it.

    python benchmarks/bench_render.py [--size 640x480] [--fps 30] [--repeat 3]

Runs ``rollaway simulate scenarios/hot-parking-rollaway.toml --render clip.mp4`` (a roll-away:
time-lapse, then real time) and the same command without ``--render``, each in a fresh process,
and prints the best wall time, the clip's length and frame count, and the peak resident memory
of the process (``ru_maxrss``; the ffmpeg encoder runs in its own process).  Wall times are also
given in reference units (benchmarks/reference.py, measured in the same run).
Targets: a 10 s clip at 640×480 and 30 fps in ≤ 10 s wall and ≤ 200 MB.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / "scenarios" / "hot-parking-rollaway.toml"


def run(args: list[str]) -> tuple[float, float]:
    """(wall s, peak RSS MB) of one `python -m rollaway ...` process; exits on a failed command."""
    t = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "rollaway", *args], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t
    code = proc.returncode = os.waitstatus_to_exitcode(status)
    if code not in (0, 1):                       # 1: the car rolled away, as this scenario should
        sys.exit(f"rollaway {' '.join(args)} failed with exit code {code}")
    return wall, usage.ru_maxrss / 1024.0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--fps", type=float, default=30.0)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from reference import reference_unit_s
    unit = reference_unit_s()
    print(f"reference unit: {unit:.3f} s (300 000 raw mj_step of a plain car)")
    with tempfile.TemporaryDirectory() as tmp:
        clip = Path(tmp) / "clip.mp4"
        render = ["simulate", str(SCENARIO), "--render", str(clip), "--size", args.size, "--fps", f"{args.fps:g}"]
        rows = []
        for name, cmd in (("simulate only", ["simulate", str(SCENARIO)]), (f"+ render {args.size} {args.fps:g} fps", render)):
            runs = [run(cmd) for _ in range(max(args.repeat, 1))]
            rows.append((name, min(r[0] for r in runs), max(r[1] for r in runs)))
        import imageio.v2 as imageio
        reader = imageio.get_reader(clip)
        meta = reader.get_meta_data()
        n_frames = reader.count_frames()
        reader.close()
    print(f"{'command':28s}{'wall_s':>8s}{'units':>7s}{'peak_MB':>9s}")
    for name, wall, mb in rows:
        print(f"{name:28s}{wall:8.2f}{wall / unit:7.2f}{mb:9.1f}")
    wall, mb = rows[1][1], rows[1][2]
    print(f"clip: {meta['duration']:.2f} s of video, {n_frames} frames at {meta['fps']:g} fps, "
          f"{meta['size'][0]}x{meta['size'][1]}; rendering added {wall - rows[0][1]:.2f} s "
          f"({n_frames / max(wall - rows[0][1], 1e-9):.0f} frames/s)")
    per_10s = wall / meta["duration"] * 10.0
    ok = mb <= 200.0 and per_10s <= 10.0
    print(f"peak {mb:.0f} MB ({'within' if mb <= 200 else 'OVER'} 200 MB); {per_10s:.2f} s wall per 10 s of video "
          f"({'within' if per_10s <= 10 else 'OVER'} 10 s)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
