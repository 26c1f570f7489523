#!/usr/bin/env python3
"""Writes cfd/system/blockMeshDict and dem/nozzle.stl of the round plasma coating reactor: files
whose coordinates and cell counts are cosim template expressions of the scene's parameters
(R, H, hn, rn, a, b, s, nc, nr, nm, nrn, nz0, nz1), so the mesh follows --set on any of them
when a run folder is made. Run it again only to change the number of cells along the nozzle's
quarter circle (the one count a template cannot change, since it sets how many faces the files
list):

    python3 scenarios/plasma-coating-reactor/make_mesh.py [--nozzle-cells 4]

Topology (README.md of the scene), seen from above, from the axis out:
  - the nozzle: a square core of half-width a (NB x NB cells) and four blocks out to its circle
    of radius rn (nrn cells), 4 NB faces on the circle; it exists above the nozzle exit only
    (below it the nozzle is solid, its side the patch nozzleWall, its exit the patch nozzle);
  - four blocks from the nozzle's circle to the square of half-width b (nm cells);
  - around that square, eight blocks filling the square of half-width s (nc cells from b to s);
  - four times three blocks from that square out to the vessel's circle of radius R (nr cells),
    the wall divided evenly: 4 (2 nc + NB) faces on the circle.
Two layers: z = 0 .. hn (the plate to the nozzle exit, nz0 cells) and hn .. H (nz1 cells).
"""
import argparse
import pathlib

HERE = pathlib.Path(__file__).resolve().parent


def e(expr):
    """A template expression, or the number itself where there is nothing to compute."""
    try:
        float(expr)
        return expr
    except ValueError:
        return "${" + expr + "}"


def build(nb):
    # ---- the points of one level (x, y as template expressions) --------------------------------
    pts = {}
    # the square of half-width s, counter-clockwise from (-s, -s): corner, two splits, next corner
    xs = ["-s", "-b", "b", "s"]
    grid = {}  # (i, j) -> name, i/j over xs
    for i in range(4):
        for j in range(4):
            grid[(i, j)] = f"g{i}{j}"
            pts[f"g{i}{j}"] = (xs[i], xs[j])
    ring = [(0, 0), (1, 0), (2, 0), (3, 0), (3, 1), (3, 2), (3, 3), (2, 3), (1, 3), (0, 3), (0, 2), (0, 1)]
    sq = [grid[p] for p in ring]
    # the vessel's circle: corners on the diagonals, the splits at even angles (nc, NB, nc cells)
    frac = ["0", f"nc/(2*nc+{nb})", f"(nc+{nb})/(2*nc+{nb})"]
    oc = []
    for k in range(4):
        for f in frac:
            ang = f"pi*(-0.75+{0.5 * k:g}+0.5*{f})"
            name = f"o{len(oc)}"
            pts[name] = (f"R*cos({ang})", f"R*sin({ang})")
            oc.append(name)
    oc_mid = []
    for k in range(4):
        for f0, f1 in ((frac[0], frac[1]), (frac[1], frac[2]), (frac[2], "1")):
            ang = f"pi*(-0.75+{0.5 * k:g}+0.25*({f0}+{f1}))"
            oc_mid.append((f"R*cos({ang})", f"R*sin({ang})"))
    # the nozzle's circle (diagonals) and core square, counter-clockwise from (-, -)
    signs = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    N, A = [], []
    for k, (sx, sy) in enumerate(signs):
        pts[f"n{k}"] = (f"{sx}*rn/sqrt(2)", f"{sy}*rn/sqrt(2)")
        pts[f"a{k}"] = (f"{sx}*a", f"{sy}*a")
        N.append(f"n{k}")
        A.append(f"a{k}")
    n_mid = [("0", "-rn"), ("rn", "0"), ("0", "rn"), ("-rn", "0")]
    B = [grid[(1, 1)], grid[(2, 1)], grid[(2, 2)], grid[(1, 2)]]

    names = list(pts)
    index = {nm: i for i, nm in enumerate(names)}
    nv = len(names)
    levels = ["0", "hn", "H"]

    def vid(name, level):
        return index[name] + nv * level

    lines = []
    lines.append("FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }")
    lines.append("// Round vessel of radius R and height H with a round nozzle of radius rn protruding hn from the")
    lines.append("// centre of the plate, as nested O-grids (written by make_mesh.py, templated by cosim from the")
    lines.append("// scenario parameters, lengths in m; the scene's README draws the blocks).")
    lines.append("scale 1;")
    lines.append("vertices")
    lines.append("(")
    for lev, z in enumerate(levels):
        lines.append(f"    // z = {z}")
        for nm in names:
            x, y = pts[nm]
            lines.append(f"    ({e(x)} {e(y)} {e(z)})  // {nm} {vid(nm, lev)}")
    lines.append(");")

    blocks = []  # (layer, [4 names ccw], (cells1, cells2))
    seg = ["nc", str(nb), "nc"] * 4
    for i in range(12):
        for layer in (0, 1):
            blocks.append((layer, [sq[i], oc[i], oc[(i + 1) % 12], sq[(i + 1) % 12]], ("nr", seg[i]), "outer"))
    cx = ["nc", str(nb), "nc"]
    for i in range(3):
        for j in range(3):
            if (i, j) == (1, 1):
                continue
            for layer in (0, 1):
                q = [grid[(i, j)], grid[(i + 1, j)], grid[(i + 1, j + 1)], grid[(i, j + 1)]]
                blocks.append((layer, q, (cx[i], cx[j]), "core"))
    for k in range(4):
        for layer in (0, 1):
            blocks.append((layer, [N[k], B[k], B[(k + 1) % 4], N[(k + 1) % 4]], ("nm", str(nb)), "middle"))
        blocks.append((1, [A[k], N[k], N[(k + 1) % 4], A[(k + 1) % 4]], ("nrn", str(nb)), "nozzle"))
    blocks.append((1, A, (str(nb), str(nb)), "nozzle"))

    def hexline(layer, q, cells):
        v = [vid(nm, layer) for nm in q] + [vid(nm, layer + 1) for nm in q]
        nz = "nz0" if layer == 0 else "nz1"
        c = " ".join(e(x) for x in (*cells, nz))
        return f"    hex ({' '.join(map(str, v))}) ({c}) simpleGrading (1 1 1)"

    lines.append("blocks")
    lines.append("(")
    for layer, q, cells, _ in blocks:
        lines.append(hexline(layer, q, cells))
    lines.append(");")

    lines.append("edges")
    lines.append("(")
    for lev, z in enumerate(levels):
        for i in range(12):
            x, y = oc_mid[i]
            lines.append(f"    arc {vid(oc[i], lev)} {vid(oc[(i + 1) % 12], lev)} ({e(x)} {e(y)} {e(z)})")
        for k in range(4):
            x, y = n_mid[k]
            lines.append(f"    arc {vid(N[k], lev)} {vid(N[(k + 1) % 4], lev)} ({e(x)} {e(y)} {e(z)})")
    lines.append(");")

    def face(q, lev_a, lev_b=None):
        if lev_b is None:
            return "(" + " ".join(str(vid(nm, lev_a)) for nm in q) + ")"
        a, b = q
        return f"({vid(a, lev_a)} {vid(b, lev_a)} {vid(b, lev_b)} {vid(a, lev_b)})"

    def patch(name, kind, comment, faces):
        lines.append(f"    {name}  // {comment}")
        lines.append("    {")
        lines.append(f"        type {kind};")
        lines.append("        faces")
        lines.append("        (")
        for f in faces:
            lines.append(f"            {f}")
        lines.append("        );")
        lines.append("    }")

    lines.append("boundary")
    lines.append("(")
    # bottom faces listed clockwise seen from above: their normal points out of the gas (down)
    patch("distributor", "patch", "fluidization gas through the plate around the nozzle",
          [face(list(reversed(q)), 0) for layer, q, _, _ in blocks if layer == 0])
    patch("nozzle", "patch", "plasma and precursor gas at the nozzle's exit",
          [face(list(reversed(q)), 1) for layer, q, _, kind in blocks if kind == "nozzle"])
    patch("nozzleWall", "wall", "the nozzle's side between the plate and its exit",
          [face((N[(k + 1) % 4], N[k]), 0, 1) for k in range(4)])
    patch("outlet", "patch", "the top of the vessel",
          [face(q, 2) for layer, q, _, _ in blocks if layer == 1])
    patch("walls", "wall", "the vessel's round wall",
          [face((oc[i], oc[(i + 1) % 12]), lev, lev + 1) for lev in (0, 1) for i in range(12)])
    lines.append(");")
    return "\n".join(lines) + "\n"


def nozzle_stl(nb):
    """The nozzle for the grains: a closed prism on the mesh's nozzle polygon (4 nb corners on the
    circle of radius rn, from the diagonal at -135 degrees on), from the plate to its exit at hn,
    capped at the exit (the jet keeps the grains out; in the DEM they must not fall into the
    region that has no gas cells)."""
    m = 4 * nb

    def p(k, z):
        ang = f"pi*(-0.75+{k}/{2 * nb})"
        return (e(f"rn*cos({ang})"), e(f"rn*sin({ang})"), e(z))

    tris = []
    for k in range(m):
        b0, b1, t0, t1 = p(k, "0"), p(k + 1, "0"), p(k, "hn"), p(k + 1, "hn")
        tris.append((b0, b1, t1))
        tris.append((b0, t1, t0))
        tris.append((("0", "0", e("hn")), t0, t1))
    out = ["solid nozzle"]
    for t in tris:
        out.append("  facet normal 0 0 0")
        out.append("    outer loop")
        for v in t:
            out.append(f"      vertex {v[0]} {v[1]} {v[2]}")
        out.append("    endloop")
        out.append("  endfacet")
    out.append("endsolid nozzle")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nozzle-cells", type=int, default=4,
                    help="cells along each quarter of the nozzle's circle (default 4)")
    args = ap.parse_args()
    if args.nozzle_cells < 2:
        ap.error("--nozzle-cells: at least 2")
    (HERE / "cfd/system").mkdir(parents=True, exist_ok=True)
    (HERE / "dem").mkdir(parents=True, exist_ok=True)
    (HERE / "cfd/system/blockMeshDict").write_text(build(args.nozzle_cells))
    (HERE / "dem/nozzle.stl").write_text(nozzle_stl(args.nozzle_cells))


if __name__ == "__main__":
    main()
