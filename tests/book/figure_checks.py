"""What a reader sees in a built page's figures, measured in the browser: :func:`figure_problems` runs every
check on a loaded, settled page (``page_checks.settle``) and returns human-readable problems (empty when the
figures are clean).

Each check is a JavaScript function evaluated in the page (some are ``async``: they press a figure's buttons or
redraw a 3-D scene and put it back as it was):

- ``LABELS_AT_MARKERS``: a text label naming a point (text drawn on a marker trace, an annotation anchored at
  a marker, 2-D or 3-D) sits next to its own marker: its box is within a few pixels of the marker as drawn and
  no other marker is nearer to it (an arrowed annotation must point at its own marker alone);
- ``LABELS_ON_CURVES``: a text label (annotation or text drawn on a trace) whose box is crossed by a drawn
  line of the figure;
- ``TICK_OVERLAPS``: tick labels that run into each other, or into a subplot title, an annotation or an axis
  title;
- ``LONG_AXIS_TITLES``: an axis title longer than its axis (a y title taller than its panel);
- ``DROPDOWN_TITLES``: a dropdown (an updatemenu that is not Play/Pause) whose choices leave the figure's
  title the same (the title must say what is shown);
- ``SCENE_TEXT``: a 3-D scene whose axis title is not drawn, or whose axis title or tick labels are cut at the
  edge of the scene (its WebGL canvas is redrawn with one text recoloured at a time and compared with the
  scene as it was, so that each text's pixels are found exactly).

``page_checks.py`` runs them with the other checks, in the browser test or alone on a build.
"""
from __future__ import annotations


# helpers shared by the checks: a figure's name, a label's visible box, distances between boxes and points
_COMMON = r"""
  const nameOf = (gd) => {
    const f = gd.closest('figure');
    return (f && f.id) || gd.id
      || ('plot ' + (Array.from(document.querySelectorAll('.plotly-graph-div')).indexOf(gd) + 1) + ' of the page');
  };
  const visibleBox = (el) => {
    const r = el.getBoundingClientRect();
    if (r.width < 1 || r.height < 1 || !el.textContent.trim()) return null;
    for (let e = el; e && e.nodeType === 1; e = e.parentElement) {
      const s = getComputedStyle(e);
      if (s.display === 'none' || s.visibility === 'hidden' || parseFloat(s.opacity) === 0) return null;
    }
    return r;
  };
  const boxDist = (b, p) => Math.hypot(Math.max(b.left - p[0], 0, p[0] - b.right),
                                       Math.max(b.top - p[1], 0, p[1] - b.bottom));
  const short = (s) => s.replace(/\s+/g, ' ').trim().slice(0, 40);
  // a 3-D scene redrawn, and its pixels read back
  const pixels = (sc) => {
    sc.glplot.redraw();
    const gl = sc.glplot.gl, w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    const px = new Uint8Array(w * h * 4); gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    return {px, w, h};
  };
  const axisOf = (gd, id) => gd._fullLayout[id.replace(/^([xy])/, '$1axis')];
"""

# A label sits next to its own marker: its box is within NEAR px of the marker's centre as drawn, and no other
# marker is nearer to the box. 2-D markers are the drawn points (their centres); 3-D markers are projected as
# plotly projects scene annotations; 3-D trace text is drawn in WebGL, so each label is found by redrawing the
# scene with only that label, recoloured, and comparing with the scene as it was.
LABELS_AT_MARKERS = "async () => {" + _COMMON + r"""
  const NEAR = 20, out = [];
  const judge = (fig, text, box, own, others, arrow) => {
    if (arrow) {
      const hit = others.find(m => Math.hypot(m[0] - own[0], m[1] - own[1]) < 4);
      if (hit) out.push(`${fig}: the arrow of "${text}" points at another marker too`);
      return;
    }
    const d = boxDist(box, own);
    if (d > NEAR) out.push(`${fig}: label "${text}" is ${Math.round(d)} px from its marker`);
    const nearer = others.filter(m => boxDist(box, m) < d - 0.5);
    if (nearer.length)
      out.push(`${fig}: label "${text}" is nearer to another marker (${Math.round(boxDist(box, nearer[0]))} px)`
               + ` than to its own (${Math.round(d)} px)`);
  };
  const centre = (el) => { const r = el.getBoundingClientRect(); return [(r.left + r.right) / 2, (r.top + r.bottom) / 2]; };
  // the scene's projection, as plotly places a scene annotation
  const projector = (gd, sid) => {
    const fl = gd._fullLayout, sl = fl[sid], sc = sl._scene, size = fl._size, dom = sl.domain;
    const svg = gd.querySelector('.main-svg').getBoundingClientRect();
    const cp = sc.glplot.cameraParams, ds = sc.dataScale;
    const mul = (m, v) => { const r = [0, 0, 0, 0];
      for (let i = 0; i < 4; i++) for (let n = 0; n < 4; n++) r[n] += m[4 * i + n] * v[i]; return r; };
    return (x, y, z) => {
      const p = mul(cp.projection, mul(cp.view, mul(cp.model,
        [sl.xaxis.r2l(x) * ds[0], sl.yaxis.r2l(y) * ds[1], sl.zaxis.r2l(z) * ds[2], 1])));
      return [svg.left + size.l + dom.x[0] * size.w + 0.5 * (1 + p[0] / p[3]) * size.w * (dom.x[1] - dom.x[0]),
              svg.top + size.t + (1 - dom.y[1]) * size.h + 0.5 * (1 - p[1] / p[3]) * size.h * (dom.y[1] - dom.y[0])];
    };
  };
  const changed = (sc, a, b) => {          // the client box of the pixels that differ between a and b
    const r = sc.glplot.canvas.getBoundingClientRect();
    let x0 = 1e9, y0 = 1e9, x1 = -1, y1 = -1;
    for (let y = 0; y < a.h; y++) for (let x = 0; x < a.w; x++) {
      const k = 4 * (y * a.w + x);
      if (Math.abs(a.px[k] - b.px[k]) + Math.abs(a.px[k + 1] - b.px[k + 1]) + Math.abs(a.px[k + 2] - b.px[k + 2])
          + Math.abs(a.px[k + 3] - b.px[k + 3]) > 40) {
        x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y); }
    }
    if (x1 < 0) return null;
    const sx = r.width / a.w, sy = r.height / a.h;
    return {left: r.left + x0 * sx, right: r.left + (x1 + 1) * sx,
            top: r.top + (a.h - 1 - y1) * sy, bottom: r.top + (a.h - y0) * sy, edge:
            x0 === 0 || y0 === 0 || x1 === a.w - 1 || y1 === a.h - 1};
  };
  for (const gd of document.querySelectorAll('.plotly-graph-div')) {
    if (!gd._fullLayout) continue;
    const fig = nameOf(gd);
    // 2-D: the drawn points, and the text drawn on marker traces or annotations anchored at a marker; the other
    // markers a label could seem to name are those of the traces that carry labels (not arrowheads, say)
    const points = Array.from(gd.querySelectorAll('.scatterlayer path.point')).filter(p => {
      const r = p.getBoundingClientRect(); return r.width > 0 && getComputedStyle(p).opacity !== '0'; });
    const where = points.map(centre), traceOf = points.map(p => p.closest('g.trace'));
    const found = [];
    gd.querySelectorAll('.scatterlayer g.textpoint').forEach(tp => {
      const t = tp.querySelector('text'); const box = t && visibleBox(t);
      if (!box) return;
      const k = points.findIndex(p => p.__data__ === tp.__data__);
      if (k >= 0) found.push({text: short(t.textContent), box, k, arrow: false});  // else a text-only trace
    });
    const svg = gd.querySelector('.main-svg').getBoundingClientRect();
    (gd._fullLayout.annotations || []).forEach((a, i) => {
      if (!a.visible || a.xref === 'paper' || a.yref === 'paper' || !a.text) return;
      const xa = axisOf(gd, a.xref), ya = axisOf(gd, a.yref);
      if (!xa || !ya) return;
      const anchor = [svg.left + xa._offset + xa.r2p(a.x), svg.top + ya._offset + ya.r2p(a.y)];
      const k = where.findIndex(m => Math.hypot(m[0] - anchor[0], m[1] - anchor[1]) < 3);
      const el = gd.querySelector(`.annotation[data-index="${i}"] .annotation-text-g`);
      const box = el && visibleBox(el);
      if (k >= 0 && box) found.push({text: short(a.text), box, k, arrow: a.showarrow});
    });
    const labelled = new Set(found.map(f => traceOf[f.k]));
    found.forEach(f => {
      const own = where[f.k];
      judge(fig, f.text, f.box, own, where.filter((m, j) => labelled.has(traceOf[j])
        && Math.hypot(m[0] - own[0], m[1] - own[1]) > 1.5), f.arrow);
    });
    // 3-D scenes: scene annotations anchored at a marker, and WebGL text on marker traces
    for (const sid of Object.keys(gd._fullLayout).filter(k => /^scene\d*$/.test(k))) {
      const sl = gd._fullLayout[sid], sc = sl._scene;
      if (!sc || !sc.glplot) continue;
      const proj = projector(gd, sid);
      const traces = gd._fullData.map((t, i) => [t, i]).filter(([t]) => t.type === 'scatter3d' && t.scene === sid
        && t.visible === true);
      const markers = [];
      traces.forEach(([t, i]) => { if ((t.mode || '').includes('markers'))
        for (let k = 0; k < t.x.length; k++) if (t.x[k] != null && isFinite(t.x[k]))
          markers.push({trace: i, k, at: proj(t.x[k], t.y[k], t.z[k])}); });
      const found3 = [];
      (sl.annotations || []).forEach((a, i) => {
        if (!a.visible || !a.text) return;
        const anchor = proj(a.x, a.y, a.z);
        const m = markers.find(m => Math.hypot(m.at[0] - anchor[0], m.at[1] - anchor[1]) < 2);
        const el = gd.querySelector(`.annotation-${sid}[data-index="${i}"] .annotation-text-g`);
        const box = el && visibleBox(el);
        if (m && box) found3.push({text: short(a.text), box, m, arrow: a.showarrow});
      });
      const text3 = new Set(traces.filter(([t]) => (t.mode || '').includes('text') && Array.isArray(t.text)
                                                 && t.text.some(s => s)).map(([, i]) => i));
      const labelled3 = new Set([...found3.map(f => f.m.trace), ...text3]);
      const othersOf = (own) => markers.filter(o => labelled3.has(o.trace)).map(o => o.at)
        .filter(o => Math.hypot(o[0] - own[0], o[1] - own[1]) > 1.5);
      found3.forEach(f => judge(fig, f.text, f.box, f.m.at, othersOf(f.m.at), f.arrow));
      for (const [t, i] of traces) {
        if (!(t.mode || '').includes('text') || !(t.mode || '').includes('markers') || !Array.isArray(t.text)) continue;
        const text = Array.from(t.text), colour = (gd.data[i].textfont || {}).color;
        const base = pixels(sc);
        for (let k = 0; k < text.length; k++) {
          if (!text[k]) continue;
          await Plotly.restyle(gd, {text: [text.map((s, j) => j === k ? s : '')], 'textfont.color': '#ff00ff'}, [i]);
          const only = pixels(sc);
          await Plotly.restyle(gd, {text: [text.map(() => '')]}, [i]);
          const none = pixels(sc);
          const box = changed(sc, only, none);
          if (!box) { out.push(`${fig}: label "${text[k]}" is not drawn`); continue; }
          const own = proj(t.x[k], t.y[k], t.z[k]);
          judge(fig, short(String(text[k])), box, own, othersOf(own), false);
        }
        await Plotly.restyle(gd, {text: [text], 'textfont.color': colour === undefined ? null : colour}, [i]);
        const after = pixels(sc);
        if (changed(sc, base, after)) out.push(`${fig}: the scene did not come back as it was after the label check`);
      }
    }
  }
  return out;
}"""

# The drawn lines of a figure (its traces' paths, as polylines in client pixels) against the boxes of its
# labels: a label crossed by a line sits on the curve.
LABELS_ON_CURVES = "() => {" + _COMMON + r"""
  const out = [];
  const polylines = (path) => {
    const d = path.getAttribute('d') || '', m = path.getScreenCTM();
    if (!m || /[CQSTA]/i.test(d)) return [];
    const lines = []; let cur = null;
    for (const seg of d.match(/[ML][^ML]*/gi) || []) {
      const nums = (seg.slice(1).match(/-?[\d.]+(?:e[-+]?\d+)?/gi) || []).map(Number);
      for (let i = 0; i + 1 < nums.length; i += 2) {
        const p = [m.a * nums[i] + m.c * nums[i + 1] + m.e, m.b * nums[i] + m.d * nums[i + 1] + m.f];
        if (seg[0].toUpperCase() === 'M' && i === 0) { cur = [p]; lines.push(cur); } else if (cur) cur.push(p);
      }
    }
    return lines;
  };
  const crosses = (b, p, q) => {            // Liang-Barsky: does segment pq enter box b?
    let t0 = 0, t1 = 1; const dx = q[0] - p[0], dy = q[1] - p[1];
    for (const [pp, qq] of [[-dx, p[0] - b.left], [dx, b.right - p[0]], [-dy, p[1] - b.top], [dy, b.bottom - p[1]]]) {
      if (pp === 0) { if (qq < 0) return false; }
      else { const r = qq / pp; if (pp < 0) { if (r > t1) return false; if (r > t0) t0 = r; }
             else { if (r < t0) return false; if (r < t1) t1 = r; } }
    }
    return true;
  };
  document.querySelectorAll('.plotly-graph-div').forEach(gd => {
    if (!gd._fullLayout) return;
    const fig = nameOf(gd);
    const lines = [];
    gd.querySelectorAll('.scatterlayer path.js-line').forEach(p => {
      if (p.closest('.legend')) return;
      const s = getComputedStyle(p);
      if (s.display === 'none' || s.visibility === 'hidden' || parseFloat(s.opacity) === 0
          || parseFloat(s.strokeOpacity) === 0 || s.stroke === 'none') return;
      for (let e = p; e && e !== gd; e = e.parentElement)
        if (e.nodeType === 1 && (getComputedStyle(e).display === 'none' || parseFloat(getComputedStyle(e).opacity) === 0)) return;
      polylines(p).forEach(l => lines.push(l));
    });
    if (!lines.length) return;
    const labels = [];
    gd.querySelectorAll('.annotation-text-g text, .scatterlayer g.textpoint text').forEach(el => {
      const r = visibleBox(el);
      if (r) labels.push({text: short(el.textContent), r});
    });
    labels.forEach(l => {
      const b = {left: l.r.left + 1, right: l.r.right - 1, top: l.r.top + 1, bottom: l.r.bottom - 1};
      if (lines.some(line => line.some((p, i) => i > 0 && crosses(b, line[i - 1], p))))
        out.push(`${fig}: label "${l.text}" sits on a plotted curve`);
    });
  });
  return out;
}"""

# Tick labels that run into each other ("0.20.40.6") or into a subplot title, an annotation or an axis title.
TICK_OVERLAPS = "() => {" + _COMMON + r"""
  const out = [];
  const overlap = (a, b) => Math.min(a.right, b.right) - Math.max(a.left, b.left) > 0.5
                         && Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top) > 0.5;
  document.querySelectorAll('.plotly-graph-div').forEach(gd => {
    if (!gd._fullLayout) return;
    const fig = nameOf(gd);
    const ticks = [], texts = [];
    gd.querySelectorAll('g.xtick text, g.ytick text, [class$="tick"] > text').forEach(el => {
      if (!/^[xy]\d*tick$/.test(el.parentNode.getAttribute('class') || '')) return;
      const r = visibleBox(el);
      if (r) ticks.push({text: short(el.textContent), r, axis: el.parentNode.getAttribute('class')});
    });
    gd.querySelectorAll('.annotation-text-g text, text[class$="title"]').forEach(el => {
      if (/^g-/.test(el.getAttribute('class') || '')) return;
      const r = visibleBox(el);
      if (r) texts.push({text: short(el.textContent), r});
    });
    const seen = new Set();
    const uniq = ticks.filter(t => { const k = [t.text, Math.round(t.r.left), Math.round(t.r.top)].join('|');
      if (seen.has(k)) return false; seen.add(k); return true; });
    for (let i = 0; i < uniq.length; i++) {
      for (let j = i + 1; j < uniq.length; j++)
        if (overlap(uniq[i].r, uniq[j].r))
          out.push(`${fig}: tick labels "${uniq[i].text}" and "${uniq[j].text}" run into each other`);
      texts.forEach(t => { if (overlap(uniq[i].r, t.r))
        out.push(`${fig}: tick label "${uniq[i].text}" runs into "${t.text}"`); });
    }
  });
  return out;
}"""

# An axis title no longer than its axis: a y title (drawn turned) no taller than its panel, an x title no
# wider than its axis.
LONG_AXIS_TITLES = "() => {" + _COMMON + r"""
  const out = [];
  document.querySelectorAll('.plotly-graph-div').forEach(gd => {
    if (!gd._fullLayout) return;
    const fig = nameOf(gd);
    // axis titles: text.xtitle, text.ytitle, text.y2title... (the class of a numbered axis holds its number)
    gd.querySelectorAll('text[class$="title"]').forEach(el => {
      const m = /^([xy])(\d*)title$/.exec(el.getAttribute('class') || '');
      const r = visibleBox(el);
      if (!m || !r) return;
      const ax = gd._fullLayout[m[1] + 'axis' + m[2]];
      if (!ax || !ax._length) return;
      const size = m[1] === 'y' ? r.height : r.width;
      if (size > ax._length + 1)
        out.push(`${fig}: axis title "${short(el.textContent)}" is ${Math.round(size)} px long on a `
                 + `${Math.round(ax._length)} px axis`);
    });
  });
  return out;
}"""

# A dropdown must say what it shows: each of its choices (pressed as plotly presses it) gives the figure a title
# of its own. Play/Pause menus are left alone; the figure is put back on the choice it showed.
DROPDOWN_TITLES = "async () => {" + _COMMON + r"""
  const out = [];
  const titleOf = (gd) => { const t = gd._fullLayout.title; return (t && (t.text || '')) || ''; };
  for (const gd of document.querySelectorAll('.plotly-graph-div')) {
    if (!gd._fullLayout) continue;
    const fig = nameOf(gd);
    const menus = gd._fullLayout.updatemenus || [];
    for (let mi = 0; mi < menus.length; mi++) {
      const menu = menus[mi], buttons = (menu.buttons || []).filter(b => b.visible !== false);
      if (buttons.length < 2 || buttons.some(b => b.method === 'animate') || menu.visible === false) continue;
      const press = (b) => b.method === 'skip' ? null : Plotly[b.method](gd, ...(b.args || []));
      const active = menu.active >= 0 ? menu.active : 0;
      const seen = new Map();
      for (const b of buttons) {
        await press(b);
        const t = titleOf(gd);
        if (seen.has(t))
          out.push(`${fig}: dropdown choices "${seen.get(t)}" and "${b.label}" show the same title "${short(t)}"`);
        else seen.set(t, b.label);
      }
      await press(menus[mi].buttons[active]);
    }
  }
  return out;
}"""

# The axis titles and tick labels of a 3-D scene are drawn in its WebGL canvas: each is recoloured in turn, the
# scene redrawn, and the pixels that changed against the scene as it was are that text. A title with no pixels
# is not drawn (outside the scene); a text whose pixels reach the canvas's edge is cut.
SCENE_TEXT = "async () => {" + _COMMON + r"""
  const out = [];
  const diff = (a, b) => {
    let n = 0, edge = 0;
    for (let y = 0; y < a.h; y++) for (let x = 0; x < a.w; x++) {
      const k = 4 * (y * a.w + x);
      if (Math.abs(a.px[k] - b.px[k]) + Math.abs(a.px[k + 1] - b.px[k + 1]) + Math.abs(a.px[k + 2] - b.px[k + 2])
          + Math.abs(a.px[k + 3] - b.px[k + 3]) > 40) {
        n++; if (x < 2 || y < 2 || x >= a.w - 2 || y >= a.h - 2) edge++; }
    }
    return {n, edge};
  };
  const get = (obj, path) => path.split('.').reduce((o, k) => (o == null ? undefined : o[k]), obj);
  for (const gd of document.querySelectorAll('.plotly-graph-div')) {
    if (!gd._fullLayout) continue;
    const fig = nameOf(gd);
    for (const sid of Object.keys(gd._fullLayout).filter(k => /^scene\d*$/.test(k))) {
      const sc = gd._fullLayout[sid]._scene;
      if (!sc || !sc.glplot) continue;
      const base = pixels(sc);
      for (const c of 'xyz') {
        const ax = gd._fullLayout[sid][c + 'axis'];
        if (!ax.visible) continue;
        const parts = [['title.font.color', 'title', (ax.title && ax.title.text) || ''],
                       ['tickfont.color', 'tick labels', ax.showticklabels ? 'ticks' : '']];
        for (const [attr, what, text] of parts) {
          if (!text) continue;
          const key = `${sid}.${c}axis.${attr}`, old = get(gd.layout, key);
          await Plotly.relayout(gd, {[key]: '#ff00ff'});
          const d = diff(base, pixels(sc));
          await Plotly.relayout(gd, {[key]: old === undefined ? null : old});
          const label = what === 'title' ? `axis title "${short(text)}"` : `${c} tick labels`;
          if (d.n === 0) out.push(`${fig}: ${sid} ${label} not drawn (outside the scene)`);
          else if (d.edge > 0) out.push(`${fig}: ${sid} ${label} cut at the edge of the scene`);
        }
      }
    }
  }
  return out;
}"""

CHECKS = (("labels at markers", LABELS_AT_MARKERS), ("labels on curves", LABELS_ON_CURVES),
          ("tick overlaps", TICK_OVERLAPS), ("long axis titles", LONG_AXIS_TITLES),
          ("dropdown titles", DROPDOWN_TITLES), ("scene text", SCENE_TEXT))


def figure_problems(pg, width: int) -> list[str]:
    """Every figure problem of the page at this viewport width (the page is loaded and settled). The checks
    that press buttons or redraw a scene put each figure back as it was."""
    problems = []
    for _, check in CHECKS:
        problems += pg.evaluate(check)
    return problems
