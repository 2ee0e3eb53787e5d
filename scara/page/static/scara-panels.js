/* The book's live panels in a static page: the mechanics only. Each panel's declaration (controls, program,
 * bindings, first figures) is JSON the build wrote from the Python declaration; the computation of every move is
 * the package's own kernels, translated to JavaScript at build time (scara-engine.js), run in a Web Worker.
 * This file builds the native controls, schedules the work (moves made while the engine is busy collapse to
 * the latest), formats the declared texts, and hands the arrays to plotly.js. The contract other tools drive
 * is written in scara/page/assets.py. */
(function () {
  "use strict";
  const SCRIPT = document.currentScript && document.currentScript.src;
  const ENGINE = SCRIPT ? SCRIPT.replace(/scara-panels\.js(\?.*)?$/, "scara-engine.js") : "_static/scara-engine.js";

  // ---- Python's format mini-language, the part the declarations use: [sign][width][.precision](f|g|e|%) ----
  // Numbers are rounded from their decimal digits (101 significant digits of the double, which settle every
  // rounding a panel meets) with Python's ties-to-even, not JavaScript's ties-away.
  function digitsOf(a) {  // a > 0 finite: [digit string, exponent of the first digit]
    const [m, e] = a.toExponential(100).split("e");
    return [m.replace(".", ""), parseInt(e, 10)];
  }
  function roundDigits(d, k) {  // the first k (>= 0) digits of d rounded half-even: [digits, carried]
    if (k >= d.length) return [d + "0".repeat(k - d.length), false];
    const head = d.slice(0, k), next = d.charCodeAt(k) - 48, rest = /[1-9]/.test(d.slice(k + 1));
    const last = k > 0 ? head.charCodeAt(k - 1) - 48 : 0;
    const up = next > 5 || (next === 5 && (rest || last % 2 === 1));
    if (!up) return [head, false];
    const arr = head.split("").map(Number);
    let i = k - 1;
    while (i >= 0 && arr[i] === 9) { arr[i] = 0; i--; }
    if (i < 0) return ["1" + arr.join(""), true];
    arr[i] += 1;
    return [arr.join(""), false];
  }
  function fixed(v, p) {  // |v| with p decimals
    const a = Math.abs(v);
    if (a === 0) return p > 0 ? "0." + "0".repeat(p) : "0";
    if (a >= 1e21) return BigInt(a).toString() + (p > 0 ? "." + "0".repeat(p) : "");
    const [d, e] = digitsOf(a);
    const k = e + 1 + p;  // significant digits kept
    let digits, point;
    if (k < 0) { digits = ""; point = 0; }
    else {
      const [r, carried] = roundDigits(d, k);
      digits = r; point = e + 1 + (carried ? 1 : 0);
    }
    // digits holds the value's digits from 10^(point-1) down to 10^-p
    let intPart, frac;
    if (point <= 0) { intPart = "0"; frac = ("0".repeat(-point) + digits).padEnd(p, "0").slice(0, p); }
    else { intPart = digits.slice(0, point).padEnd(point, "0"); frac = digits.slice(point).padEnd(p, "0").slice(0, p); }
    intPart = intPart.replace(/^0+(?=\d)/, "");
    if (!/[1-9]/.test(intPart + frac) && digits === "") intPart = "0";
    return p > 0 ? intPart + "." + frac : intPart;
  }
  function expo(v, p) {  // |v| as d.ddd(p decimals)e+XX
    const a = Math.abs(v);
    let m, n;
    if (a === 0) { m = "0".repeat(p + 1); n = 0; }
    else {
      const [d, e] = digitsOf(a);
      const [r, carried] = roundDigits(d, p + 1);
      m = carried ? r.slice(0, p + 1) : r; n = e + (carried ? 1 : 0);
    }
    return m[0] + (p > 0 ? "." + m.slice(1) : "") + "e" + (n < 0 ? "-" : "+") + String(Math.abs(n)).padStart(2, "0");
  }
  function general(v, p) {
    if (p === 0) p = 1;
    const a = Math.abs(v);
    if (a === 0) return "0";
    const exp = parseInt(expo(a, p - 1).split("e")[1], 10);
    if (exp >= -4 && exp < p) {
      let s = fixed(a, p - 1 - exp);
      if (s.indexOf(".") >= 0) s = s.replace(/0+$/, "").replace(/\.$/, "");
      return s;
    }
    let [m, e] = expo(a, p - 1).split("e");
    if (m.indexOf(".") >= 0) m = m.replace(/0+$/, "").replace(/\.$/, "");
    return m + "e" + e;
  }
  function formatNumber(v, spec) {
    const m = /^([+ ])?(\d+)?(?:\.(\d+))?([fge%])$/.exec(spec);
    if (!m) throw new Error("format spec " + spec + " is not one the page formats");
    const [, sign, width, prec, type] = m;
    let body;
    const neg = v < 0 || Object.is(v, -0);
    if (Number.isNaN(v)) body = "nan";
    else if (!Number.isFinite(v)) body = "inf";
    else {
      const p = prec === undefined ? 6 : parseInt(prec, 10);
      if (type === "f") body = fixed(v, p);
      else if (type === "e") body = expo(v, p);
      else if (type === "%") body = (Number.isFinite(v * 100) ? fixed(v * 100, p) : "inf") + "%";
      else body = general(v, prec === undefined ? 6 : p);
    }
    let s = (neg && !Number.isNaN(v) ? "-" : (sign === "+" ? "+" : sign === " " ? " " : "")) + body;
    if (width) s = s.padStart(parseInt(width, 10), " ");
    return s;
  }
  function format(template, values) {
    return template.replace(/\{([A-Za-z_][A-Za-z0-9_]*)(?::([^{}]*))?\}/g, (all, name, spec) => {
      const v = values[name];
      if (v === undefined) throw new Error("the template " + template + " names " + name + ", which has no value");
      return spec ? formatNumber(Number(v), spec) : String(v);
    });
  }

  // ---- the engine: one worker for every panel of the page -------------------------------------------------------
  let worker = null;
  const waiting = {};
  let nextId = 1;
  function engine() {
    if (worker) return worker;
    worker = new Worker(ENGINE);
    worker.onmessage = (ev) => {
      const m = ev.data;
      const cb = waiting[m.id];
      delete waiting[m.id];
      if (cb) cb(m);
    };
    worker.onerror = (ev) => {
      for (const id of Object.keys(waiting)) { waiting[id]({error: "the page's engine failed: " + ev.message}); delete waiting[id]; }
    };
    return worker;
  }
  function ask(message, answered) {  // a message to the engine whose answer goes to answered(reply)
    const id = nextId++;
    waiting[id] = answered;
    engine().postMessage(Object.assign({id}, message));
  }

  // ---- the address: #NAME.KEY=VALUE&... ------------------------------------------------------------------------
  function readAddress() {
    const out = {};
    const hash = decodeURIComponent(location.hash.replace(/^#/, ""));
    if (hash.indexOf("=") < 0) return out;
    for (const part of hash.split("&")) {
      const eq = part.indexOf("=");
      const dot = part.indexOf(".");
      if (eq < 0 || dot < 0 || dot > eq) continue;
      const panel = part.slice(0, dot), key = part.slice(dot + 1, eq), value = part.slice(eq + 1);
      (out[panel] = out[panel] || {})[key] = value;
    }
    return out;
  }
  function writeAddress(name, changed) {
    const all = readAddress();
    if (changed && Object.keys(changed).length) all[name] = changed; else delete all[name];
    const parts = [];
    for (const [panel, kv] of Object.entries(all)) for (const [k, v] of Object.entries(kv)) parts.push(panel + "." + k + "=" + v);
    const url = location.pathname + location.search + (parts.length ? "#" + parts.map(encodeURI).join("&") : "");
    history.replaceState(null, "", url);
  }

  // ---- one panel -------------------------------------------------------------------------------------------------
  function el(tag, attrs, parent) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === "text") e.textContent = v; else if (k === "class") e.className = v; else e.setAttribute(k, v);
    }
    if (parent) parent.appendChild(e);
    return e;
  }
  // plotly keeps the objects it is given, and the reader's theme edits them in place (dark colours): it gets
  // copies, so that the panel's own record of each figure stays the light one the bindings write into
  function drawable(fig) {
    const data = fig.data.map((t) => {
      const c = Object.assign({}, t);
      for (const k of ["line", "marker", "textfont", "fillcolor"]) if (c[k] && typeof c[k] === "object") c[k] = JSON.parse(JSON.stringify(c[k]));
      return c;
    });
    const layout = JSON.parse(JSON.stringify(fig.layout));
    // the title is shown above the figure as text, which wraps on a phone (a plotly title does not)
    if (layout.title) layout.title = Object.assign({}, layout.title, {text: ""});
    return [data, layout];
  }
  function titleText(fig) {  // the figure's title as plain text, plotly's <br> as line breaks
    const t = (fig.layout.title || {}).text || "";
    return String(t).replace(/<br\s*\/?>/gi, "\n").replace(/<[^>]*>/g, "");
  }
  function float64(v) {  // {float64: base64 of little-endian float64s} (PageProgram.describe) to a Float64Array
    const bytes = Uint8Array.from(atob(v.float64), (ch) => ch.charCodeAt(0));
    return new Float64Array(bytes.buffer);
  }
  function plain(x) { return x instanceof Float64Array ? Array.from(x, (v) => (Number.isNaN(v) ? null : v)) : x; }
  class PagePanel {
    constructor(root, spec) {
      this.root = root;
      this.spec = spec;
      this.name = spec.name;
      this.prog = spec.program;
      this.seq = 0;
      this.busy = false;
      this.pending = null;
      this.stale = false;
      this.values = Object.assign({}, spec.values);
      this.defaults = Object.assign({}, spec.values);
      this.data = float64(this.prog.data);  // the panel's data; a carry updates it after a move
      this.history = [];  // a carrying panel's accepted edits, one per stretch of the same picks (the address)
      this.build();
      const saved = readAddress()[this.name];
      if (saved) this.load(saved);
      this.send();
      const replay = saved && this.prog.carry && saved.edits ? this.edits(saved.edits) : [];
      if (replay.length) this.run({t0: performance.now(), move: 0, replay});  // the earlier edits first, undrawn
      else this.schedule(performance.now());
      this.warmWhenSeen();
    }

    warmWhenSeen() {  // the engine's first runs of a program are 2-3 times slower (the browser compiles it as it
      // runs): once the reader has the panel in view, each choice of its selector runs twice at the panel's
      // settings, results unused, one at a time and only while no move is waiting, so the reader's moves find
      // it compiled
      const sel = this.spec.selector ? this.spec.controls.find((c) => c.name === this.spec.selector) : null;
      const choices = sel ? sel.options.map(([, v]) => ({[sel.name]: v})) : [{}];
      const queue = choices.concat(choices);
      const step = () => {
        if (!queue.length) return;
        if (this.busy) { setTimeout(step, 300); return; }
        this.compute(this.pack(Object.assign({}, this.values, queue.shift())), () => step());
      };
      if (typeof IntersectionObserver === "undefined") { step(); return; }
      const seen = new IntersectionObserver((entries) => {
        if (entries.some((e) => e.isIntersecting)) { seen.disconnect(); step(); }
      });
      seen.observe(this.root);
    }

    stretch(values) {  // the picks (PageProgram.react's controls) a carrying panel's edit was made at
      return Object.keys(this.prog.react || {}).map((n) => JSON.stringify(values[n])).join("|");
    }

    edits(text) {  // the address's earlier edits of a carrying panel: settings, each as LivePanel.values() gives them
      return text.split(";").filter((e) => e).map((e) => {
        const v = Object.assign({}, this.defaults);
        for (const kv of e.split(",")) {
          const i = kv.indexOf(":"), c = this.spec.controls.find((x) => x.name === kv.slice(0, i));
          if (!c) continue;
          const raw = kv.slice(i + 1);
          if (c.kind === "dropdown") { const o = c.options.find(([, x]) => String(x) === raw); if (o) v[c.name] = o[1]; }
          else if (c.kind === "toggle") v[c.name] = raw === "true";
          else if (Number.isFinite(Number(raw))) v[c.name] = Number(raw);
        }
        return v;
      });
    }

    send() {  // the data to the engine (prepared there from its compact form when the program has a prepare)
      engine().postMessage({type: "data", panel: this.name, data: this.data, prepare: this.prog.prepare,
                            size: this.prog.data_size, scratch: this.prog.scratch || 0});
    }

    react(name) {  // the controls a change of `name` sets, read from the data (PageProgram.react)
      const picks = (this.prog.react || {})[name];
      if (!picks) return;
      for (const [target, k] of Object.entries(picks)) {
        const v = this.data[k.offset + k.stride * Number(this.values[k.index])];
        const c = this.spec.controls.find((x) => x.name === target);
        let value;
        if (k.as_ === "flag") value = v > 0;
        else if (k.as_ === "value" || v > 0) value = v;
        else continue;
        this.values[target] = value;
        this.show(c, value);
      }
    }

    show(c, v) {  // a control's input showing the value v
      const input = this.inputs[c.name];
      if (c.kind === "dropdown") input.value = String(c.options.findIndex(([, x]) => JSON.stringify(x) === JSON.stringify(v)));
      else if (c.kind === "toggle") input.checked = !!v;
      else {
        input.value = String(Number(Number(v).toPrecision(12)));
        if (this.ranges[c.name]) this.ranges[c.name].value = String(c.scale === "log" ? Math.log10(v) : v);
      }
    }

    build() {
      const s = this.spec, root = this.root;
      root.classList.add("scara-panel");
      const head = el("div", {class: "scara-panel-head"}, root);
      el("b", {text: s.title}, head);
      const reset = el("button", {type: "button", class: "scara-panel-reset", text: "Reset to the book's values"}, head);
      reset.addEventListener("click", () => this.reset());
      el("span", {class: "scara-panel-live", text: "live: computed in this page by the package's own code"}, head);
      const grid = el("div", {class: "scara-panel-controls", style: "--scara-columns:" + s.columns}, root);
      this.inputs = {};
      this.ranges = {};
      for (const c of s.controls) this.control(grid, c);
      this.message = el("div", {class: "scara-panel-message", role: "status", "aria-live": "polite"}, root);
      this.figures = [];
      s.figures.forEach((f, k) => {
        // a figure with its caption, which the reader's scripts give the figure as its text alternative
        const box = el("figure", {class: "scara-panel-figure"}, root);
        const heading = el("div", {class: "scara-panel-figure-title"}, box);
        const gd = el("div", {class: "plotly-graph-div"}, el("div", {class: "scara-panel-figure-scroll"}, box));
        el("figcaption", {class: "scara-panel-caption", text: "Live figure " + (k + 1) + " of the panel \u201c" + s.title +
          "\u201d, recomputed in this page on every move of its controls."}, box);
        const fig = JSON.parse(JSON.stringify(f.figure));
        this.figures.push({spec: f, box, gd, fig, heading});
        heading.textContent = titleText(fig);
        Plotly.newPlot(gd, ...drawable(fig), {displaylogo: false, responsive: true});
      });
      this.notes = el("div", {class: "scara-panel-note"}, root);
      this.info = el("div", {class: "scara-panel-info"}, root);
      this.valuesEl = el("span", {class: "scara-panel-values", hidden: ""}, root);
      if (this.prog.drag) this.draggable(this.figures.find((f) => f.spec.role === this.prog.drag.figure));
      this.grey();
    }

    draggable(f) {  // PageProgram.drag: the reader drags a point of this figure; each pointer move is a move
      const d = this.prog.drag, gd = f.gd, by = (n) => this.spec.controls.find((c) => c.name === n);
      const caption = f.box.querySelector("figcaption");
      caption.textContent += " Drag one of its points (mouse or finger) to move it: its controls follow.";
      const pick = by(d.pick), cx = by(d.x), cy = by(d.y), rx = this.prog.react[d.pick][d.x], ry = this.prog.react[d.pick][d.y];
      const axes = () => { const fl = gd._fullLayout; return fl && fl.xaxis && fl.yaxis ? [fl.xaxis, fl.yaxis] : null; };
      const local = (ev) => { const r = gd.getBoundingClientRect(); return [ev.clientX - r.left, ev.clientY - r.top]; };
      const nearest = (ev) => {  // the point under the pointer (within 14 px; 24 for a finger), by its index
        const a = axes();
        if (!a || this.inputs[d.pick].disabled) return -1;
        const [px, py] = local(ev), reach = ev.pointerType === "touch" ? 24 : 14;
        let best = -1, dist = reach;
        pick.options.forEach(([, i]) => {
          const current = JSON.stringify(this.values[d.pick]) === JSON.stringify(i);
          const x = current ? this.values[d.x] : this.data[rx.offset + rx.stride * i];
          const y = current ? this.values[d.y] : this.data[ry.offset + ry.stride * i];
          const dx = a[0].l2p(x) + a[0]._offset - px, dy = a[1].l2p(y) + a[1]._offset - py, r = Math.hypot(dx, dy);
          if (r < dist) { dist = r; best = i; }
        });
        return best;
      };
      const place = (ev) => {  // the pointer's place in the axes' units, on the sliders' steps
        const a = axes(), [px, py] = local(ev);
        const round = (v, c) => Number((Math.round(v / c.step) * c.step).toPrecision(12));
        return [[cx, round(a[0].p2l(px - a[0]._offset), cx)], [cy, round(a[1].p2l(py - a[1]._offset), cy)]];
      };
      let held = null;
      gd.addEventListener("pointerdown", (ev) => {
        const i = nearest(ev);
        if (i < 0) return;
        ev.preventDefault();
        ev.stopPropagation();  // not plotly's zoom box
        held = ev.pointerId;
        gd.setPointerCapture(ev.pointerId);
        if (JSON.stringify(this.values[d.pick]) !== JSON.stringify(i)) {
          this.show(pick, i);
          this.changed(pick, this.inputs[d.pick]);  // picking it loads its values (react), one move
        }
      }, true);
      gd.addEventListener("pointermove", (ev) => {
        if (held === ev.pointerId) { ev.preventDefault(); ev.stopPropagation(); this.setMany(place(ev)); return; }
        const drag = gd.querySelector(".nsewdrag");
        if (drag) drag.style.cursor = nearest(ev) >= 0 ? "grab" : "";
      }, true);
      const release = (ev) => { if (held === ev.pointerId) { held = null; ev.stopPropagation(); } };
      gd.addEventListener("pointerup", release, true);
      gd.addEventListener("pointercancel", release, true);
      for (const type of ["mousedown", "touchstart"]) {  // plotly's own drag starts on these: not on a point held
        gd.addEventListener(type, (ev) => { if (held !== null) { ev.stopPropagation(); if (ev.cancelable) ev.preventDefault(); } },
                            {capture: true, passive: false});
      }
    }

    setMany(pairs) {  // several controls set together (a drag): one move, or the refusal of a value outside its range
      this.move = (this.move || 0) + 1;
      for (const [c, value] of pairs) {
        const input = this.inputs[c.name];
        input.value = String(value);
        const v = this.read(c, input);
        if (v instanceof Error) {
          this.values[c.name] = input.value;
          this.refusedAt = this.move;
          this.refuse(v.message);
          return;
        }
        this.values[c.name] = v;
        if (this.ranges[c.name]) this.ranges[c.name].value = String(c.scale === "log" ? Math.log10(v) : v);
      }
      this.schedule(performance.now());
    }

    control(grid, c) {
      const wrap = el("label", {class: "scara-panel-control"}, grid);
      el("span", {class: "scara-panel-label", text: c.label}, wrap);
      let input;
      if (c.kind === "dropdown") {
        input = el("select", {name: c.name}, wrap);
        c.options.forEach(([label, value], i) => {
          const o = el("option", {value: String(i), text: label}, input);
          if (JSON.stringify(value) === JSON.stringify(this.values[c.name])) o.selected = true;
        });
      } else if (c.kind === "toggle") {
        input = el("input", {type: "checkbox", name: c.name}, wrap);
        input.checked = !!this.values[c.name];
      } else {
        if (c.kind === "slider") {
          const log = c.scale === "log";
          const range = el("input", {type: "range", "aria-label": c.label + (log ? " (decades)" : ""),
            min: String(log ? Math.log10(c.low) : c.low), max: String(log ? Math.log10(c.high) : c.high),
            step: String(c.step)}, wrap);
          range.value = String(log ? Math.log10(this.values[c.name]) : this.values[c.name]);
          range.addEventListener("input", (ev) => {
            const v = log ? Math.pow(10, Number(range.value)) : Number(range.value);
            input.value = String(Number(v.toPrecision(12)));
            this.changed(c, input, ev);
          });
          this.ranges[c.name] = range;
        }
        input = el("input", {type: "number", name: c.name, step: "any", inputmode: "decimal"}, wrap);
        if (c.kind === "slider") { input.min = String(c.low); input.max = String(c.high); }
        input.value = String(Number(Number(this.values[c.name]).toPrecision(12)));
        if (c.unit) el("span", {class: "scara-panel-unit", text: c.unit}, wrap);
      }
      input.addEventListener("change", (ev) => this.changed(c, input, ev));
      this.inputs[c.name] = input;
    }

    read(c, input) {  // the control's value as LivePanel.values() gives it, or an Error naming the limit
      if (c.kind === "dropdown") return c.options[Number(input.value)][1];
      if (c.kind === "toggle") return input.checked;
      const v = input.value.trim() === "" ? NaN : Number(input.value);
      if (!Number.isFinite(v)) return new Error(format(c.not_number, {value: input.value || "(empty)"}));
      if (c.kind === "slider" && !(c.low <= v && v <= c.high)) return new Error(format(c.outside, {value: v}));
      return v;
    }

    changed(c, input, ev) {
      const v = this.read(c, input);
      this.move = (this.move || 0) + 1;
      if (v instanceof Error) {
        this.values[c.name] = input.value;
        this.refusedAt = this.move;  // a result of an earlier move, still on its way, is not drawn over this
        this.refuse(v.message);
        return;
      }
      this.values[c.name] = v;
      if (c.kind === "slider" && ev && ev.target === input && this.ranges[c.name]) {
        this.ranges[c.name].value = String(c.scale === "log" ? Math.log10(v) : v);
      }
      this.react(c.name);
      if (c.name === this.spec.selector || (this.prog.react || {})[c.name]) this.grey();
      this.schedule(performance.now());
    }

    grey() {
      const sel = this.spec.selector;
      for (const c of this.spec.controls) {
        const off = !!(sel && c.applies_to && !c.applies_to.some((x) => JSON.stringify(x) === JSON.stringify(this.values[sel])));
        this.inputs[c.name].disabled = off;
        if (this.ranges[c.name]) this.ranges[c.name].disabled = off;
      }
    }

    load(saved) {  // settings from the address
      for (const c of this.spec.controls) {
        if (!(c.name in saved)) continue;
        const input = this.inputs[c.name];
        if (c.kind === "dropdown") input.value = String(c.options.findIndex(([, v]) => String(v) === saved[c.name]));
        else if (c.kind === "toggle") input.checked = saved[c.name] === "true";
        else input.value = saved[c.name];
        const v = this.read(c, input);
        if (!(v instanceof Error)) {
          this.values[c.name] = v;
          if (this.ranges[c.name]) this.ranges[c.name].value = String(c.scale === "log" ? Math.log10(v) : v);
        }
      }
      this.grey();
    }

    reset() {
      this.move = (this.move || 0) + 1;
      for (const c of this.spec.controls) this.show(c, this.defaults[c.name]);
      this.values = Object.assign({}, this.defaults);
      if (this.prog.carry) { this.data = float64(this.prog.data); this.history = []; this.send(); }
      this.grey();
      writeAddress(this.name, null);
      this.schedule(performance.now());
    }

    pack(values) {
      const by = Object.fromEntries(this.spec.controls.map((c) => [c.name, c]));
      return this.prog.inputs.map((i) => {
        const c = by[i.name], v = values[i.name];
        if (c.kind === "dropdown") return c.options.findIndex(([, x]) => JSON.stringify(x) === JSON.stringify(v));
        if (c.kind === "toggle") return v ? 1 : 0;
        return Number(v);
      });
    }

    schedule(t0) {
      const job = {t0, values: Object.assign({}, this.values), move: this.move || 0};
      if (this.busy) { this.pending = job; return; }
      this.run(job);
    }

    run(job) {  // the engine computes one move at a time; the page draws the last result meanwhile
      this.busy = true;
      // what this run computes: the latest settings, or an earlier edit the address replays
      job.values = job.replay ? job.replay[0] : Object.assign({}, this.values);
      this.compute(this.pack(job.values), (m) => this.done(job, m));
    }

    compute(inputs, answered) {  // one run of the panel's program in the engine
      ask({type: "run", panel: this.name, kernel: this.prog.kernel, inputs, size: this.prog.size}, answered);
    }

    engineData() {  // a promise of the data as the engine holds it (prepared in the page), scratch left out
      return new Promise((resolve) => ask({type: "dump", panel: this.name}, (m) => resolve(m.data ? Array.from(m.data) : null)));
    }

    next() {
      this.busy = false;
      if (this.pending) { const job = this.pending; this.pending = null; this.run(job); }
    }

    redraw(f) {  // one figure redrawn from its record, in the page's theme: drawn dark at once when the page is
      // dark and the figure already follows it (scaraReader.darkened), otherwise themed after the redraw
      const [data, layout] = drawable(f.fig);
      const dark = !!(window.scaraReader && window.scaraReader.darkened && window.scaraReader.darkened(f.gd, data, layout));
      return Plotly.react(f.gd, data, layout).then(() => {
        if (dark || !window.scaraReader) return undefined;
        f.gd.__themeDark = false;
        return window.scaraReader.applyTheme(f.gd);
      });
    }

    outputs(out, settings) {
      const v = Object.assign({}, settings);
      for (const f of this.prog.outputs) v[f.name] = f.size === 1 ? out[f.offset] : out.slice(f.offset, f.offset + f.size);
      return v;
    }

    bound(b, v) {
      if (b.list) return b.list.map((x) => this.bound(x, v));
      if (b.text !== undefined) return format(b.text, v);
      if (b.flag !== undefined) return v[b.flag] !== 0;
      return plain(v[b.field]);
    }

    done(job, m) {
      const tc = performance.now();
      const v = m.error ? null : this.outputs(m.out, job.values);
      if (v && m.status === 0 && this.prog.carry) {  // an accepted move: the next one starts from its result
        const c = this.prog.carry, f = this.prog.outputs.find((x) => x.name === c.field);
        this.data.set(m.out.subarray(f.offset, f.offset + f.size), c.offset);
        this.send();
        const at = this.stretch(job.values), last = this.history[this.history.length - 1];
        if (last && last.at === at) last.values = job.values; else this.history.push({at, values: job.values});
      }
      if (job.replay) {  // the address's edits, one after the other, then the settings it shows
        this.busy = false;
        if (job.replay.length > 1) this.run({t0: job.t0, move: 0, replay: job.replay.slice(1)});
        else this.schedule(job.t0);
        return;
      }
      this.next();  // a move made meanwhile starts computing now, while this one is drawn
      if (job.move < (this.refusedAt || 0)) return;  // a later setting was refused: this result is not current
      if (m.error) { this.refuse(m.error); return; }
      if (m.status !== 0) {
        const t = this.prog.refusals[String(m.status)];
        this.refuse(t === undefined ? "the panel's program returned status " + m.status + ", which it does not declare" : format(t, v));
        return;
      }
      const draws = this.figures.map((f) => {
        const role = f.spec.role;
        // back from a refusal: every trace as the first figure had it, then the bound properties (visible too)
        if (this.stale) f.fig.data.forEach((t, i) => { t.visible = f.spec.figure.data[i].visible === undefined ? true : f.spec.figure.data[i].visible; });
        for (const [key, props] of Object.entries(this.prog.traces[role] || {})) {
          const i = f.spec.index[key];
          for (const [prop, b] of Object.entries(props)) f.fig.data[i][prop] = this.bound(b, v);
        }
        for (const [path, b] of Object.entries(this.prog.paths[role] || {})) window.scaraReader.put(f.fig.layout, path, this.bound(b, v));
        const title = this.prog.titles[role];
        if (title !== undefined) f.fig.layout.title = Object.assign({}, f.fig.layout.title || {}, {text: format(title, v)});
        else if (this.stale) f.fig.layout.title = JSON.parse(JSON.stringify(f.spec.figure.layout.title || {}));
        f.fig.layout.datarevision = this.seq + 1;
        f.heading.textContent = titleText(f.fig);
        return this.redraw(f);
      });
      this.stale = false;
      this.root.classList.remove("scara-stale");
      this.message.textContent = "";
      const rows = this.prog.rows.map(([label, t]) => [label, format(t, v)]);
      const notes = this.prog.notes.filter(([flag]) => v[flag] !== 0).map(([, t]) => format(t, v));
      Promise.all(draws).then(() => {
        this.table(rows);
        this.notes.replaceChildren(...notes.map((n) => el("div", {text: "⚠ " + n})));
        this.record({compute_ms: m.compute_ms, draw_ms: performance.now() - tc, total_ms: performance.now() - job.t0},
                    job.values);
        this.address();
      });
    }

    table(rows) {
      const t = el("table", {class: "scara-panel-table"});
      for (const [a, b] of rows) {
        const tr = el("tr", {}, t);
        el("td", {text: a}, tr);
        el("b", {text: b}, el("td", {}, tr));
      }
      this.info.replaceChildren(...(rows.length ? [t] : []));
    }

    record(timings, values) {  // the settings the figures now show (a move's own, not those made since)
      this.seq += 1;
      this.valuesEl.textContent = JSON.stringify(Object.assign({values: values || this.values, seq: this.seq}, timings || {}));
      this.root.dispatchEvent(new CustomEvent("scara-redraw", {detail: {seq: this.seq, timings}}));
    }

    address() {
      const changed = {};
      for (const c of this.spec.controls) {
        const v = this.values[c.name];
        if (JSON.stringify(v) !== JSON.stringify(this.defaults[c.name])) changed[c.name] = String(v);
      }
      // a carrying panel's edits build on each other: the earlier stretches too, replayed in order on a reload
      const earlier = this.history.slice(0, -1).map((h) => this.spec.controls
        .filter((c) => JSON.stringify(h.values[c.name]) !== JSON.stringify(this.defaults[c.name]))
        .map((c) => c.name + ":" + String(h.values[c.name])).join(","));
      if (earlier.length) changed.edits = earlier.join(";");
      writeAddress(this.name, changed);
    }

    refuse(text) {
      this.message.replaceChildren(el("b", {text: this.spec.refused + " "}), document.createTextNode(text));
      this.notes.replaceChildren();
      this.info.replaceChildren();
      if (!this.stale) {
        this.stale = true;
        this.root.classList.add("scara-stale");
        for (const f of this.figures) {
          f.fig.data.forEach((t) => { t.visible = false; });
          f.fig.layout.title = Object.assign({}, f.fig.layout.title || {}, {text: this.spec.stale_title});
          f.heading.textContent = titleText(f.fig);
          this.redraw(f);
        }
      }
      this.record({});
    }
  }

  function start() {
    document.querySelectorAll("[data-scara-panel]").forEach((root) => {
      if (root.__scaraPanel) return;
      const specEl = root.querySelector("script.scara-panel-spec");
      if (!specEl || !window.Plotly || typeof Worker === "undefined") return;
      root.__scaraPanel = new PagePanel(root, JSON.parse(specEl.textContent));
    });
  }
  window.scaraFormat = format;  // the tests check the formatter against Python's
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start); else start();
})();
