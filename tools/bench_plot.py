#!/usr/bin/env python3
"""Draws the peer comparison of `tools/bench_peers.sh` as an SVG bar chart (standard library
only; the SVG is written by hand).

    python3 tools/bench_plot.py [CBOX_JSON [HEAVY_JSON]] [-o SVG]

CBOX_JSON is the `timings.json` of a cbox run (`run_peers.py`: one record per renderer with
`peer`, `samples_per_s_render`, `wall_median_s`); default `docs/bench/cbox_timings.json`.
HEAVY_JSON, when given, is the `heavy_timings.json` of a heavy run (`run_heavy.py`: one
record per renderer and scene size, with `ttfp_median_s` and `render_median_s`); its largest
scene gets two more panels. The output (default `docs/images/performance.svg`) has one panel
per measure: a bar per renderer, its value, and its ratio to mira's written on the bar
("2.0 × mira": for samples/s more is better, for times less is). The same JSON always gives
the same file, byte for byte.
"""

import argparse
import json
import os
import sys
from xml.sax.saxutils import escape

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Layout, in SVG user units (pixels).
WIDTH = 720
LABEL_W = 190  # renderer names, left of the bars
BAR_H = 22
BAR_GAP = 8
PANEL_TITLE_H = 26
PANEL_GAP = 18
RIGHT_PAD = 150  # room for the value and ratio written after the longest bar
MIRA_COLOUR = "#d9534f"
PEER_COLOUR = "#5b7db1"


def renderer_name(record):
    """A readable name for a renderer's record: mira, or the peer with its version and
    variant as its child process reported them."""
    peer = record.get("peer", "?")
    child = record.get("child") or {}
    if peer == "mira":
        return "mira"
    if peer.startswith("mitsuba"):
        version = child.get("version", "")
        variant = child.get("variant", peer.split("_", 1)[-1])
        return ("Mitsuba %s %s" % (version, variant)).replace("  ", " ")
    if peer == "cycles":
        return ("Cycles %s" % child.get("version", "")).strip()
    return peer


def panel(title, unit, rows, better, fmt):
    """A panel: `rows` is [(name, value, is_mira)], `better` "higher" or "lower"."""
    return dict(title=title, unit=unit, rows=rows, better=better, fmt=fmt)


def cbox_panels(records, label):
    ok = [r for r in records if "failed" not in r]
    samples = [(renderer_name(r), r.get("samples_per_s_render"), r.get("peer") == "mira") for r in ok]
    wall = [(renderer_name(r), r.get("wall_median_s"), r.get("peer") == "mira") for r in ok]
    first = ok[0] if ok else {}
    setup = "%s², %s spp, %s threads" % (first.get("res", "?"), first.get("spp", "?"), first.get("threads", "?"))
    return [
        panel("%s (%s): render samples per second (millions; higher is better)" % (label, setup),
              "M", [(n, v / 1e6 if v else None, m) for n, v, m in samples], "higher", "%.2f M"),
        panel("%s: whole-process wall time (seconds, median; lower is better)" % label,
              "s", wall, "lower", "%.2f s"),
    ]


def heavy_panels(records):
    ok = [r for r in records if "failed" not in r and r.get("triangles")]
    if not ok:
        return []
    largest = max(r["triangles"] for r in ok)
    rows = [r for r in ok if r["triangles"] == largest]
    label = "heavy scene (%.1f M triangles)" % (largest / 1e6)
    first = rows[0]
    setup = "%s², %s spp, %s threads" % (first.get("res", "?"), first.get("spp", "?"), first.get("threads", "?"))
    return [
        panel("%s: time to first pixel (seconds, median; lower is better)" % label, "s",
              [(renderer_name(r), r.get("ttfp_median_s"), r.get("peer") == "mira") for r in rows], "lower", "%.2f s"),
        panel("%s (%s): render time (seconds, median; lower is better)" % (label, setup), "s",
              [(renderer_name(r), r.get("render_median_s"), r.get("peer") == "mira") for r in rows], "lower",
              "%.2f s"),
    ]


def draw(panels, note):
    """The SVG text of `panels` stacked vertically, `note` written under them."""
    out = []
    y = 10
    body = []
    for p in panels:
        rows = [r for r in p["rows"] if r[1] is not None]
        body.append('<text x="10" y="%d" class="title">%s</text>' % (y + 16, escape(p["title"])))
        y += PANEL_TITLE_H
        if not rows:
            body.append('<text x="%d" y="%d" class="note">no figures</text>' % (LABEL_W, y + 15))
            y += BAR_H + PANEL_GAP
            continue
        top = max(v for _, v, _ in rows)
        mira = next((v for _, v, m in rows if m), None)
        span = WIDTH - LABEL_W - RIGHT_PAD
        for name, value, is_mira in rows:
            w = max(1.0, span * value / top) if top > 0 else 1.0
            colour = MIRA_COLOUR if is_mira else PEER_COLOUR
            body.append('<text x="%d" y="%d" class="name">%s</text>' % (LABEL_W - 8, y + 15, escape(name)))
            body.append('<rect x="%d" y="%d" width="%.1f" height="%d" fill="%s"/>' % (LABEL_W, y, w, BAR_H, colour))
            text = p["fmt"] % value
            if mira:
                ratio = value / mira
                text += "   %s × mira" % ("1" if is_mira else "%.2f" % ratio)
            body.append('<text x="%.1f" y="%d" class="value">%s</text>' % (LABEL_W + w + 6, y + 15, escape(text)))
            y += BAR_H + BAR_GAP
        y += PANEL_GAP
    if note:
        body.append('<text x="10" y="%d" class="note">%s</text>' % (y + 4, escape(note)))
        y += 14
    height = y + 6
    out.append('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d" '
               'font-family="sans-serif">' % (WIDTH, height, WIDTH, height))
    out.append("<style>.title{font-size:13px;font-weight:bold;fill:#222}.name{font-size:12px;"
               "text-anchor:end;fill:#222}.value{font-size:12px;fill:#222}.note{font-size:11px;fill:#555}"
               "</style>")
    out.append('<rect width="100%" height="100%" fill="white"/>')
    out.extend(body)
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("cbox", nargs="?", default=os.path.join(ROOT, "docs", "bench", "cbox_timings.json"))
    ap.add_argument("heavy", nargs="?", help="heavy_timings.json of a heavy run (optional)")
    ap.add_argument("-o", "--out", default=os.path.join(ROOT, "docs", "images", "performance.svg"))
    ap.add_argument("--note", default="tools/bench_peers.sh: medians of fresh processes in one interleaved run; "
                    "ratios are to mira's figure in the same run.")
    a = ap.parse_args(argv)
    with open(a.cbox) as f:
        panels = cbox_panels(json.load(f), "Cornell box")
    if a.heavy:
        with open(a.heavy) as f:
            panels += heavy_panels(json.load(f))
    svg = draw(panels, a.note)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out, "w") as f:
        f.write(svg)
    print("wrote %s" % a.out)


if __name__ == "__main__":
    main(sys.argv[1:])
