#!/usr/bin/env python3
"""Draws docs/img/architecture.svg: skyview's pipeline stages (the folders of src/ and
include/skyview/) and which stage includes which, read from the #include lines themselves.

usage: python3 scripts/architecture_diagram.py [OUTPUT.svg]   (default docs/img/architecture.svg)

Stages are laid out in rows by dependency depth: a stage sits above every stage it includes, core
at the bottom. Stages that include each other (a cycle) share a row and are joined by a red
double arrow; the cycles are also printed. Arrows that others imply are left out, and core, which
every stage uses, is drawn as a bar under all.
Plain Python 3, no packages: the SVG is written by hand.
"""
import html
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
INCLUDE = re.compile(r'#include\s+"skyview/([a-z_]+)/')

# One line of main types per stage, shown under its name (the paragraphs of docs/architecture.md
# say more).
MAIN_TYPES = {
    "core": "Grid, Error, ProgressCounter",
    "raster": "Terrain, GeoReference, BandWriter",
    "solar": "SunPosition, SunEvents, Site",
    "dsm": "DsmOptions, PointCloud, LasReader",
    "sky": "SkyModel, ExposureMap, EpwFile",
    "preview": "PreviewSpec, ColourRamp",
    "horizon": "HorizonEngine, HorizonField",
    "sky_view": "SkyViewProducts, SvfRequest",
    "synthetic": "SyntheticDistrict",
    "points": "PointTable, PointQueryResult",
    "scene": "Scene, RayScene",
    "fisheye": "FisheyeView, ImageCircle",
    "exposure": "ExposureBands, ShadowBands",
    "benchmark": "BenchResult, ParetoPoint",
}


def stages():
    src = {p.name for p in (ROOT / "src").iterdir() if p.is_dir()}
    inc = {p.name for p in (ROOT / "include/skyview").iterdir() if p.is_dir()}
    return sorted(src | inc)


def dependencies(names):
    """stage -> the other stages its sources and public headers include."""
    deps = {s: set() for s in names}
    for s in names:
        for folder in (ROOT / "src" / s, ROOT / "include/skyview" / s):
            if not folder.is_dir():
                continue
            for f in folder.rglob("*"):
                if f.suffix not in (".h", ".cpp", ".inc") or not f.is_file():
                    continue
                for m in INCLUDE.finditer(f.read_text(errors="replace")):
                    if m.group(1) != s and m.group(1) in deps:
                        deps[s].add(m.group(1))
    return deps


def strongly_connected(deps):
    """Tarjan's components, each a sorted list; cycles are those of more than one stage."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(deps[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            out.append(sorted(comp))

    for v in sorted(deps):
        if v not in index:
            visit(v)
    return out


def layers(deps, components):
    """Row of each stage: 0 for stages that include none, else one above the highest it includes."""
    comp_of = {s: i for i, c in enumerate(components) for s in c}
    depth = {}

    def d(i):
        if i not in depth:
            depth[i] = 0
            below = {comp_of[w] for s in components[i] for w in deps[s]} - {i}
            depth[i] = max((d(j) + 1 for j in below), default=0)
        return depth[i]

    return {s: d(comp_of[s]) for s in deps}


def reduced(deps, components):
    """The edges no longer path implies (transitive reduction over the components), as
    stage -> stages: what a stage may use is then everything below it along the arrows."""
    comp_of = {s: i for i, c in enumerate(components) for s in c}
    succ = {i: set() for i in range(len(components))}
    for s, ts in deps.items():
        for t in ts:
            if comp_of[t] != comp_of[s]:
                succ[comp_of[s]].add(comp_of[t])

    def reachable(i, skip):
        seen, todo = set(), [j for j in succ[i] if j != skip]
        while todo:
            j = todo.pop()
            if j not in seen:
                seen.add(j)
                todo.extend(succ[j])
        return seen

    keep = {s: set() for s in deps}
    for s, ts in deps.items():
        for t in ts:
            if comp_of[t] == comp_of[s] or comp_of[t] not in reachable(comp_of[s], comp_of[t]):
                keep[s].add(t)
    return keep


def svg(deps, row, cycles):
    box_w, box_h, gap_x, gap_y, margin = 190, 48, 26, 70, 20
    rows = {}
    for s in sorted(deps, key=lambda s: (row[s], s)):
        rows.setdefault(row[s], []).append(s)
    widest = max(len(m) for m in rows.values())
    width = 2 * margin + widest * box_w + (widest - 1) * gap_x
    top_row = max(rows)
    height = 2 * margin + 70 + (top_row + 1) * box_h + top_row * gap_y + 40
    pos = {}
    cycle_of = {s: c for c in cycles for s in c}
    # Bottom up, each stage above the mean of the stages it includes (fewer crossing arrows); a
    # cycle's stages side by side.
    for r in sorted(rows):
        members = rows[r]

        def centre(s):
            below = [pos[t][0] for m in cycle_of.get(s, [s]) for t in deps[m] if t in pos and t != "core"]
            return sum(below) / len(below) if below else 0.0

        members.sort(key=lambda s: (centre(s), cycle_of.get(s, [s])[0], s))
        total = len(members) * box_w + (len(members) - 1) * gap_x
        x0 = (width - total) / 2
        y = margin + 70 + (top_row - r) * (box_h + gap_y)
        for i, s in enumerate(members):
            pos[s] = (x0 + i * (box_w + gap_x), y)
    in_cycle = {s for c in cycles for s in c}
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
        f'viewBox="0 0 {width} {height}" font-family="DejaVu Sans, Arial, sans-serif">',
        "<defs>",
        '<marker id="a" viewBox="0 0 10 10" refX="10" refY="5" markerWidth="7" markerHeight="7" '
        'orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="#555"/></marker>',
        '<marker id="c" viewBox="0 0 10 10" refX="10" refY="5" markerWidth="7" markerHeight="7" '
        'orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="#c0392b"/></marker>',
        "</defs>",
        f'<rect width="{width}" height="{height}" fill="white"/>',
        f'<text x="{margin}" y="{margin + 18}" font-size="18" font-weight="bold">skyview: pipeline stages '
        "(src/&lt;stage&gt;/, include/skyview/&lt;stage&gt;/)</text>",
        f'<text x="{margin}" y="{margin + 38}" font-size="12" fill="#444">An arrow runs from a stage to one it '
        "includes; a stage may use every stage below it along the arrows.</text>",
        f'<text x="{margin}" y="{margin + 54}" font-size="12" fill="#444">Arrows that others imply are left out. '
        "tools/ (the command line) uses every stage.</text>",
    ]
    # Edges first, under the boxes.
    for s in sorted(deps):
        for t in sorted(deps[s]):
            if t == "core":
                continue
            (xs, ys), (xt, yt) = pos[s], pos[t]
            if row[s] == row[t]:  # a cycle within one row: drawn once, both ways
                if s > t:
                    continue
                left, right = (s, t) if xs < xt else (t, s)
                (xl, yl), (xr, _) = pos[left], pos[right]
                y = yl + box_h / 2
                out.append(
                    f'<line x1="{xl + box_w}" y1="{y}" x2="{xr}" y2="{y}" stroke="#c0392b" stroke-width="2" '
                    'marker-start="url(#c)" marker-end="url(#c)"/>'
                )
                continue
            x1, y1 = xs + box_w / 2, ys + box_h
            x2, y2 = xt + box_w / 2, yt
            out.append(
                f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" stroke="#777" stroke-width="1.2" '
                'marker-end="url(#a)" opacity="0.8"/>'
            )
    for s, (x, y) in sorted(pos.items()):
        stroke = "#c0392b" if s in in_cycle else "#2c3e50"
        fill = "#fdecea" if s in in_cycle else "#eaf2f8"
        w = box_w
        types = MAIN_TYPES.get(s, "")
        if s == "core":  # under everything: a bar across the picture
            x, w = margin, width - 2 * margin
            fill, types = "#f4f6f7", types + " \u2014 used by every stage"
        out.append(f'<rect x="{x}" y="{y}" width="{w}" height="{box_h}" rx="6" fill="{fill}" '
                   f'stroke="{stroke}" stroke-width="1.5"/>')
        out.append(f'<text x="{x + w / 2}" y="{y + 20}" font-size="15" font-weight="bold" '
                   f'text-anchor="middle">{html.escape(s)}</text>')
        out.append(f'<text x="{x + w / 2}" y="{y + 38}" font-size="10.5" fill="#333" '
                   f'text-anchor="middle">{html.escape(types)}</text>')
    note = ("Cycle: " + "; ".join(" \u2194 ".join(c) for c in cycles)) if cycles else "No cycles."
    out.append(f'<text x="{margin}" y="{height - margin}" font-size="12" '
               f'fill="{"#c0392b" if cycles else "#444"}">{html.escape(note)} Generated by '
               "scripts/architecture_diagram.py from the #include lines.</text>")
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs/img/architecture.svg"
    names = stages()
    deps = dependencies(names)
    components = strongly_connected(deps)
    cycles = [c for c in components if len(c) > 1]
    row = layers(deps, components)
    target.write_text(svg(reduced(deps, components), row, cycles))
    for s in sorted(names, key=lambda s: (row[s], s)):
        print(f"{s:10} row {row[s]}: includes {', '.join(sorted(deps[s])) or '-'}")
    for c in cycles:
        print("cycle: " + " <-> ".join(c))
    print(f"wrote {target}")


if __name__ == "__main__":
    main()
