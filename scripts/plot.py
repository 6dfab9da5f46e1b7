#!/usr/bin/python3
"""Every figure phongsim draws, from the data phongsim writes (docs/render.md, docs/exploration.md).

  plot.py grid --title T --columns C [C ...] --row LABEL IMAGE [IMAGE ...] [--row ...] --out PNG
      A labelled grid of PNG images: one row per --row (IMAGE "-" leaves a cell empty), one
      column header per --columns entry. A row whose label ends "(reference)" is set in bold.
  plot.py scanline --csv CSV --title T --out PNG
      Vlasic's eq. 6.3 illumination along one image row. CSV header "x,<curve>,<curve>...", one
      row per pixel column. A curve whose name ends "(reference)" is drawn thick and black.
  plot.py pareto --csv CSV --title T --x-label X --y-label Y --out PNG
      Error against area. CSV header "series,label,area,max_error,pareto", one row per point;
      pareto is 1 for the points on the Pareto front, which is drawn and whose points are labelled.
  plot.py cost --csv CSV --title T --out PNG
      Clocks per triangle against its pixels (render's <scene>_triangle_cycles.csv: header
      "method,backend,triangle,pixels,cycles,setup_cycles,empty_row_cycles"), a series per method
      and backend, with the line of one pixel per clock.
  plot.py study --csv CSV --title T --out PNG
      phongsim study's claims: a histogram per claim of its metric difference over the scenes
      (study.csv: "scene,mesh,shininess,lights" then "<claim>_holds,<claim>_diff" per claim).

Run with Debian's /usr/bin/python3 (package python3-matplotlib); phongsim runs it with the Python
it was configured with (base/paths.h). The PNG (8-bit RGB) is written to --out as given (phongsim passes a
temporary name and renames it). Any failure: one line on stderr, exit status 1, no PNG.
"""
import argparse
import csv
import math
import os
import sys

PROG = "plot.py"


class PlotError(Exception):
    """A problem with the input, reported as one line."""


# ---- styles: distinct colour, line style and marker for any number of series ----

COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
           "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"]  # Tableau 10
LINE_STYLES = ["-", "--", "-.", ":"]
MARKERS = ["o", "s", "^", "v", "D", "P", "X", "*"]


def series_style(i):
    """Style of series i: the colour cycles fastest; every 10 series the line style and marker
    change, so no two of the first 40 series look alike."""
    group = i // len(COLOURS)
    return {"color": COLOURS[i % len(COLOURS)],
            "linestyle": LINE_STYLES[group % len(LINE_STYLES)],
            "marker": MARKERS[(i + group) % len(MARKERS)]}


def is_reference(name):
    return name.endswith("(reference)")


# ---- input ----

def read_csv(path, header):
    """Rows of a CSV file as lists of strings, the header checked: `header` is the exact list of
    column names, or a callable that raises PlotError for a bad header."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise PlotError(f"cannot read {path}: {e.strerror}") from None
    if not rows:
        raise PlotError(f"{path}: empty file (expected a header line)")
    if callable(header):
        header(rows[0])
    elif rows[0] != header:
        raise PlotError(f"{path}:1: expected the header '{','.join(header)}', got "
                        f"'{','.join(rows[0])}'")
    for n, row in enumerate(rows[1:], start=2):
        if len(row) != len(rows[0]):
            raise PlotError(f"{path}:{n}: {len(row)} values, but the header has "
                            f"{len(rows[0])} columns")
    if len(rows) < 2:
        raise PlotError(f"{path}: no data rows")
    return rows


def number(text, path, line):
    try:
        v = float(text)
    except ValueError:
        raise PlotError(f"{path}:{line}: '{text}' is not a number") from None
    if not math.isfinite(v):
        raise PlotError(f"{path}:{line}: '{text}' is not a finite number")
    return v


# ---- figures ----

def figure_grid(args, plt):
    """Images at their own pixel size (scaled up by an integer factor when small), laid out on
    a pixel grid so nothing is resampled by a fraction."""
    import matplotlib.image as mpimg

    dpi = 100
    ncols = len(args.columns)
    rows = []
    for spec in args.row:
        label, files = spec[0], spec[1:]
        if not files:
            raise PlotError(f"grid row '{label}' has no image")
        if len(files) > ncols:
            raise PlotError(f"grid row '{label}' has {len(files)} images for {ncols} columns")
        images = []
        for f in files:
            if f == "-":
                images.append(None)
                continue
            try:
                images.append(mpimg.imread(f))
            except (OSError, ValueError, SyntaxError) as e:
                raise PlotError(f"cannot read image {f}: {e}") from None
        rows.append((label, images + [None] * (ncols - len(images))))
    if not rows:
        raise PlotError("grid: no --row given")

    col_w = [max((ims[c].shape[1] for _, ims in rows if ims[c] is not None), default=0)
             for c in range(ncols)]
    row_h = [max((im.shape[0] for im in ims if im is not None), default=0) for _, ims in rows]
    tallest = max(row_h)
    scale = max(1, min(4, 128 // max(1, tallest)))  # small renders: at least ~128 px a row

    fig = plt.figure(dpi=dpi)
    renderer = fig.canvas.get_renderer()

    def text_size(text, **kw):  # whole pixels, so every image lands on the pixel grid
        t = fig.text(0, 0, text, **kw)
        box = t.get_window_extent(renderer)
        t.remove()
        return math.ceil(box.width), math.ceil(box.height)

    label_font = {"fontsize": 11}
    label_w = max(text_size(label, fontweight="bold", **label_font)[0] for label, _ in rows)
    header_h = max(text_size(c, **label_font)[1] for c in args.columns) if args.columns else 0
    title_h = text_size(args.title, fontsize=15, fontweight="bold")[1] if args.title else 0
    pad = 10
    width = pad + label_w + pad + sum(w * scale + pad for w in col_w)
    height = pad + (title_h + pad if args.title else 0) + header_h + 6 + \
        sum(h * scale + pad for h in row_h)
    # Agg draws at most 2^16 pixels a side; stay well inside by shrinking the images.
    limit = 30000
    if max(width, height) > limit:
        scale *= limit / max(width, height)
        width = pad + label_w + pad + sum(w * scale + pad for w in col_w)
        height = pad + (title_h + pad if args.title else 0) + header_h + 6 + \
            sum(h * scale + pad for h in row_h)
    title_w = text_size(args.title, fontsize=15, fontweight="bold")[0] if args.title else 0
    width = max(width, title_w + 2 * pad)
    fig.set_size_inches(width / dpi, height / dpi)

    def box(x, y, w, h):  # pixels from the top-left -> figure fraction
        return [x / width, 1 - (y + h) / height, w / width, h / height]

    y = pad
    if args.title:
        fig.text(0.5, 1 - (y + title_h / 2) / height, args.title, ha="center", va="center",
                 fontsize=15, fontweight="bold")
        y += title_h + pad
    x0 = pad + label_w + pad
    x = x0
    for c, name in enumerate(args.columns):
        fig.text((x + col_w[c] * scale / 2) / width, 1 - (y + header_h / 2) / height, name,
                 ha="center", va="center", **label_font)
        x += col_w[c] * scale + pad
    y += header_h + 6
    for r, (label, images) in enumerate(rows):
        h = row_h[r] * scale
        fig.text((pad + label_w) / width, 1 - (y + h / 2) / height, label, ha="right",
                 va="center", fontweight="bold" if is_reference(label) else "normal",
                 **label_font)
        x = x0
        for c, im in enumerate(images):
            if im is not None:
                iw, ih = im.shape[1] * scale, im.shape[0] * scale
                ax = fig.add_axes(box(x + (col_w[c] * scale - iw) / 2, y + (h - ih) / 2, iw, ih))
                ax.imshow(im, interpolation="nearest", aspect="auto")
                ax.set_xticks([])
                ax.set_yticks([])
                for spine in ax.spines.values():
                    spine.set_color("#bbbbbb")
            x += col_w[c] * scale + pad
        y += h + pad
    return fig


def figure_scanline(args, plt):
    def check_header(header):
        if len(header) < 2 or header[0] != "x":
            raise PlotError(f"{args.csv}:1: expected the header 'x,<curve>,...', got "
                            f"'{','.join(header)}'")

    rows = read_csv(args.csv, check_header)
    names = rows[0][1:]
    xs = [number(r[0], args.csv, n) for n, r in enumerate(rows[1:], start=2)]
    curves = [[number(r[k + 1], args.csv, n) for n, r in enumerate(rows[1:], start=2)]
              for k in range(len(names))]

    # Leave out flat background at either end (columns where every curve has the value of the
    # end column), keeping a margin of it; nothing else is cut.
    def flat(i, end):
        return all(c[i] == c[end] for c in curves) and len({c[end] for c in curves}) == 1

    first, last = 0, len(xs) - 1
    while first < last and flat(first, 0):
        first += 1
    while last > first and flat(last, len(xs) - 1):
        last -= 1
    margin = max(2.0, 0.04 * (xs[-1] - xs[0]))
    lo, hi = max(xs[0], xs[first] - margin), min(xs[-1], xs[last] + margin)
    if hi <= lo:
        lo, hi = xs[0], xs[-1]
    if hi <= lo:
        lo, hi = lo - 1, hi + 1

    many = len(names) > 12
    fig, ax = plt.subplots(figsize=(13 if many else 11, 6.5 if many else 5.5), dpi=100)
    shown = [i for i, x in enumerate(xs) if lo <= x <= hi]
    every = max(1, len(shown) // 12)
    k = 0
    order = sorted(zip(names, curves), key=lambda nc: not is_reference(nc[0]))  # legend: ref first
    for name, values in order:
        if is_reference(name):
            ax.plot(xs, values, color="black", linewidth=2.6, label=name, zorder=1)
            continue
        style = series_style(k)
        ax.plot(xs, values, linewidth=1.3, label=name, zorder=2, markersize=4.5,
                markevery=(shown[0] + (k * every) // 7 % every if shown else 0, every), **style)
        k += 1
    ax.set_xlim(lo, hi)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("pixel column x")
    ax.set_ylabel("illumination I(x, y) = (R + G + B) / (3 \u00b7 255)   (eq. 6.3)")
    ax.set_title(args.title, fontsize=13, fontweight="bold")
    ax.grid(True, color="#dddddd", linewidth=0.6)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8.5 if many else 9.5,
              ncol=2 if len(names) > 24 else 1, frameon=False, handlelength=3.2)
    fig.tight_layout()
    return fig


def figure_cost(args, plt):
    rows = read_csv(args.csv, ["method", "backend", "triangle", "pixels", "cycles",
                               "setup_cycles", "empty_row_cycles"])[1:]
    series = {}
    for n, r in enumerate(rows, start=2):
        pixels, cycles = series.setdefault(f"{r[0]} [{r[1]}]", ([], []))
        pixels.append(number(r[3], args.csv, n))
        cycles.append(number(r[4], args.csv, n))
    if not series:
        raise PlotError(f"{args.csv}: no triangles")
    fig, ax = plt.subplots(figsize=(9, 6), dpi=100)
    top = 1.0
    for k, (name, (pixels, cycles)) in enumerate(series.items()):
        style = series_style(k)
        ax.plot(pixels, cycles, linestyle="none", marker=style["marker"], color=style["color"],
                markersize=4, alpha=0.6, label=name)
        top = max(top, max(pixels), max(cycles))
    ax.plot([0, top], [0, top], color="black", linewidth=1, label="one pixel per clock")
    ax.set_xlabel("pixels of the triangle")
    ax.set_ylabel("clocks on the unit (its rows set up, empty rows, pixels)")
    ax.set_title(args.title, fontsize=13, fontweight="bold")
    ax.grid(True, color="#dddddd", linewidth=0.6)
    ax.legend(loc="upper left", fontsize=9, frameon=False)
    fig.tight_layout()
    return fig


def figure_study(args, plt):
    rows = read_csv(args.csv, lambda header: None)
    header, rows = rows[0], rows[1:]
    claims = [h[:-len("_diff")] for h in header if h.endswith("_diff")]
    if (not claims or header[:4] != ["scene", "mesh", "shininess", "lights"]
            or any(c + "_holds" not in header for c in claims)):
        raise PlotError(f"{args.csv}:1: expected 'scene,mesh,shininess,lights,<claim>_holds,"
                        f"<claim>_diff,...', got '{','.join(header)}'")
    columns = 2
    lines = (len(claims) + columns - 1) // columns
    fig, axes = plt.subplots(lines, columns, figsize=(12, 2.6 * lines), dpi=100, squeeze=False)
    for k, claim in enumerate(claims):
        ax = axes[k // columns][k % columns]
        col = header.index(claim + "_diff")
        values = [number(r[col], args.csv, n) for n, r in enumerate(rows, start=2) if r[col]]
        # The judgement itself, not the rounded difference (a difference below 5e-7 prints as 0).
        hcol = header.index(claim + "_holds")
        holds = sum(1 for r in rows if r[hcol] == "1")
        if values:
            ax.hist(values, bins=30, color="#4878a8")
        ax.axvline(0, color="black", linewidth=1)
        ax.set_title(f"{claim}: holds in {holds} of {len(values)}", fontsize=10)
        ax.grid(True, color="#dddddd", linewidth=0.6)
    for k in range(len(claims), lines * columns):
        axes[k // columns][k % columns].axis("off")
    fig.suptitle(args.title, fontsize=12, fontweight="bold")
    fig.supxlabel("metric difference (colour correctness, eq. 6.1; > 0: the claim holds)")
    fig.tight_layout()
    return fig


def figure_pareto(args, plt):
    header = ["series", "label", "area", "max_error", "pareto"]
    rows = read_csv(args.csv, header)
    points = []
    for n, r in enumerate(rows[1:], start=2):
        if r[4] not in ("0", "1"):
            raise PlotError(f"{args.csv}:{n}: pareto must be 0 or 1, got '{r[4]}'")
        points.append({"series": r[0], "label": r[1], "area": number(r[2], args.csv, n),
                       "error": number(r[3], args.csv, n), "front": r[4] == "1"})
    areas = [p["area"] for p in points]
    errors = [p["error"] for p in points]
    log_x = min(areas) > 0 and max(areas) / min(areas) >= 10
    log_y = min(errors) > 0

    many = sum(p["front"] for p in points) > 8 or len(points) > 12
    fig, ax = plt.subplots(figsize=(13 if many else 10, 7 if many else 6), dpi=100)
    series = list(dict.fromkeys(p["series"] for p in points))  # in order of appearance
    for i, name in enumerate(series):
        style = series_style(i)
        mine = [p for p in points if p["series"] == name]
        ax.plot([p["area"] for p in mine], [p["error"] for p in mine], linestyle="none",
                marker=style["marker"], color=style["color"], markersize=7, label=name, zorder=3)
    front = sorted((p for p in points if p["front"]), key=lambda p: p["area"])
    if log_x:
        plain_log_axis(ax.xaxis, ax.set_xscale)
    if log_y:
        plain_log_axis(ax.yaxis, ax.set_yscale)
    ax.margins(x=0.12, y=0.12)
    if front:
        # The front as a staircase from the top edge to the right edge: at any area, the least
        # error some point of that area or less reaches; everything above and right of it is
        # dominated.
        (x_lo, x_hi), (y_lo, y_hi) = ax.get_xlim(), ax.get_ylim()
        xs, ys = [front[0]["area"]], [y_hi]
        for prev, p in zip([None] + front[:-1], front):
            if prev is not None:
                xs.append(p["area"])
                ys.append(prev["error"])
            xs.append(p["area"])
            ys.append(p["error"])
        xs.append(x_hi)
        ys.append(front[-1]["error"])
        ax.plot(xs, ys, color="black", linewidth=1.4, linestyle="--", zorder=2,
                label="Pareto front")
        ax.plot([p["area"] for p in front], [p["error"] for p in front], linestyle="none",
                marker="o", markersize=13, markerfacecolor="none", markeredgecolor="black",
                markeredgewidth=1.2, zorder=4)
        ax.set_xlim(x_lo, x_hi)
        ax.set_ylim(y_lo, y_hi)
    # Labels: every point of a small sweep, else the front's. When there are many, the points
    # carry their "#index" and a key beside the plot spells out the front.
    labelled = sorted(points if len(points) <= 12 else front, key=lambda p: p["area"])
    compact = len(labelled) > 8
    for j, p in enumerate(labelled):
        ax.annotate(p["label"].split()[0] if compact else p["label"], (p["area"], p["error"]),
                    textcoords="offset points", xytext=(7, 7 if j % 2 == 0 else -13),
                    fontsize=8, fontweight="bold" if p["front"] else "normal", zorder=5)
    if compact and front:
        ax.text(1.02, 1.0, "Pareto front, by area:\n" + "\n".join(p["label"] for p in front),
                transform=ax.transAxes, va="top", ha="left", fontsize=8, family="monospace")
    ax.set_xlabel(args.x_label + ("   (log scale)" if log_x else ""))
    ax.set_ylabel(args.y_label + ("   (log scale)" if log_y else ""))
    ax.set_title(args.title, fontsize=13, fontweight="bold")
    ax.grid(True, which="major", color="#dddddd", linewidth=0.6)
    ax.grid(True, which="minor", color="#f0f0f0", linewidth=0.5)
    ax.legend(loc="best", fontsize=9, framealpha=0.9)
    fig.tight_layout()
    return fig


def plain_log_axis(axis, set_scale):
    """A log axis whose tick labels are plain numbers ("0.002", "30000") rather than powers of
    ten, labelled where matplotlib's log formatter would label (minor ticks too when the axis
    spans few decades)."""
    from matplotlib import ticker

    class Plain(ticker.LogFormatterSciNotation):
        def __call__(self, x, pos=None):
            return f"{x:g}" if super().__call__(x, pos) else ""

    set_scale("log")
    axis.set_major_formatter(Plain())
    axis.set_minor_formatter(Plain(labelOnlyBase=False, minor_thresholds=(3, 1)))


FIGURES = {"grid": figure_grid, "scanline": figure_scanline, "pareto": figure_pareto,
           "cost": figure_cost, "study": figure_study}


def save_rgb_png(fig, path):
    """8-bit RGB, as phongsim's own images (matplotlib would write RGBA): the figure is drawn on
    opaque white, so dropping alpha loses nothing."""
    import numpy
    from PIL import Image

    fig.patch.set_facecolor("white")
    fig.canvas.draw()
    rgba = numpy.asarray(fig.canvas.buffer_rgba())
    Image.fromarray(rgba[:, :, :3]).save(path, format="PNG", optimize=True)


def parse_args(argv):
    p = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="figure", required=True)
    g = sub.add_parser("grid")
    g.add_argument("--title", default="")
    g.add_argument("--columns", nargs="+", required=True)
    g.add_argument("--row", nargs="+", action="append", required=True,
                   metavar=("LABEL", "IMAGE"))
    s = sub.add_parser("scanline")
    s.add_argument("--csv", required=True)
    s.add_argument("--title", default="")
    q = sub.add_parser("pareto")
    q.add_argument("--csv", required=True)
    q.add_argument("--title", default="")
    q.add_argument("--x-label", default="area")
    q.add_argument("--y-label", default="error")
    c = sub.add_parser("cost")
    c.add_argument("--csv", required=True)
    c.add_argument("--title", default="")
    t = sub.add_parser("study")
    t.add_argument("--csv", required=True)
    t.add_argument("--title", default="")
    for parser in (g, s, q, c, t):
        parser.add_argument("--out", required=True)
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"{PROG}: matplotlib is not installed for {sys.executable} (Debian package "
              "python3-matplotlib; scripts/setup.sh installs it)", file=sys.stderr)
        return 1
    writing = False
    try:
        fig = FIGURES[args.figure](args, plt)
        writing = True
        save_rgb_png(fig, args.out)
        return 0
    except Exception as e:  # one line whatever went wrong, and no (partial) output file
        if isinstance(e, PlotError):
            message = str(e)
        elif isinstance(e, OSError) and writing:
            message = f"cannot write {args.out}: {e.strerror}"
        else:
            message = f"{args.figure}: {type(e).__name__}: {e}"
        print(f"{PROG}: {message}".replace("\n", " "), file=sys.stderr)
        if writing and os.path.exists(args.out):
            os.remove(args.out)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
