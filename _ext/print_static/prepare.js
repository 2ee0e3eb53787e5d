// Turns a built chapter page, loaded and drawn, into print: run once by _ext/print_edition.py in Chromium.
// Each plotly figure with controls becomes small multiples (images of a few of its states), each animation a
// strip of frames; live panels and controls give way to a line of text; ids and links are made unique for a
// book of many chapters. Returns {html, styles, sheets, sections, figures}: the article, MathJax's styles, the page's
// style sheets, its sections and what was printed.
async (args) => {
  const {stem, pages, multiples, frames, width} = args;
  const article = document.querySelector('article.bd-article');
  if (!article) throw new Error(`no article.bd-article in ${location.href} ("${document.title}")`);
  const figures = [];
  const pick = (n, k, keep) => {            // k evenly spaced indices of n, always the first, last and `keep`
    if (n <= k) return [...Array(n).keys()];
    const out = new Set([0, n - 1, keep]);
    for (let i = 1; out.size < k && i < k - 1; i++) out.add(Math.round(i * (n - 1) / (k - 1)));
    return [...out].sort((a, b) => a - b);
  };
  // a still of the figure as it stands, without its controls (the label under each still says the step)
  const still = (gd, w, h) => Plotly.toImage({data: gd.data, layout: Object.assign({}, gd.layout,
      {sliders: [], updatemenus: []})}, {format: 'svg', width: w, height: h});
  const grid = (gd, shots, kind, what) => {
    const box = document.createElement('div');
    box.className = 'print-multiples print-' + kind;
    for (const s of shots) {
      const cell = document.createElement('figure');
      cell.className = 'print-multiple';
      const img = document.createElement('img');
      img.src = s.src; img.alt = s.label;
      const cap = document.createElement('figcaption');
      cap.textContent = s.label;
      cell.append(img, cap);
      box.append(cell);
    }
    const note = document.createElement('p');
    note.className = 'print-multiples-note';
    note.textContent = what;
    gd.replaceWith(box);
    box.after(note);
    unbox(box);
  };
  // the boxes around a figure were sized for the figure: they take their content's height now
  const unbox = (el) => {
    for (let e = el.parentElement; e && e !== article; e = e.parentElement)
      Object.assign(e.style, {height: 'auto', maxHeight: 'none', overflow: 'visible'});
  };
  const apply = async (gd, step) => {
    if (step.method === 'animate') {
      await Plotly.animate(gd, step.args[0], {mode: 'immediate', frame: {duration: 0, redraw: true},
                                               transition: {duration: 0}});
    } else if (step.method && step.method !== 'skip') {
      await Plotly[step.method](gd, ...step.args);
    }
  };
  for (const gd of Array.from(article.querySelectorAll('.plotly-graph-div'))) {
    if (!gd._fullLayout || gd.closest('.scara-page-panel')) continue;
    const layout = gd.layout;
    const caption = (() => { const f = gd.closest('figure'); const c = f && f.querySelector('figcaption .caption-number');
                             return c ? c.textContent.trim() : gd.id; })();
    const menus = (layout.updatemenus || []);
    const play = menus.some(m => (m.buttons || []).some(b => b.method === 'animate'));
    const framesOf = (gd._transitionData && gd._transitionData._frames) || [];
    const w = gd._fullLayout.width, h = gd._fullLayout.height;
    const small = Math.round(width * 0.65), tall = Math.round(h * small / w);
    if (play && framesOf.length) {
      const slider = (layout.sliders || [])[0];
      const steps = slider ? slider.steps : framesOf.map(f => ({label: f.name, args: [[f.name]]}));
      const prefix = slider && slider.currentvalue && slider.currentvalue.prefix || '';
      const shots = [];
      for (const i of pick(steps.length, frames, 0)) {
        await apply(gd, {method: 'animate', args: steps[i].args});
        shots.push({label: (prefix + (steps[i].label ?? '')).trim(), src: await still(gd, small, tall)});
      }
      grid(gd, shots, 'frames', `The animation, ${shots.length} of its ${steps.length} frames.`);
      figures.push({caption, kind: 'animation', labels: shots.map(s => s.label), of: steps.length});
      continue;
    }
    const slider = (layout.sliders || [])[0];
    const buttons = menus.filter(m => (m.buttons || []).length > 1 && m.type !== 'buttons').flatMap(m => m.buttons);
    if (slider && slider.steps && slider.steps.length > 1) {
      const prefix = slider.currentvalue && slider.currentvalue.prefix || '';
      const shots = [];
      for (const i of pick(slider.steps.length, multiples, slider.active || 0)) {
        await apply(gd, slider.steps[i]);
        await Plotly.relayout(gd, {'sliders[0].active': i});
        shots.push({label: (prefix + (slider.steps[i].label ?? '')).trim(), src: await still(gd, small, tall)});
      }
      grid(gd, shots, 'steps', `The figure's slider at ${shots.length} of its ${slider.steps.length} steps.`);
      figures.push({caption, kind: 'slider', labels: shots.map(s => s.label), of: slider.steps.length});
      continue;
    }
    if (buttons.length > 1) {
      const shots = [];
      for (const b of buttons) {
        await apply(gd, b);
        shots.push({label: b.label, src: await still(gd, small, tall)});
      }
      grid(gd, shots, 'choices', `The figure for each choice of its menu.`);
      figures.push({caption, kind: 'menu', labels: shots.map(s => s.label), of: buttons.length});
      continue;
    }
    const img = document.createElement('img');
    img.className = 'print-still';
    img.src = await still(gd, w, h);
    img.alt = gd.getAttribute('aria-label') || caption;
    gd.replaceWith(img);
    unbox(img);
    figures.push({caption, kind: 'still', labels: [], of: 1});
  }
  // live panels and anything else that needs a kernel or a script: one line of text in their place
  article.querySelectorAll('.scara-page-panel').forEach(p => {
    const note = document.createElement('p');
    note.className = 'print-live-note';
    note.textContent = 'A live panel stands here in the web book and in the notebook (it needs a browser or a kernel).';
    p.replaceWith(note);
  });
  article.querySelectorAll('.plotly-graph-div, script, noscript, button, .headerlink, .take-home, #take-home, '
                           + '.scara-panel-spec, .scara-panel-noscript, .toggle-button, .copybtn').forEach(e => e.remove());
  // code the web page folds away stays off paper; folded solutions print open
  article.querySelectorAll('details.above-input').forEach(d => d.remove());
  article.querySelectorAll('details').forEach(d => d.setAttribute('open', ''));
  article.querySelectorAll('.toggle-hidden, .toggle-details__container').forEach(e => e.classList.remove('toggle-hidden'));
  // one book: ids prefixed with the page's name, links between pages made links inside the book
  const local = (id) => stem + '--' + id;
  article.querySelectorAll('[id]').forEach(e => { if (!(e instanceof SVGElement)) e.id = local(e.id); });
  article.querySelectorAll('a[href]').forEach(a => {
    const href = a.getAttribute('href');
    if (href.startsWith('#')) { a.setAttribute('href', '#' + local(href.slice(1))); return; }
    const m = href.match(/^(?:\.\/)?([\w-]+)\.html(?:#(.*))?$/);
    if (m && pages.includes(m[1])) a.setAttribute('href', '#' + (m[2] ? m[1] + '--' + m[2] : 'page--' + m[1]));
    else if (!/^(https?:|mailto:)/.test(href)) { a.removeAttribute('href'); a.classList.add('print-unlinked'); }
  });
  const styles = Array.from(document.querySelectorAll('style')).filter(s => /mjx-/.test(s.textContent))
                      .map(s => s.textContent).join('\n');
  // numbers in tables never break (text in them may)
  article.querySelectorAll('td, th').forEach(c => {
    if (/^[\s\d.,+\-−eE%×()\/]+$/.test(c.textContent.trim())) c.classList.add('print-number'); });
  // the sections of the page, for the contents: [id, title] of each second-level heading
  const sections = Array.from(article.querySelectorAll('section[id] > h2')).map(h => [h.parentElement.id,
      h.textContent.replace(/#$/, '').trim()]);
  const sheets = Array.from(document.querySelectorAll('link[rel="stylesheet"]')).map(l => l.getAttribute('href'));
  return {html: article.innerHTML, styles, sheets, sections, figures};
}
