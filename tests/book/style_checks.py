"""How the built pages look to a reader, measured in the browser: colours, table spacing, equation numbers.

:func:`style_problems` runs every check on a page that is loaded and settled (``page_checks.settle``) and
returns human-readable problems (empty when the page is clean). Each check is a JavaScript function evaluated in
the page:

- ``READOUTS``: every slider's value readout (the time of an animation) is drawn in a colour that reads
  against the figure (contrast at least 4.5:1 after its opacity), with its box inside the figure; no slider draws
  its step labels as a stray row of dots (labels too small to read that are still painted);
- ``TABLES``: neighbouring cells keep their text apart (at least 6 px between the text of two cells of a row),
  no number breaks over two lines, a table wider than its box shows a scroll cue (a shadow on the edge where it
  continues), and in dark mode a table is drawn on a dark background with light text;
- ``EQUATIONS``: no equation's terms lie under its number, and no formula, display or inline, runs past the
  edge of its box unless that box scrolls and shows a scroll cue; folded solutions and hidden code are opened
  first (and folded again afterwards), so the formulas inside them count;
- ``DROPDOWNS``: the arrow of every figure's dropdown reads against its button (contrast at least 3:1).

``page_checks.py`` runs them with the other checks, in the browser test or alone on a build.
"""
from __future__ import annotations


#: least contrast of text (the slider's readout, table text) and of a dropdown's arrow (a graphic) against
#: what is behind it: WCAG 2 levels AA for text and for the parts of a control
TEXT_CONTRAST, GRAPHIC_CONTRAST = 4.5, 3.0
#: least gap (px) between the text of two neighbouring cells of a table row
CELL_GAP = 6

# Colour arithmetic shared by the checks: CSS colours as [r, g, b, a], alpha compositing, WCAG contrast.
_COLOURS = r"""
  const probe = document.createElement('canvas').getContext('2d');
  const rgba = (c) => {
    if (!c || c === 'none' || c.startsWith('url(')) return null;
    const m = c.match(/^rgba?\(([^)]*)\)$/);
    if (m) {
      const v = m[1].split(/[\s,\/]+/).filter(Boolean).map(parseFloat);
      return [v[0], v[1], v[2], v.length > 3 ? v[3] : 1];
    }
    // what color-mix() computes to: color(srgb r g b / a), channels from 0 to 1
    const f = c.match(/^color\(srgb\s+([^)]*)\)$/);
    if (f) {
      const v = f[1].split(/[\s\/]+/).filter(Boolean).map(parseFloat);
      return [v[0] * 255, v[1] * 255, v[2] * 255, v.length > 3 ? v[3] : 1];
    }
    probe.fillStyle = '#010203'; probe.fillStyle = c;
    const s = probe.fillStyle;
    if (s[0] === '#') return s === '#010203' ? null : [1, 3, 5].map(i => parseInt(s.slice(i, i + 2), 16)).concat([1]);
    return s !== c && /^(rgba?|color)\(/.test(s) ? rgba(s) : null;
  };
  // a colour painted over another (both [r, g, b, a])
  const over = (top, below) => {
    const a = top[3] + below[3] * (1 - top[3]);
    if (a === 0) return [0, 0, 0, 0];
    return [0, 1, 2].map(i => (top[i] * top[3] + below[i] * below[3] * (1 - top[3])) / a).concat([a]);
  };
  const lum = (c) => {
    const l = c.slice(0, 3).map(v => { v /= 255; return v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4); });
    return 0.2126 * l[0] + 0.7152 * l[1] + 0.0722 * l[2];
  };
  const contrast = (a, b) => { const x = lum(a), y = lum(b); return (Math.max(x, y) + 0.05) / (Math.min(x, y) + 0.05); };
  const hex = (c) => '#' + c.slice(0, 3).map(v => Math.round(v).toString(16).padStart(2, '0')).join('');
  // the opaque colour behind an element: its own and its ancestors' backgrounds over the white canvas
  const backdrop = (el) => {
    const layers = [];
    for (let e = el; e && e.nodeType === 1; e = e.parentElement) {
      const c = rgba(getComputedStyle(e).backgroundColor);
      if (c && c[3] > 0) { layers.push(c); if (c[3] >= 1) break; }
    }
    let bg = [255, 255, 255, 1];
    for (let i = layers.length - 1; i >= 0; i--) bg = over(layers[i], bg);
    return bg;
  };
  // the product of the opacities of an element and its ancestors
  const opacity = (el) => {
    let o = 1;
    for (let e = el; e && e.nodeType === 1; e = e.parentElement) {
      const s = getComputedStyle(e);
      if (s.display === 'none' || s.visibility === 'hidden') return 0;
      o *= parseFloat(s.opacity);
    }
    return o;
  };
  // the colour an SVG text or shape is painted in, its opacities applied, over `bg`
  const painted = (el, bg, what = 'fill') => {
    const s = getComputedStyle(el);
    const c = rgba(s[what]);
    if (!c) return null;
    const a = c[3] * parseFloat(s[what + 'Opacity'] || '1') * opacity(el);
    return {colour: over([c[0], c[1], c[2], a], bg), alpha: a};
  };
  // the colour behind a plotly figure's own drawing: its paper over the page
  const paper = (gd) => over(rgba(gd._fullLayout.paper_bgcolor) || [0, 0, 0, 0], backdrop(gd));
  const figName = (gd) => {
    const f = gd.closest('figure');
    const num = f && f.querySelector('.caption-number');
    return num ? num.textContent.trim() : (f && f.id) || gd.id;
  };
  const inside = (r, box, tol = 1) => r.left >= box.left - tol && r.right <= box.right + tol
                                   && r.top >= box.top - tol && r.bottom <= box.bottom + tol;
"""

# A box scrolls sideways and shows that it does: a cue drawn by a gradient attached to the box itself (it stays
# at the edge while the content scrolls; the usual scrolling shadow) or by a gradient on one of its ::before and
# ::after boxes.
_SCROLL = r"""
  const scroller = (el, stop) => {
    for (let e = el.parentElement; e && e !== stop && e.tagName !== 'BODY'; e = e.parentElement) {
      const o = getComputedStyle(e).overflowX;
      if (o !== 'visible') return {box: e, scrolls: o === 'auto' || o === 'scroll'};
    }
    return null;
  };
  // overOnly: only a cue drawn over the content (a pseudo-element), not a background under it
  const hasCue = (box, overOnly = false) => {
    const s = getComputedStyle(box);
    const images = s.backgroundImage.split(/,(?![^(]*\))/);
    const attach = s.backgroundAttachment.split(',').map(x => x.trim());
    if (!overOnly && images.some((im, i) => /gradient/.test(im) && attach[i % attach.length] === 'scroll')) return true;
    return ['::before', '::after'].some(p => {
      const ps = getComputedStyle(box, p);
      return ps.content !== 'none' && /gradient/.test(ps.backgroundImage) && ps.display !== 'none'
          && parseFloat(ps.opacity) > 0;
    });
  };
"""

READOUTS = "() => {" + _COLOURS + r"""
  const out = [];
  document.querySelectorAll('.js-plotly-plot').forEach(gd => {
    const full = gd._fullLayout;
    if (!full || !(full.sliders || []).length) return;
    const name = figName(gd);
    const fr = gd.getBoundingClientRect();
    if (fr.width < 1) return;
    const bg = paper(gd);
    const animated = (full.updatemenus || []).some(m => (m.buttons || []).some(b => b.method === 'animate'));
    gd.querySelectorAll('.slider-container').forEach((sc, i) => {
      const opts = (full.sliders || [])[i] || {};
      const readout = sc.querySelector('.slider-group > text.slider-label');
      const want = opts.currentvalue ? opts.currentvalue.visible !== false : true;
      if (!readout) {
        if (animated && want) out.push(`${name}: the animation's slider has no readout of its value`);
      } else {
        const p = painted(readout, bg);
        const r = readout.getBoundingClientRect();
        const size = parseFloat(getComputedStyle(readout).fontSize);
        const what = `${name}: the slider's readout "${readout.textContent.trim().slice(0, 30)}"`;
        if (!p || p.alpha < 0.05) out.push(`${what} is not painted (opacity ${p ? p.alpha.toFixed(2) : 'none'})`);
        else {
          const c = contrast(p.colour, bg);
          if (c < """ + str(TEXT_CONTRAST) + r""") out.push(`${what} is ${hex(p.colour)} on ${hex(bg)}: contrast ${c.toFixed(2)}:1`);
        }
        if (size < 9) out.push(`${what} is ${size} px high`);
        if (r.width < 1 || r.height < 1 || !inside(r, fr)) out.push(`${what} lies outside the figure`);
      }
      // step labels too small to read but painted: a row of dots under the rail
      const dots = Array.from(sc.querySelectorAll('.slider-label-group text')).filter(t => {
        const p = painted(t, bg);
        return p && p.alpha > 0.05 && parseFloat(getComputedStyle(t).fontSize) < 6 && t.textContent.trim();
      });
      if (dots.length >= 2) out.push(`${name}: the slider paints ${dots.length} step labels `
                                     + `${getComputedStyle(dots[0]).fontSize} high (a row of dots)`);
    });
  });
  return out;
}"""

TABLES = "(dark) => {" + _COLOURS + _SCROLL + r"""
  const out = [];
  const article = document.querySelector('article') || document.body;
  // a number: a sign only where it starts a word (not the hyphen of "joint-1"), digits with separators
  // inside, an exponent
  const NUMBER = /(?<![\w.\u2212-])[-+\u2212]?(?:\d(?:[\d,.]*\d)?|\.\d+)(?:[eE][-+\u2212]?\d+)?/g;
  // the text of a cell as boxes: its text nodes, and its typeset formulas (whose glyphs are not text nodes)
  const textRects = (cell) => {
    const rects = [];
    const walk = document.createTreeWalker(cell, NodeFilter.SHOW_TEXT);
    for (let n = walk.nextNode(); n; n = walk.nextNode()) {
      if (!n.textContent.trim() || n.parentElement.closest('mjx-container, style, script')) continue;
      const r = document.createRange(); r.selectNodeContents(n);
      rects.push(...Array.from(r.getClientRects()).filter(x => x.width > 0 && x.height > 0));
    }
    cell.querySelectorAll('mjx-container').forEach(m => {
      const r = m.getBoundingClientRect(); if (r.width > 0) rects.push(r); });
    return rects;
  };
  const union = (rs) => rs.length ? {left: Math.min(...rs.map(r => r.left)), right: Math.max(...rs.map(r => r.right)),
                                     top: Math.min(...rs.map(r => r.top)), bottom: Math.max(...rs.map(r => r.bottom))} : null;
  const cellText = (c) => c.textContent.replace(/\s+/g, ' ').trim();
  const opaque = (e) => { const b = rgba(getComputedStyle(e).backgroundColor); return b && b[3] > 0.5; };
  document.querySelectorAll('article table').forEach((t, ti) => {
    const tr = t.getBoundingClientRect();
    if (tr.width < 1 || t.closest('.js-plotly-plot')) return;
    const name = `table ${ti + 1} (${cellText(t).slice(0, 40)})`;
    // neighbouring cells: the text of one ends at least CELL_GAP px before the next one's starts
    let tight = [];
    t.querySelectorAll('tr').forEach(row => {
      const cells = Array.from(row.children).filter(c => c.tagName === 'TD' || c.tagName === 'TH');
      for (let k = 0; k + 1 < cells.length; k++) {
        const a = union(textRects(cells[k])), b = union(textRects(cells[k + 1]));
        if (!a || !b || Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top) < 1) continue;
        const gap = b.left - a.right;
        if (gap < """ + str(CELL_GAP) + r""" - 0.05) tight.push(`"${cellText(cells[k]).slice(-12)}" and "${cellText(cells[k + 1]).slice(0, 12)}" ${gap.toFixed(1)} px apart`);
      }
    });
    if (tight.length) out.push(`${name}: ${tight.length} pairs of neighbouring cells whose text nearly touches, `
                               + `e.g. ${tight.slice(0, 2).join('; ')}`);
    // a number is never broken over two lines
    const broken = [];
    t.querySelectorAll('td, th').forEach(c => {
      const walk = document.createTreeWalker(c, NodeFilter.SHOW_TEXT);
      for (let n = walk.nextNode(); n; n = walk.nextNode()) {
        // code (a signature in a narrow column) breaks where it must, names and numbers alike
        if (n.parentElement.closest('mjx-container, style, script, code, pre')) continue;
        for (const m of n.textContent.matchAll(NUMBER)) {
          if (m[0].length < 2) continue;
          const r = document.createRange(); r.setStart(n, m.index); r.setEnd(n, m.index + m[0].length);
          const tops = new Set(Array.from(r.getClientRects()).filter(x => x.width > 0).map(x => Math.round(x.top)));
          if (tops.size > 1) broken.push(m[0]);
        }
      }
    });
    if (broken.length) out.push(`${name}: ${broken.length} numbers broken over two lines, e.g. ${broken.slice(0, 3).join(', ')}`);
    // wider than its box: the box scrolls and shows it
    const sc = scroller(t, null);
    const room = sc ? sc.box.clientWidth : article.clientWidth;
    if (sc && sc.scrolls && sc.box.scrollWidth > sc.box.clientWidth + 1) {
      if (!hasCue(sc.box))
        out.push(`${name} is ${Math.round(sc.box.scrollWidth)} px wide in a ${room} px box that scrolls with no visible cue`);
      else {
        // a cue drawn under the table (a background of the box) is hidden by opaque cells, rows or table
        if (!hasCue(sc.box, true)) {
          const covered = [t, ...t.querySelectorAll('thead, tbody, tr, td, th')].filter(opaque).length;
          if (covered) out.push(`${name}: ${covered} cells or rows with an opaque background hide its scroll cue`);
        }
      }
    } else if (tr.width > room + 1) {
      out.push(`${name} is ${Math.round(tr.width)} px wide in a ${room} px box and cut off`);
    }
    // dark mode: a dark table with light text
    if (dark) {
      const cell = t.querySelector('tbody td') || t.querySelector('td, th');
      if (cell) {
        const bg = backdrop(cell);
        const fg = over(rgba(getComputedStyle(cell).color) || [0, 0, 0, 1], bg);
        if (lum(bg) > 0.2) out.push(`${name} is drawn on a light background (${hex(bg)}) in dark mode`);
        else if (contrast(fg, bg) < """ + str(TEXT_CONTRAST) + r""")
          out.push(`${name}: its text ${hex(fg)} on ${hex(bg)} has contrast ${contrast(fg, bg).toFixed(2)}:1 in dark mode`);
      }
    }
  });
  return out;
}"""

# Fold out every folded solution and hidden cell, so that what is inside them can be measured: returns how many
# it opened; FOLD_BACK closes them again.
UNFOLD = """async () => {
  const opened = [];
  document.querySelectorAll('details:not([open])').forEach(d => { d.open = true; opened.push(d); });
  document.querySelectorAll('.toggle.toggle-hidden').forEach(t => {
    const b = t.querySelector('.admonition-title .toggle-button, .toggle-button');
    if (b) { b.click(); opened.push(t); }
  });
  window.__styleUnfolded = opened;
  await new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)));
  if (window.Plotly) await Promise.all(opened.flatMap(o => Array.from(o.querySelectorAll('.js-plotly-plot')))
    .map(gd => Plotly.Plots.resize(gd).catch(() => null)));
  return opened.length;
}"""

FOLD_BACK = """() => {
  (window.__styleUnfolded || []).forEach(o => {
    if (o.tagName === 'DETAILS') o.open = false;
    else { const b = o.querySelector('.toggle-button'); if (b && !o.classList.contains('toggle-hidden')) b.click(); }
  });
  window.__styleUnfolded = [];
}"""

EQUATIONS = "() => {" + _COLOURS + _SCROLL + r"""
  const out = [];
  const label = (m) => {
    const box = m.closest('div.math');
    const no = box && box.querySelector('.eqno');
    const where = m.closest('.solution, .exercise, details');
    const title = where && where.querySelector('.admonition-title, summary');
    const text = (m.querySelector('mjx-assistive-mml') || m).textContent.replace(/\s+/g, ' ').trim().slice(0, 40);
    return (no ? 'equation ' + no.textContent.replace('#', '').trim() : box ? 'an unnumbered equation' : 'the formula')
         + ` "${text}"` + (title ? ' in "' + title.textContent.replace(/\s+/g, ' ').trim().slice(0, 40) + '"' : '');
  };
  document.querySelectorAll('mjx-container').forEach(c => {
    const m = c.querySelector(':scope > mjx-math');
    if (!m) return;
    const mr = m.getBoundingClientRect();
    if (mr.width < 1 || opacity(c) === 0) return;
    // terms under the number
    const box = c.closest('div.math');
    const no = box && c.parentElement === box && box.querySelector(':scope > .eqno');
    if (no) {
      const nr = no.getBoundingClientRect();
      const w = Math.min(mr.right, nr.right) - Math.max(mr.left, nr.left);
      const h = Math.min(mr.bottom, nr.bottom) - Math.max(mr.top, nr.top);
      if (w > 0.5 && h > 0.5) out.push(`${label(c)}: ${Math.round(w)} px of its terms lie under its number`);
    }
    // past the edge of its box: the nearest box that clips it must scroll and show it
    for (let e = c; e && e.tagName !== 'BODY'; e = e.parentElement) {
      const s = getComputedStyle(e);
      if (s.overflowX === 'visible') continue;
      const er = e.getBoundingClientRect();
      const inner = {left: er.left + e.clientLeft, right: er.left + e.clientLeft + e.clientWidth};
      if (mr.right > inner.right + 1 || mr.left < inner.left - 1) {
        const scrolls = (s.overflowX === 'auto' || s.overflowX === 'scroll') && e.scrollWidth > e.clientWidth + 1;
        if (!scrolls) out.push(`${label(c)} is cut at the edge of its box (${Math.round(mr.width)} px in ${e.clientWidth} px)`);
        else if (!hasCue(e)) out.push(`${label(c)} is ${Math.round(mr.width)} px wide in a ${e.clientWidth} px box `
                                      + 'that scrolls with no visible cue');
      }
      break;
    }
  });
  return out;
}"""

DROPDOWNS = "() => {" + _COLOURS + r"""
  const out = [];
  document.querySelectorAll('.js-plotly-plot').forEach(gd => {
    if (!gd._fullLayout) return;
    const bgFigure = paper(gd);
    gd.querySelectorAll('.updatemenu-header-arrow').forEach(arrow => {
      const ar = arrow.getBoundingClientRect();
      if (ar.width < 1) return;
      // the arrow sits on the menu's header button
      let bg = bgFigure;
      const menu = arrow.parentElement;
      const rect = Array.from(menu.querySelectorAll('.updatemenu-header .updatemenu-item-rect')).find(r => {
        const rr = r.getBoundingClientRect(); const cx = (ar.left + ar.right) / 2, cy = (ar.top + ar.bottom) / 2;
        return cx >= rr.left && cx <= rr.right && cy >= rr.top && cy <= rr.bottom; });
      if (rect) { const p = painted(rect, bgFigure); if (p) bg = p.colour; }
      const p = painted(arrow, bg);
      const c = p ? contrast(p.colour, bg) : 1;
      if (c < """ + str(GRAPHIC_CONTRAST) + r""")
        out.push(`${figName(gd)}: the dropdown's arrow is ${p ? hex(p.colour) : 'unpainted'} on ${hex(bg)}: `
                 + `contrast ${c.toFixed(2)}:1`);
    });
  });
  return out;
}"""


def style_problems(pg, width: int, dark: bool) -> list[str]:
    """Every style problem of the loaded, settled page ``pg`` at this viewport ``width`` (px), in the dark theme
    when ``dark``: the checks of this module. Folded solutions are opened for the equations and tables inside
    them and folded again afterwards."""
    problems = list(pg.evaluate(READOUTS)) + list(pg.evaluate(DROPDOWNS))
    pg.evaluate(UNFOLD)
    pg.wait_for_timeout(150)
    try:
        problems += pg.evaluate(TABLES, dark) + pg.evaluate(EQUATIONS)
    finally:
        pg.evaluate(FOLD_BACK)
    return problems
