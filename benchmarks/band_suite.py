"""Road-margin bands over many held-out chunks, run in parallel, kept per chunk, compared between two trees.

    PYTHONPATH=src python benchmarks/band_suite.py run --tag new                 # the default chunks, 2 workers
    PYTHONPATH=src python benchmarks/band_suite.py run --tag new untuned         # campaigns never tuned on
    PYTHONPATH=src python benchmarks/band_suite.py run --tag new two:0:36 1Hz:0:12
    PYTHONPATH=src python benchmarks/band_suite.py compare base new              # pooled, per kind, question, effect

A chunk ``kind:start:n`` is *n* campaigns of :mod:`tests.uncertainty.band_questions` from *start*; *kind* is a
sampling (``5min``, ``1min``, ``15min``, ``irregular``, ``1Hz``, ``10Hz``: :func:`campaign_data`), ``rot`` + a
sampling (:func:`rotated_campaign_data`), ``two`` (:func:`two_effect_data`) or ``short`` (tests of 12–1200 s:
:func:`short_campaign_data`).  ``untuned`` runs :data:`UNTUNED` instead: 24 chunks of campaigns that no change to
the bands was measured on before it was made (1 670 questions).  Each chunk's rows are written to
``OUT/TAG/kind_start_n.json`` as soon as it ends, and a chunk already written is not run again, so an interrupted
suite keeps what it did and goes on from there.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))     # tests.uncertainty.band_questions

DEFAULT = ([f"5min:{s}:24" for s in range(0, 144, 24)] + [f"1min:{s}:24" for s in range(0, 96, 24)]
           + [f"15min:{s}:24" for s in range(0, 96, 24)] + ["irregular:0:24", "irregular:24:24"]
           + [f"rot5min:{s}:24" for s in range(0, 96, 24)] + [f"rot1min:{s}:24" for s in range(0, 48, 24)]
           + [f"rot15min:{s}:24" for s in range(0, 72, 24)] + [f"two:{s}:24" for s in range(0, 288, 24)]
           + ["1Hz:0:12", "1Hz:12:12", "10Hz:0:12"] + [f"short:{s}:12" for s in range(0, 48, 12)])
UNTUNED = (["5min:2000:24", "5min:2100:24", "1min:3000:24", "1min:3100:24", "15min:4000:24", "15min:4100:24",
            "irregular:900:24", "irregular:1000:24", "rot15min:500:24", "rot15min:700:24", "rot5min:600:24",
            "rot5min:800:24", "rot1min:900:24", "short:400:12", "short:500:12"]
           + [f"two:{s}:24" for s in (1200, 1224, 1248, 1300, 1324, 1348, 1372, 1396, 1420)])


def run_chunk(spec: str, path: str) -> tuple[str, float, int]:
    """Run chunk *spec*, write its rows to *path*; (spec, seconds, questions)."""
    from tests.uncertainty.band_questions import campaign
    kind, start, n = spec.split(":")
    t = time.perf_counter()
    rows = []
    for i in range(int(start), int(start) + int(n)):
        if kind == "two":
            rows += campaign(i, two=True)
        elif kind == "short":
            rows += campaign(i, short=True)
        elif kind.startswith("rot"):
            rows += campaign(i, sampling=kind[3:], rotated=True)
        else:
            rows += campaign(i, sampling=kind)
    for r in rows:
        r.update(kind=kind, covered=bool(r["covered"]))
    Path(path).write_text(json.dumps(rows))
    return spec, time.perf_counter() - t, len(rows)


def run(specs: list[str], out: Path, jobs: int) -> None:
    out.mkdir(parents=True, exist_ok=True)
    todo = [(s, out / (s.replace(":", "_") + ".json")) for s in specs]
    todo = [(s, p) for s, p in todo if not p.exists()]
    print(f"{len(specs) - len(todo)} chunks already in {out}; running {len(todo)}", flush=True)
    with ProcessPoolExecutor(jobs) as pool:
        futs = [pool.submit(run_chunk, s, str(p)) for s, p in todo]
        for f in as_completed(futs):
            s, sec, n = f.result()
            print(f"  {s}: {n} questions in {sec:.0f} s", flush=True)


def load(out: Path) -> dict:
    """{(kind, campaign, question): row} of every chunk under *out*."""
    rows = {}
    for p in sorted(out.glob("*.json")):
        for r in json.loads(p.read_text()):
            rows[(r["kind"], r["campaign"], r["question"])] = r
    return rows


def _cw(r: dict) -> bool:
    return (r["p5"] >= 1.0 > r["m_star"]) or (r["p95"] < 1.0 <= r["m_star"])


def summarise(rows: list[dict]) -> str:
    if not rows:
        return "-"
    cov = np.mean([r["covered"] for r in rows])
    hw = np.median([r["half_width"] for r in rows])
    return f"{cov:.3f} / {hw:.4f} / {sum(map(_cw, rows))} cw (n {len(rows)})"


def compare(root: Path, tags: list[str]) -> None:
    sets = [load(root / t) for t in tags]
    keys = set.intersection(*(set(s) for s in sets))
    print(f"{len(keys)} questions in all of {tags}")
    groups = {"pooled": lambda k: True}
    for kind in sorted({k[0] for k in keys}):
        groups[kind] = lambda k, kind=kind: k[0] == kind
    for q in sorted({k[2] for k in keys}):
        groups[q] = lambda k, q=q: k[2] == q
    hidden = lambda k: (sets[0][k]["hidden"] or "none").split("+")      # noqa: E731  (a pair counts for each)
    for e in sorted({e for k in keys for e in hidden(k)}):
        groups[e] = lambda k, e=e: e in hidden(k)
    for name, sel in groups.items():
        ks = [k for k in keys if sel(k)]
        print(f"{name:>19}: " + " | ".join(summarise([s[k] for k in ks]) for s in sets))
    for t, s in zip(tags, sets):
        for k in sorted(k for k in keys if _cw(s[k])):
            r = s[k]
            print(f"  cw {t} {k}: {r['hidden']} m* {r['m_star']:.3f} [{r['p5']:.3f}, {r['p95']:.3f}]")
    if len(sets) == 2:
        a, b = sets
        moved = [k for k in keys if abs(a[k]["p5"] - b[k]["p5"]) + abs(a[k]["p95"] - b[k]["p95"]) > 1e-4]
        flips = [k for k in moved if a[k]["covered"] != b[k]["covered"]]
        print(f"{len(moved)} bands moved; coverage changed in {len(flips)}:")
        for k in sorted(flips):
            print(f"  {k} {a[k]['hidden']}: m* {a[k]['m_star']:.3f} [{a[k]['p5']:.3f}, {a[k]['p95']:.3f}] → "
                  f"[{b[k]['p5']:.3f}, {b[k]['p95']:.3f}]")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("specs", nargs="*", help="kind:start:n chunks (default: the suite above)")
    r.add_argument("--tag", required=True)
    r.add_argument("--out", default=os.environ.get("BAND_SUITE_OUT", "/tmp/band_suite"))
    r.add_argument("--jobs", type=int, default=2)
    c = sub.add_parser("compare")
    c.add_argument("tags", nargs="+")
    c.add_argument("--out", default=os.environ.get("BAND_SUITE_OUT", "/tmp/band_suite"))
    a = ap.parse_args(argv)
    if a.cmd == "run":
        run(UNTUNED if a.specs == ["untuned"] else a.specs or DEFAULT, Path(a.out) / a.tag, a.jobs)
        compare(Path(a.out), [a.tag])
    else:
        compare(Path(a.out), a.tags)


if __name__ == "__main__":
    main()
