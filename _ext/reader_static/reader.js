/* What the reader sees: figures that follow the dark theme, a text alternative on every figure, search results
 * without raw TeX, tables whose numbers never break, formulas that fit their line, scroll cues on what scrolls
 * sideways. Loaded on every page of the book (see _ext/reader.py). */
(function () {
  "use strict";

  // ---- colours ---------------------------------------------------------------------------------------------
  const probe = document.createElement("canvas").getContext("2d");

  /** [r, g, b, a] of any CSS colour (0-255, alpha 0-1), or null. */
  function rgba(colour) {
    if (typeof colour !== "string" || !colour) return null;
    probe.fillStyle = "#010203";
    probe.fillStyle = colour;
    const s = probe.fillStyle;  // "#rrggbb" or "rgba(r, g, b, a)"
    if (s === "#010203" && colour.replace(/\s/g, "").toLowerCase() !== "#010203") return null;
    if (s[0] === "#") return [1, 3, 5].map((i) => parseInt(s.slice(i, i + 2), 16)).concat([1]);
    const m = s.match(/[\d.]+/g);
    return m ? m.map(Number) : null;
  }

  /** Relative luminance (0 black, 1 white) of a CSS colour, or null when it is not a colour. */
  function luminance(colour) {
    const c = rgba(colour);
    if (!c || c[3] === 0) return null;
    const lin = c.slice(0, 3).map((v) => { v /= 255; return v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4); });
    return 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2];
  }

  function cssVar(name, fallback) {
    const v = getComputedStyle(document.documentElement).getPropertyValue(name).trim();
    return v || fallback;
  }

  function get(obj, path) {
    return path.split(".").reduce((o, k) => (o == null ? undefined : o[k]), obj);
  }

  // ---- figures follow the theme ------------------------------------------------------------------------------
  const isDark = () => document.documentElement.dataset.theme === "dark";

  /** The layout changes that put a figure on the dark page: {attribute: value}. */
  function darkLayout(gd) {
    const full = gd._fullLayout;
    const text = cssVar("--pst-color-text-base", "#ced6dd");
    const muted = cssVar("--pst-color-text-muted", "#9ca4af");
    const surface = cssVar("--pst-color-surface", "#29313d");
    const grid = "rgba(200, 210, 220, 0.16)";
    const line = "rgba(200, 210, 220, 0.45)";
    const pane = "#1f242b";
    const u = {
      paper_bgcolor: "rgba(0, 0, 0, 0)",
      plot_bgcolor: "rgba(255, 255, 255, 0.03)",
      "font.color": text,
      "title.font.color": text,
      "legend.bgcolor": "rgba(0, 0, 0, 0)",
      "legend.font.color": text,
      "legend.bordercolor": line,
    };
    for (const key of Object.keys(full)) {
      if (/^[xy]axis\d*$/.test(key)) {
        Object.assign(u, {
          [key + ".gridcolor"]: grid, [key + ".zerolinecolor"]: line, [key + ".linecolor"]: line,
          [key + ".tickcolor"]: line, [key + ".tickfont.color"]: muted, [key + ".title.font.color"]: text,
        });
      } else if (/^scene\d*$/.test(key)) {
        u[key + ".bgcolor"] = "rgba(0, 0, 0, 0)";
        for (const ax of ["xaxis", "yaxis", "zaxis"]) {
          Object.assign(u, {
            // WebGL ignores the alpha of these colours: the scene's panes and grid get opaque ones
            [`${key}.${ax}.backgroundcolor`]: pane, [`${key}.${ax}.gridcolor`]: "#3b424c",
            [`${key}.${ax}.zerolinecolor`]: "#6b7480", [`${key}.${ax}.linecolor`]: "#6b7480",
            [`${key}.${ax}.tickfont.color`]: muted, [`${key}.${ax}.title.font.color`]: text,
          });
        }
      }
    }
    (full.annotations || []).forEach((a, i) => {
      const lum = luminance(get(a, "font.color"));
      if (lum !== null && lum < 0.25) u[`annotations[${i}].font.color`] = text;
      const bg = luminance(a.bgcolor);
      if (bg !== null && bg > 0.6) u[`annotations[${i}].bgcolor`] = surface;
    });
    (full.shapes || []).forEach((s, i) => {
      const lum = luminance(get(s, "line.color"));
      if (lum !== null && lum < 0.25) u[`shapes[${i}].line.color`] = line;
    });
    ["sliders", "updatemenus"].forEach((kind) => (full[kind] || []).forEach((m, i) => {
      // a transparent font stays transparent: an animation's slider hides its step labels (one per frame) so
      // (painted, they would be a row of dots under the rail)
      const hidden = (rgba(get(m, "font.color")) || [0, 0, 0, 1])[3] === 0;
      if (!hidden) u[`${kind}[${i}].font.color`] = text;
      u[`${kind}[${i}].bgcolor`] = surface;
      if (kind === "sliders") Object.assign(u, {
        [`sliders[${i}].currentvalue.font.color`]: text, [`sliders[${i}].bordercolor`]: line,
        [`sliders[${i}].tickcolor`]: line, [`sliders[${i}].activebgcolor`]: muted,
      });
    }));
    return u;
  }

  const TRACE_COLOURS = ["line.color", "marker.color", "marker.line.color", "textfont.color", "fillcolor"];

  /** The trace colours too dark to read on the dark page, lightened: {attribute: [value per trace]}. */
  function darkTraces(gd) {
    const light = cssVar("--pst-color-text-base", "#ced6dd");
    const changes = {};
    (gd.data || []).forEach((trace, i) => {
      for (const attr of TRACE_COLOURS) {
        const v = get(trace, attr);
        const lum = luminance(v);
        if (typeof v === "string" && lum !== null && lum < 0.08) {
          (changes[attr] = changes[attr] || { values: [], traces: [], before: [] });
          changes[attr].values.push(light); changes[attr].traces.push(i); changes[attr].before.push(v);
        }
      }
    });
    return changes;
  }

  function applyTheme(gd) {
    if (!window.Plotly || !gd._fullLayout || !gd.data) return Promise.resolve();
    const dark = isDark();
    if (!!gd.__themeDark === dark) return Promise.resolve();
    gd.__themeDark = dark;
    if (dark) {
      const layout = darkLayout(gd);
      const traces = darkTraces(gd);
      // what the light page had: relayout with null restores plotly's default (the figure's template)
      gd.__themeLight = {
        layout: Object.fromEntries(Object.keys(layout).map((k) => [k, get(gd.layout, k.replace(/\[(\d+)\]/g, ".$1")) ?? null])),
        traces,
      };
      let p = Plotly.relayout(gd, layout);
      for (const [attr, c] of Object.entries(traces)) p = p.then(() => Plotly.restyle(gd, { [attr]: c.values }, c.traces));
      return p;
    }
    const saved = gd.__themeLight;
    if (!saved) return Promise.resolve();
    let p = Plotly.relayout(gd, saved.layout);
    for (const [attr, c] of Object.entries(saved.traces)) p = p.then(() => Plotly.restyle(gd, { [attr]: c.before }, c.traces));
    return p;
  }

  // obj at a plotly attribute path ("xaxis.tickfont.color", "annotations[2].font.color" or "annotations.2.font.color"):
  // a missing object on the way is made, a missing entry of a list is an error (the path names what is not there)
  function put(obj, path, value) {
    const keys = path.replace(/\[(\d+)\]/g, ".$1").split(".");
    let o = obj;
    for (const k of keys.slice(0, -1)) {
      if (o[k] === undefined || o[k] === null) {
        if (Array.isArray(o)) throw new Error("layout path " + path + ": no entry " + k);
        o[k] = {};
      }
      o = o[k];
    }
    o[keys[keys.length - 1]] = value;
  }

  /** A figure about to be redrawn with new (data, layout) on a dark page, which it already follows: the dark
   * colours written into them, so one redraw draws it dark (no relayout after it). True when it did. */
  function darkened(gd, data, layout) {
    if (!isDark() || !gd.__themeDark || !gd._fullLayout) return false;
    for (const [k, v] of Object.entries(darkLayout(gd))) put(layout, k, v);
    const light = cssVar("--pst-color-text-base", "#ced6dd");
    data.forEach((trace) => {
      for (const attr of TRACE_COLOURS) {
        const v = get(trace, attr), lum = luminance(v);
        if (typeof v === "string" && lum !== null && lum < 0.08) put(trace, attr, light);
      }
    });
    return true;
  }

  function themeAll() {
    return Promise.all(Array.from(document.querySelectorAll(".js-plotly-plot")).map(applyTheme));
  }

  // ---- a text alternative on every figure ----------------------------------------------------------------------
  function describe(gd) {
    if (gd.hasAttribute("aria-label")) return;
    const figure = gd.closest("figure");
    const caption = figure && figure.querySelector("figcaption");
    let text = caption ? caption.textContent.replace(/\s+/g, " ").replace(/#\s*$/, "").trim() : "";
    if (!text && gd._fullLayout) text = (get(gd._fullLayout, "title.text") || "").replace(/<[^>]+>/g, " ").trim();
    if (!text) return;
    gd.setAttribute("role", "group");
    gd.setAttribute("aria-label", text);
  }

  function figures() {
    document.querySelectorAll(".plotly-graph-div").forEach(describe);
    return themeAll();
  }

  // ---- the text column: numbers that never break, formulas that fit, scroll cues -----------------------------
  // a table cell that holds a number and nothing else (a sign, digits, an exponent, a unit symbol)
  const NUMBER_CELL = /^[-+\u2212\u00b1]?[\d\s.,:\u00d7\u2212\u2013+\-^()\/%\u00b0eE\u2070-\u209f]*\d[\d\s.,:\u00d7\u2212\u2013+\-^()\/%\u00b0eE\u2070-\u209f]*$/;

  function markNumbers() {
    document.querySelectorAll("article table td, article table th").forEach((cell) => {
      cell.classList.toggle("scara-number", NUMBER_CELL.test(cell.textContent.trim()));
    });
  }

  // a number written with a signed exponent, which a browser may break after its sign ("3.03e-" / "05")
  const EXPONENT = /[-+\u2212]?\d[\d.,]*[eE][-+\u2212]\d+/g;

  /** Every number with a signed exponent in the tables under ``root`` kept on one line: wrapped in a
   * span.scara-nobr (the text is unchanged). */
  function keepNumbers(root) {
    const texts = [];
    root.querySelectorAll("table td, table th").forEach((cell) => {
      const walk = document.createTreeWalker(cell, NodeFilter.SHOW_TEXT);
      for (let n = walk.nextNode(); n; n = walk.nextNode()) {
        EXPONENT.lastIndex = 0;
        if (EXPONENT.test(n.data) && !n.parentElement.closest(".scara-nobr, mjx-container")) texts.push(n);
      }
    });
    texts.forEach((n) => {
      const parts = [];
      let last = 0;
      EXPONENT.lastIndex = 0;
      for (const m of n.data.matchAll(EXPONENT)) {
        if (m.index > last) parts.push(document.createTextNode(n.data.slice(last, m.index)));
        const span = document.createElement("span");
        span.className = "scara-nobr";
        span.textContent = m[0];
        parts.push(span);
        last = m.index + m[0].length;
      }
      if (last < n.data.length) parts.push(document.createTextNode(n.data.slice(last)));
      n.replaceWith(...parts);
    });
  }

  /** The live panels rewrite their table of results at each move: its numbers are kept whole each time. */
  function watchPanels() {
    document.querySelectorAll("[data-scara-panel]").forEach((panel) => {
      new MutationObserver((records) => {
        if (records.some((r) => r.target.closest && r.target.closest(".scara-panel-info"))) keepNumbers(panel);
      }).observe(panel, { childList: true, subtree: true });
    });
  }

  /** An inline formula wider than its line gets a line of its own (reader.css: .scara-wide-math), made smaller
   * to fit when that costs at most a quarter of its size; otherwise it scrolls there, with a cue. Measured again
   * whenever the column changes (the width of the window, a folded solution opened). */
  function fitInlineMath() {
    const all = Array.from(document.querySelectorAll("article mjx-container:not([display='true'])"))
      .filter((c) => !c.closest("table, .js-plotly-plot, .scara-page-panel"));
    // every write before every read: one layout for the whole page
    all.forEach((c) => {
      if (c.classList.contains("scara-wide-math")) { c.classList.remove("scara-wide-math"); c.style.fontSize = c.__scaraSize; }
    });
    const wide = all.map((c) => {
      const width = c.getBoundingClientRect().width;
      if (!width) return null;
      const block = c.parentElement.closest("p, li, dd, dt, figcaption, blockquote, section, div");
      if (!block) return null;
      const s = getComputedStyle(block);
      const room = block.clientWidth - parseFloat(s.paddingLeft) - parseFloat(s.paddingRight);
      return width > room + 0.5 ? { c, scale: room / width, size: parseFloat(getComputedStyle(c).fontSize) } : null;
    }).filter(Boolean);
    wide.forEach(({ c, scale, size }) => {
      c.__scaraSize = c.style.fontSize;
      c.classList.add("scara-wide-math");
      if (scale >= 0.75) c.style.fontSize = (size * scale * 0.97).toFixed(2) + "px";
    });
  }

  /** A table wider than its box gets the compact style (reader.css: .scara-compact). */
  function fitTables() {
    const tables = Array.from(document.querySelectorAll("article table"))
      .filter((t) => !t.closest(".js-plotly-plot, .scara-page-panel"));
    tables.forEach((t) => t.classList.remove("scara-compact"));
    tables.filter((t) => {
      const box = t.parentElement;
      return t.getBoundingClientRect().width > 0 && box && t.getBoundingClientRect().width > box.clientWidth + 0.5;
    }).forEach((t) => t.classList.add("scara-compact"));
  }

  // the boxes that may scroll sideways: wide tables, the outputs of cells, display equations, wide inline formulas
  const SCROLLERS = "article .pst-scrollable-table-container, article div.cell_output .output, "
                  + "article div.math > mjx-container, article mjx-container.scara-wide-math";

  /** A box that scrolls sideways is marked on each edge where its content continues (reader.css draws a shadow
   * there): scara-more-left, scara-more-right. */
  function cue(box) {
    const o = getComputedStyle(box).overflowX;
    const more = o === "auto" || o === "scroll" ? box.scrollWidth - box.clientWidth : 0;
    box.classList.toggle("scara-more-left", more > 1 && box.scrollLeft > 1);
    box.classList.toggle("scara-more-right", more > 1 && box.scrollLeft < more - 1);
  }

  function cues() {
    document.querySelectorAll(SCROLLERS).forEach((box) => {
      if (!box.__scaraCue) {
        box.__scaraCue = true;
        box.addEventListener("scroll", () => cue(box), { passive: true });
      }
      cue(box);
    });
  }

  function column() {
    markNumbers();
    keepNumbers(document.querySelector("article") || document.body);
    fitTables();
    fitInlineMath();
    cues();
  }

  let pending = false;
  function columnSoon() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => { pending = false; column(); });
  }

  /** Once MathJax has typeset the page (or at once when it has no math). */
  function whenMath(then, tries = 300) {
    const mj = window.MathJax;
    if (mj && mj.startup && mj.startup.promise) mj.startup.promise.then(then);
    else if (!document.querySelector(".math") || tries <= 0) then();
    else setTimeout(() => whenMath(then, tries - 1), 100);
  }

  // ---- search results without raw TeX --------------------------------------------------------------------------
  const SYMBOLS = {
    alpha: "α", beta: "β", gamma: "γ", delta: "δ", epsilon: "ε", varepsilon: "ε", zeta: "ζ", eta: "η",
    theta: "θ", vartheta: "ϑ", iota: "ι", kappa: "κ", lambda: "λ", mu: "μ", nu: "ν", xi: "ξ", pi: "π", rho: "ρ",
    sigma: "σ", tau: "τ", upsilon: "υ", phi: "φ", varphi: "φ", chi: "χ", psi: "ψ", omega: "ω",
    Gamma: "Γ", Delta: "Δ", Theta: "Θ", Lambda: "Λ", Xi: "Ξ", Pi: "Π", Sigma: "Σ", Phi: "Φ", Psi: "Ψ", Omega: "Ω",
    cdot: "·", times: "×", le: "≤", leq: "≤", ge: "≥", geq: "≥", ne: "≠", neq: "≠", approx: "≈", pm: "±",
    infty: "∞", partial: "∂", nabla: "∇", sum: "Σ", int: "∫", to: "→", rightarrow: "→", Rightarrow: "⇒",
    implies: "⇒", dots: "…", ldots: "…", cdots: "…", circ: "∘", deg: "°", sqrt: "√", in: "∈", quad: " ",
    qquad: " ", dagger: "†", top: "ᵀ", ell: "ℓ", mid: "|", lVert: "‖", rVert: "‖", Vert: "‖", langle: "⟨",
    rangle: "⟩", min: "min", max: "max", sin: "sin", cos: "cos", tan: "tan", det: "det", exp: "exp", log: "log",
  };
  const ACCENTS = { dot: "\u0307", ddot: "\u0308", hat: "\u0302", tilde: "\u0303", bar: "\u0304", vec: "\u20d7" };

  /** Plain text for a TeX fragment: J_{A} -> J_A, \vartheta_1 -> ϑ_1, \dot{q} -> q̇, \frac{a}{b} -> a/b. */
  function texToText(tex) {
    let s = tex;
    for (let n = 0; n < 4; n++) {  // nested groups, innermost first
      s = s.replace(/\\(?:d|t)?frac\s*\{([^{}]*)\}\s*\{([^{}]*)\}/g, "($1)/($2)")
           .replace(/\\(dot|ddot|hat|tilde|bar|vec)\s*\{([^{}]*)\}/g, (m, a, x) => x + ACCENTS[a])
           .replace(/\\(dot|ddot|hat|tilde|bar|vec)\s+(\\?[A-Za-z])/g, (m, a, x) => x + ACCENTS[a])
           .replace(/\\(?:text|mathrm|mathbf|mathit|boldsymbol|operatorname|textrm|mathcal|bm)\s*\{([^{}]*)\}/g, "$1");
    }
    s = s.replace(/\\(?:left|right|big|Big|bigg|Bigg)\b\s*\\?/g, "")
         .replace(/\\begin\{[^}]*\}|\\end\{[^}]*\}/g, " ")
         .replace(/\\\\/g, "; ").replace(/&/g, " ")
         .replace(/\\[,;:! ]/g, " ")
         .replace(/\\([A-Za-z]+)/g, (m, name) => (name in SYMBOLS ? SYMBOLS[name] : name))
         .replace(/\\([{}|%#$_])/g, "$1")
         .replace(/[{}]/g, "");
    return s.replace(/\s+/g, " ").trim();
  }

  /** Every \( ... \), \[ ... \] and $$ ... $$ of a text, as plain text. */
  function stripMath(text) {
    return text.replace(/\\\(([\s\S]*?)\\\)/g, (m, t) => texToText(t))
               .replace(/\\\[([\s\S]*?)\\\]/g, (m, t) => " " + texToText(t) + " ")
               .replace(/\$\$([\s\S]*?)\$\$/g, (m, t) => " " + texToText(t) + " ");
  }

  function readableSearch() {
    if (typeof Search === "undefined" || !Search.htmlToText || Search.htmlToText.__readable) return;
    const original = Search.htmlToText;
    Search.htmlToText = function (html, anchor) { return stripMath(original(html, anchor)); };
    Search.htmlToText.__readable = true;
  }

  // ---- a folded block opens from anywhere on its title bar ----------------------------------------------------
  /* sphinx-togglebutton listens on a folded admonition's title bar but only finds its button when the click lands
   * on the bar itself or the chevron: a click on the title's text or its link (a solution's "Exercise 4.1 (...)")
   * follows the link back to the exercise and throws. This listener, first in line (capture), turns any click on
   * the bar into a click on the chevron. */
  const TOGGLE_TITLE = ".admonition.dropdown > .admonition-title, .admonition.toggle > .admonition-title";

  function openFromTitle(event) {
    const target = event.target instanceof Element ? event.target : null;
    const title = target && target.closest(TOGGLE_TITLE);
    if (!title || target === title || target.closest(".toggle-button")) return;
    const button = title.querySelector(".toggle-button");
    if (!button) return;
    event.preventDefault();
    event.stopPropagation();
    button.click();
  }
  document.addEventListener("click", openFromTitle, true);

  window.scaraReader = { texToText, stripMath, applyTheme, darkened, themeAll, figures, rgba, luminance, put, column };

  readableSearch();
  document.addEventListener("DOMContentLoaded", readableSearch);
  window.addEventListener("load", () => {
    figures();
    new MutationObserver(themeAll).observe(document.documentElement, { attributes: true, attributeFilter: ["data-theme"] });
    whenMath(column);
    watchPanels();
    window.addEventListener("resize", columnSoon);
    // the column changes height when a folded solution or cell opens, or late content arrives: measure again
    const article = document.querySelector("article");
    if (article && window.ResizeObserver) new ResizeObserver(columnSoon).observe(article);
  });
})();
