"""A 2-D schematic of the DH frames of chapter 1: a top view (x_b-y_b) and a side view (x_b-z_b) of the arm at one
configuration, every frame drawn as short axis arrows with its name, the lengths ``a1``, ``a2``, ``d0`` as
dimension lines and the joint variables ``theta1``, ``theta2`` (arcs), ``d3`` (a dimension along the quill) and
``theta4`` (an arc) marked.

The labels are plotly annotations pinned to a point of the drawing and moved off it by an explicit offset in
pixels (``xshift``, ``yshift``, ``xanchor``, ``yanchor``). The offsets are chosen here, from boxes estimated
from each label's text and font size, so that no two labels overlap at any page width from a phone (390 px)
to the figure's own width: :func:`label_boxes` gives those boxes, and the tests use the same geometry.
"""
from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..errors import as_vector
from ..kinematics import link_frames
from ..params import ScaraParams
from ._common import AXIS_COLOURS, DASHES, PALETTE
from .layout import _text_width, finish_layout

__all__ = ["frames_figure", "label_boxes", "frame_labels", "FRAME_ORDER", "LABEL_SIZE", "CHECK_WIDTHS"]

#: the frames drawn, in the order of ``[b] + link_frames(q)``
FRAME_ORDER = ("b", "0", "1", "2", "3", "4", "e")
#: font size (px) of the labels
LABEL_SIZE = 13
#: page widths (px) at which the labels are placed and checked: a phone page, and plotly's default width
CHECK_WIDTHS = (390, 520, 700, 900)
_DEFAULT_Q = (math.radians(40), math.radians(-70), 0.3, math.radians(45))
_HEIGHT = 560
_MARGIN = dict(l=50, r=15, b=40)
_GAP = 0.14  # vertical gap between the panels, fraction of the plot area
_SPLIT = 0.5  # share of the plot area (without the gap) given to the top view


def frame_labels(points, names=FRAME_ORDER, tol: float = 1e-6):
    """Group frames whose points (N, 2) coincide within ``tol``: ``[(label, point), ...]``, e.g. ``"3, 4, e"``."""
    out = []
    for name, pt in zip(names, np.asarray(points, float)):
        for k, (lab, other) in enumerate(out):
            if np.hypot(*(other - pt)) < tol:
                out[k] = (lab + ", " + name, other)
                break
        else:
            out.append((name, pt))
    return out


# ------------------------------------------------------------------------------ page geometry (pixels)
def _panel_px(lay_ranges, width: int, height: int, top: int):
    """Pixel mapping of each panel at page ``width``: {panel: (x0_px, y0_px, scale px/m, xmin, ymin)} with y
    counted upwards from the bottom of the figure. Equal scales on both axes, the panel centred in its domain
    (plotly's ``scaleanchor`` with ``constrain="domain"``)."""
    W = width - _MARGIN["l"] - _MARGIN["r"]
    H = height - top - _MARGIN["b"]
    out = {}
    for panel, (xr, yr, dom_y) in lay_ranges.items():
        dw, dh = W, H * (dom_y[1] - dom_y[0])
        s = min(dw / (xr[1] - xr[0]), dh / (yr[1] - yr[0]))
        x0 = _MARGIN["l"] + (dw - s * (xr[1] - xr[0])) / 2
        y0 = _MARGIN["b"] + H * dom_y[0] + (dh - s * (yr[1] - yr[0])) / 2
        out[panel] = (x0, y0, s, xr[0], yr[0])
    return out


def _to_px(m, panel, x, y):
    x0, y0, s, xmin, ymin = m[panel]
    return x0 + s * (x - xmin), y0 + s * (y - ymin)


def _box(px, py, w, h, xs, ys, xanchor, yanchor):
    """Box (left, bottom, right, top) of a label of ``w`` x ``h`` px pinned at (px, py) and moved by (xs, ys)."""
    left = px + xs - {"left": 0.0, "center": w / 2, "right": w}[xanchor]
    bottom = py + ys - {"bottom": 0.0, "middle": h / 2, "top": h}[yanchor]
    return (left, bottom, left + w, bottom + h)


def _text_box_size(text: str, size: float):
    return _text_width(text, size) + 4.0, 1.35 * size + 2.0


def label_boxes(fig: go.Figure, width: int):
    """Boxes (left, bottom, right, top) in pixels, y upwards, of the labels (annotations named ``"label"``) of a
    :func:`frames_figure` shown ``width`` px wide: ``[(text, box), ...]``."""
    m = _panel_px(fig.layout.meta["panels"], width, fig.layout.height, fig.layout.margin.t)
    out = []
    for a in fig.layout.annotations:
        if a.name != "label":
            continue
        panel = "top" if a.xref == "x" else "side"
        px, py = _to_px(m, panel, a.x, a.y)
        w, h = _text_box_size(a.text, a.font.size)
        out.append((a.text, _box(px, py, w, h, a.xshift or 0, a.yshift or 0, a.xanchor, a.yanchor)))
    return out


def _overlap(b1, b2, pad=1.0):
    return b1[0] < b2[2] + pad and b2[0] < b1[2] + pad and b1[1] < b2[3] + pad and b2[1] < b1[3] + pad


def _candidates(prefer=None, near=(7, 16, 28, 44)):
    """Offsets (xs, ys, xanchor, yanchor) around a point, in the preferred direction first."""
    dirs = [(1, 1), (1, -1), (-1, 1), (-1, -1), (1, 0), (-1, 0), (0, 1), (0, -1)]
    if prefer is not None:
        ang = math.atan2(prefer[1], prefer[0])
        dirs.sort(key=lambda d: abs(math.remainder(math.atan2(d[1], d[0]) - ang, 2 * math.pi)))
    out = []
    for r in near:
        for dx, dy in dirs:
            xa = "left" if dx > 0 else "right" if dx < 0 else "center"
            ya = "bottom" if dy > 0 else "top" if dy < 0 else "middle"
            k = r / math.hypot(dx, dy)
            out.append((dx * k, dy * k, xa, ya))
    return out


# ------------------------------------------------------------------------------ the figure
#: (horizontal, vertical, toward-viewer) axes of the base frame in each view, and the sign of the toward-viewer one
_VIEWS = {"top": (0, 1, 2, +1.0), "side": (0, 2, 1, -1.0)}
_ROW = {"top": 1, "side": 2}
_REF = {"top": ("x", "y"), "side": ("x2", "y2")}
_DIMENSION_GREY = "#555555"


class _Drawing:
    """The two panels being drawn: the figure, the label requests ``ann`` ``[(panel, text, x, y, preferred
    direction)]``, the segments ``segs`` (data) the labels should avoid, and the arrowheads ``heads`` (drawn after
    the lines, one trace per panel, colour and size)."""

    def __init__(self, fig: go.Figure):
        self.fig = fig
        self.ann = []
        self.segs = {"top": [], "side": []}
        self.heads = {}  # (panel, colour, size): [(x, y, angle)]

    def line(self, panel, xs, ys, name, colour, *, width=2, dash="solid", showlegend=False, mode="lines",
             **kw):
        """A polyline (``None`` breaks it) added as a trace, its segments kept for the label placement."""
        self.fig.add_trace(go.Scatter(x=list(xs), y=list(ys), mode=mode, name=name, showlegend=showlegend,
                                      line=dict(color=colour, width=width, dash=dash), hoverinfo="skip", **kw),
                           row=_ROW[panel], col=1)
        for k in range(len(xs) - 1):
            if None not in (xs[k], xs[k + 1]):
                self.segs[panel].append(((xs[k], ys[k]), (xs[k + 1], ys[k + 1])))

    def markers(self, panel, points, name, colour, symbol):
        """Axis-perpendicular markers (a circle with a dot or a cross) at ``points`` (M, 2)."""
        g = np.array(points)
        self.fig.add_trace(go.Scatter(x=list(g[:, 0]), y=list(g[:, 1]), mode="markers", name=name, legendgroup=name,
                                      showlegend=False, marker=dict(symbol=symbol, size=13, color=colour,
                                                                    line=dict(width=1.5, color=colour)),
                                      hoverinfo="skip"), row=_ROW[panel], col=1)

    def label(self, panel, text, x, y, prefer=None):
        """Ask for a label at (x, y) (data), moved off it preferably along ``prefer``."""
        self.ann.append((panel, text, x, y, prefer))

    def arrowhead(self, panel, tail, tip, colour, size=9):
        # the "arrow" marker points up at angle 0 and turns clockwise; both axes have the same scale
        ang = 90.0 - math.degrees(math.atan2(tip[1] - tail[1], tip[0] - tail[0]))
        self.heads.setdefault((panel, colour, size), []).append((float(tip[0]), float(tip[1]), round(ang, 2)))

    def dimension(self, panel, a, b, text, normal):
        """A dimension line from a to b (data), arrowheads at both ends, its label on the ``normal`` side."""
        a, b = np.asarray(a, float), np.asarray(b, float)
        self.line(panel, [a[0], b[0]], [a[1], b[1]], text, _DIMENSION_GREY, width=1.2)
        self.arrowhead(panel, b, a, _DIMENSION_GREY, 8)
        self.arrowhead(panel, a, b, _DIMENSION_GREY, 8)
        mid = (a + b) / 2
        self.label(panel, text, mid[0], mid[1], normal)

    def arc(self, panel, centre, a0, a1, r, text, colour="#333333"):
        """An arc of radius ``r`` about ``centre`` turning from angle ``a0`` to ``a1`` (rad, in the view), with an
        arrowhead at ``a1`` and its label outside its middle; nothing for an angle under 1e-3 rad."""
        if abs(a1 - a0) < 1e-3:
            return
        t = np.linspace(a0, a1, 40)
        xs, ys = centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)
        self.line(panel, list(xs), list(ys), text, colour, width=1.5)
        self.arrowhead(panel, (xs[-3], ys[-3]), (xs[-1], ys[-1]), colour, 9)
        mid = 0.5 * (a0 + a1)
        self.label(panel, text, centre[0] + r * math.cos(mid), centre[1] + r * math.sin(mid),
                   (math.cos(mid), math.sin(mid)))

    def draw_heads(self):
        """The arrowheads collected, one marker trace per (panel, colour, size)."""
        for (panel, colour, size), hs in self.heads.items():
            h = np.array(hs)
            self.fig.add_trace(go.Scatter(x=list(h[:, 0]), y=list(h[:, 1]), mode="markers", showlegend=False,
                                          marker=dict(symbol="arrow", size=size, color=colour, angle=list(h[:, 2])),
                                          hoverinfo="skip"), row=_ROW[panel], col=1)


def _draw_arm(d: _Drawing, o):
    """The links through the base, frame 0, the elbow, the top of the quill and the gripper, in both views."""
    arm = np.array([[0.0, 0.0, 0.0], o[1], o[2], o[3], o[6]])
    for panel, (h, v, n, sgn) in _VIEWS.items():
        d.line(panel, arm[:, h], arm[:, v], "arm", PALETTE["arm"], width=6, showlegend=panel == "top",
               mode="lines+markers", marker=dict(size=7, color=PALETTE["arm"]))


def _draw_triads(d: _Drawing, frames, L: float):
    """The axes of every frame projected on each view, ``L`` m long, an axis seen end-on as a dot or a cross."""
    o = frames[:, :3, 3]
    for panel, (h, v, n, sgn) in _VIEWS.items():
        for k in range(3):
            xs, ys, tails, tips, dots, crosses = [], [], [], [], [], []
            for f in range(len(frames)):
                axis = frames[f, :3, k]
                proj = np.array([axis[h], axis[v]])
                org = np.array([o[f, h], o[f, v]])
                if np.hypot(*proj) < 0.3:
                    (dots if sgn * axis[n] > 0 else crosses).append(org)
                    continue
                end = org + L * proj
                xs += [org[0], end[0], None]
                ys += [org[1], end[1], None]
                tails.append(org + 0.7 * L * proj)
                tips.append(end)
            name = ("x", "y", "z")[k] + " axes"
            if xs:
                d.line(panel, xs, ys, name, AXIS_COLOURS[k], width=2.5, dash=DASHES[k],
                       showlegend=panel == "top" and k < 2, legendgroup=name)
            for tail, tp in zip(tails, tips):
                d.arrowhead(panel, tail, tp, AXIS_COLOURS[k], 10)
            for group, symbol in ((dots, "circle-open-dot"), (crosses, "circle-x-open")):
                if group:
                    d.markers(panel, group, name, AXIS_COLOURS[k], symbol)
    # a legend entry for the z axes (drawn as circles in the top view)
    d.fig.add_trace(go.Scatter(x=[None], y=[None], mode="lines", name="z axes", legendgroup="z axes",
                               line=dict(color=AXIS_COLOURS[2], width=2.5, dash=DASHES[2])), row=1, col=1)
    # frame labels: one per distinct origin in each view
    for panel, (h, v, n, sgn) in _VIEWS.items():
        for text, pt in frame_labels(o[:, [h, v]]):
            d.label(panel, text, pt[0], pt[1])


def _draw_top_marks(d: _Drawing, frames):
    """The top view's ``a1``, ``a2`` (dimension lines on the side away from the other link) and ``theta1``,
    ``theta2``, ``theta4`` (arcs from the reference direction to the moved one)."""
    o = frames[:, :3, 3]
    elbow, wrist, tip = o[2], o[3], o[6]
    u1 = elbow[:2] / np.linalg.norm(elbow[:2])
    d12 = wrist[:2] - elbow[:2]
    u2 = d12 / np.linalg.norm(d12)
    n1 = np.array([u1[1], -u1[0]])  # right of link 1
    n2 = np.array([u2[1], -u2[0]])
    if n2 @ (-u1) > 0:  # put a2's dimension on the side away from link 1
        n2 = -n2
    if n1 @ u2 > 0:
        n1 = -n1
    off = 0.09
    d.dimension("top", n1 * off, elbow[:2] + n1 * off, "a1", n1)
    d.dimension("top", elbow[:2] + n2 * off, wrist[:2] + n2 * off, "a2", n2)
    ang1 = math.atan2(u1[1], u1[0])  # = -theta1 (about -z_b)
    d.arc("top", (0.0, 0.0), 0.0, ang1, 0.2, "θ1")
    ang2 = math.atan2(u2[1], u2[0])
    ext = elbow[:2] + 0.24 * u1
    d.line("top", [elbow[0], ext[0]], [elbow[1], ext[1]], "link 1 extended", "#999999", width=1, dash="dot")
    d.arc("top", elbow[:2], ang1, ang1 + math.remainder(ang2 - ang1, 2 * math.pi), 0.17, "θ2")
    x3 = frames[4, :2, 0]
    x4 = frames[5, :2, 0]
    a3, a4 = math.atan2(x3[1], x3[0]), math.atan2(x4[1], x4[0])
    d.arc("top", tip[:2], a3, a3 + math.remainder(a4 - a3, 2 * math.pi), 0.1, "θ4")


def _draw_side_marks(d: _Drawing, o, q, p, xr_side):
    """The side view's ``d0`` and the quill's stroke ``d3`` (dimension lines) and the floor; returns the
    horizontal range of both views, widened to hold the ``d0`` dimension and to span at least 1.4 m."""
    side_left = min(0.0, o[:, 0].min())
    d.dimension("side", (side_left - 0.12, 0.0), (side_left - 0.12, p.d0), "d0", (-1.0, 0.0))
    tip = o[6]
    if q[2] > 1e-6:
        xq = tip[0] + (0.12 if tip[0] >= 0 else -0.12)
        d.dimension("side", (xq, p.d0), (xq, p.d0 - q[2]), "d3", (1.0 if tip[0] >= 0 else -1.0, 0.0))
    d.line("side", [xr_side[0], xr_side[1]], [0.0, 0.0], "floor", "#BBBBBB", width=1)
    xr = [min(xr_side[0], side_left - 0.3), xr_side[1]]
    span = xr[1] - xr[0]
    if span < 1.4:  # keep a narrow arm readable: at least 1.4 m across
        xr = [xr[0] - (1.4 - span) / 2, xr[1] + (1.4 - span) / 2]
    return xr


def _lay_out_views(fig: go.Figure, xr, yr_top, zr_side):
    """Equal scales on both axes of each view (``scaleanchor``, ``constrain="domain"``); returns the panels'
    ranges and domains ``{panel: (x range, y range, y domain)}``, also stored in ``layout.meta``."""
    fig.update_xaxes(range=list(xr), row=1, col=1, constrain="domain", zeroline=False)
    fig.update_yaxes(range=yr_top, row=1, col=1, title_text="y_b (m)", scaleanchor="x", scaleratio=1,
                     constrain="domain", zeroline=False)
    fig.update_xaxes(range=list(xr), row=2, col=1, title_text="x_b (m)", constrain="domain", zeroline=False)
    fig.update_yaxes(range=zr_side, row=2, col=1, title_text="z_b (m)", scaleanchor="x2", scaleratio=1,
                     constrain="domain", zeroline=False)
    panels = {"top": (list(xr), yr_top, tuple(fig.layout.yaxis.domain)),
              "side": (list(xr), zr_side, tuple(fig.layout.yaxis2.domain))}
    fig.update_layout(meta=dict(panels=panels))
    return panels


def frames_figure(q=None, p=None, triad: float = 0.18, height: int = _HEIGHT, title: str | None = None) -> go.Figure:
    """Schematic of the DH frames of the arm at ``q`` (default ``[40°, -70°, 0.3 m, 45°]``, the configuration of
    {numref}`fig-ch1-arm`): a top view (x_b-y_b, seen from +z_b) above a side view (x_b-z_b, seen from -y_b).

    Every frame ``b, 0, 1, 2, 3, 4, e`` is drawn at its origin (from :func:`scara.link_frames`) with its axes
    ``triad`` m long, projected on the view: x, y, z in ``AXIS_COLOURS`` (blue, vermilion, green) and dashed as
    ``DASHES`` (solid, dash, dot); an axis perpendicular to the view is a circle with a dot (out of the page) or a
    cross (into it). Frames whose origins coincide in a view share one label (``"3, 4, e"``). The top view marks
    ``a1``, ``a2`` with dimension lines and ``theta1``, ``theta2``, ``theta4`` with arcs, each turning from the
    reference direction to the moved one (a positive angle turns about the downward ``z_0``: clockwise seen from
    above); the side view marks ``d0`` and the quill's
    stroke ``d3``. Every label sits at an explicit pixel offset chosen so that no two labels overlap at page
    widths 390 to 900 px (:data:`CHECK_WIDTHS`).

    ``q`` (4,) in rad, rad, m, rad; ``p`` a :class:`~scara.ScaraParams` (``None``: the book's robot). Raises
    :class:`~scara.ScaraError` for a bad ``q`` or ``p``.

    >>> fig = frames_figure()
    >>> sorted({a.text for a in fig.layout.annotations if a.name == "label" and a.xref == "x"})[:3]
    ['1', '2, 3, 4, e', 'a1']
    """
    p = ScaraParams.resolve(p)
    q = as_vector(list(_DEFAULT_Q) if q is None else q, "q")
    frames = np.concatenate([np.eye(4)[None], link_frames(q, p)])  # b, 0, 1, 2, 3, 4, e (checks q)
    origins = frames[:, :3, 3]
    # ---- view ranges: the top view holds every origin and the base, the side view the column and the quill
    pts_top = np.vstack([origins[:, :2], [[0.0, 0.0]]])
    pad = 0.26
    xr_top = [min(pts_top[:, 0].min(), 0.0) - pad, max(pts_top[:, 0].max(), 0.0) + pad]
    yr_top = [pts_top[:, 1].min() - pad, pts_top[:, 1].max() + pad]
    zr_side = [-0.07, p.d0 + 0.16]
    ratio_top = (yr_top[1] - yr_top[0])
    ratio_side = (zr_side[1] - zr_side[0])
    split = ratio_top / (ratio_top + ratio_side)
    split = min(max(split, 0.3), 0.6)
    fig = make_subplots(rows=2, cols=1, vertical_spacing=_GAP, row_heights=[split, 1 - split],
                        subplot_titles=("top view, from above", "side view, from −y_b"))
    d = _Drawing(fig)
    _draw_arm(d, origins)
    _draw_triads(d, frames, float(triad))
    _draw_top_marks(d, frames)
    xr = _draw_side_marks(d, origins, q, p, xr_top)
    d.draw_heads()
    # ---- layout, then the labels placed at the page widths checked
    t1, t2, t4 = (round(math.degrees(v), 1) + 0.0 for v in (q[0], q[1], q[3]))
    head = title or (f"DH frames at θ1 = {t1:g}°, θ2 = {t2:g}°,<br>d3 = {q[2]:.2f} m, θ4 = {t4:g}°"
                     .replace("-", "−"))
    finish_layout(fig, head, height, subplot_titles=True)
    fig.update_layout(margin=dict(l=_MARGIN["l"], r=_MARGIN["r"], b=_MARGIN["b"]))
    panels = _lay_out_views(fig, xr, yr_top, zr_side)
    _place_frame_annotations(fig, d.ann, d.segs, panels, _REF)
    return fig


def _place_frame_annotations(fig, ann, segs, panels, ref):
    top = fig.layout.margin.t
    maps = {w: _panel_px(panels, w, fig.layout.height, top) for w in CHECK_WIDTHS}
    placed = {w: [] for w in CHECK_WIDTHS}
    # the drawing a label should not cover, sampled in pixels at each width
    samples = {}
    for w, m in maps.items():
        pts = {}
        for panel, ss in segs.items():
            arr = []
            for (a, b) in ss:
                for t in np.linspace(0, 1, 12):
                    arr.append(_to_px(m, panel, a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
            pts[panel] = np.array(arr)
        samples[w] = pts
    for panel, text, x, y, prefer in ann:
        w_txt, h_txt = _text_box_size(text, LABEL_SIZE)
        best, best_score = None, None
        for rank, cand in enumerate(_candidates(prefer)):
            ok, cover = True, 0
            for w, m in maps.items():
                px, py = _to_px(m, panel, x, y)
                b = _box(px, py, w_txt, h_txt, *cand)
                x0, y0, s, xmin, ymin = m[panel]
                xr, yr = panels[panel][0], panels[panel][1]
                inside = (b[0] >= x0 - 2 and b[2] <= x0 + s * (xr[1] - xr[0]) + 2 and b[1] >= y0 - 2
                          and b[3] <= y0 + s * (yr[1] - yr[0]) + 2)
                if not inside or any(_overlap(b, other, pad=2.0) for other in placed[w]):
                    ok = False
                    break
                sp = samples[w][panel]
                cover += int(np.sum((sp[:, 0] > b[0]) & (sp[:, 0] < b[2]) & (sp[:, 1] > b[1]) & (sp[:, 1] < b[3])))
            if not ok:
                continue
            score = cover + 0.6 * rank
            if best_score is None or score < best_score:
                best, best_score = cand, score
        if best is None:  # nothing free: the last resort is far off, above
            best = (0.0, 60.0, "center", "bottom")
        for w, m in maps.items():
            px, py = _to_px(m, panel, x, y)
            placed[w].append(_box(px, py, w_txt, h_txt, *best))
        xs, ys, xa, ya = best
        fig.add_annotation(x=float(x), y=float(y), xref=ref[panel][0], yref=ref[panel][1], text=text,
                           showarrow=False, xshift=round(xs, 1), yshift=round(ys, 1), xanchor=xa, yanchor=ya,
                           font=dict(size=LABEL_SIZE, color="#222222"), name="label",
                           bgcolor="rgba(255,255,255,0.75)")
