"""Drive a real JupyterLab in Debian's Chromium, as a learner does: open a chapter, run all cells, move the
controls of the live panels and watch the figures redraw.

Used by ``tests/book/test_jupyterlab.py`` (which asserts) and ``benchmarks/live_panels.py`` (which times). The
server is started on 127.0.0.1 with a free port and no token, on a temporary copy of the chapters as a learner
gets them: the take-home copies from the built book's download (``_downloads/scara-course.zip``: the chapters as
JupyterLab reads them, numbers, captions and references included; running them never touches the committed
notebooks), with its own settings folder (no news pop-up, every cell kept in
the page) and stopped afterwards. Nothing is fetched from outside this machine: every request that is not to
the server is aborted and recorded.
"""
from __future__ import annotations

import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
import zipfile
from contextlib import contextmanager
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BOOK = ROOT / "book"
#: the take-home download of the built book, whose chapters a learner opens in JupyterLab
TAKE_HOME = Path(os.environ.get("SCARA_BOOK_HTML", ROOT / "_build" / "html")) / "_downloads" / "scara-course.zip"
CHROMIUM = os.environ.get("SCARA_CHROMIUM", "/usr/bin/chromium")
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-quic"]

#: JupyterLab settings for a quiet, deterministic session
SETTINGS = {
    "@jupyterlab/apputils-extension/notification.jupyterlab-settings": {"fetchNews": "false",
                                                                        "checkForUpdates": False},
    # keep every cell in the page, so that all outputs can be inspected without scrolling them into view
    "@jupyterlab/notebook-extension/tracker.jupyterlab-settings": {"windowingMode": "none",
                                                                   "autoStartDefaultKernel": True},
}


def jupyter_executable() -> Path | None:
    exe = Path(sys.executable).parent / "jupyter"
    return exe if exe.exists() else (Path(p) if (p := shutil.which("jupyter")) else None)


def chromium_available() -> bool:
    return Path(CHROMIUM).exists() or shutil.which(CHROMIUM) is not None


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_until_up(url: str, proc, timeout: float, log_path) -> None:
    """Wait until the JupyterLab server ``proc`` answers ``url``/api/status; ``RuntimeError`` with the end of its
    log ``log_path`` if it exits first or does not answer within ``timeout`` s."""
    deadline = time.monotonic() + timeout
    while True:
        if proc.poll() is not None:
            raise RuntimeError(f"jupyter lab exited with {proc.returncode}:\n{Path(log_path).read_text()[-3000:]}")
        try:
            with urllib.request.urlopen(f"{url}/api/status", timeout=2) as r:
                if r.status == 200:
                    return
        except OSError:
            pass
        if time.monotonic() > deadline:
            raise RuntimeError(f"jupyter lab did not answer on {url} within {timeout:.0f} s:\n"
                               f"{Path(log_path).read_text()[-3000:]}")
        time.sleep(0.3)


def stop_process_group(proc) -> None:
    """End a server started with ``start_new_session=True`` and everything it started (its kernels): SIGTERM to
    its process group, SIGKILL if it is still there after 20 s."""
    try:
        os.killpg(proc.pid, signal.SIGTERM)
        proc.wait(timeout=20)
    except (ProcessLookupError, subprocess.TimeoutExpired):
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


@contextmanager
def jupyterlab_server(notebooks=None, timeout: float = 180.0):
    """Start ``jupyter lab`` on a temporary copy of ``notebooks`` (default: every chapter and page of the book's
    folder in the take-home download, :data:`TAKE_HOME`); yield its base URL. The server, its kernels and its
    temporary folders are removed on exit."""
    exe = jupyter_executable()
    if exe is None:
        raise RuntimeError("jupyter is not installed in this environment")
    if notebooks is None and not TAKE_HOME.is_file():
        raise RuntimeError(f"the book is not built: {TAKE_HOME} is missing (jupyter-book build . first)")
    tmp = Path(tempfile.mkdtemp(prefix="scara-lab-"))
    root = tmp / "book"
    root.mkdir()
    if notebooks is None:
        with zipfile.ZipFile(TAKE_HOME) as zf:
            for name in zf.namelist():
                if Path(name).parent.name == "book" and not name.endswith("/"):  # the chapters and their files
                    (root / Path(name).name).write_bytes(zf.read(name))
    for nb in notebooks or ():
        shutil.copy(nb, root / Path(nb).name)
    settings = tmp / "settings"
    for name, value in SETTINGS.items():
        path = settings / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(value))
    env = dict(os.environ, JUPYTER_CONFIG_DIR=str(tmp / "config"), JUPYTERLAB_SETTINGS_DIR=str(settings),
               JUPYTERLAB_WORKSPACES_DIR=str(tmp / "workspaces"), JUPYTER_RUNTIME_DIR=str(tmp / "runtime"),
               IPYTHONDIR=str(tmp / "ipython"))
    port = _free_port()
    log = open(tmp / "server.log", "w")
    proc = subprocess.Popen(
        [str(exe), "lab", "--no-browser", "--ServerApp.ip=127.0.0.1", f"--ServerApp.port={port}",
         "--ServerApp.port_retries=0", "--allow-root", "--IdentityProvider.token=", "--ServerApp.password=",
         f"--ServerApp.root_dir={root}", "--LabApp.news_url=", "--ServerApp.disable_check_xsrf=True"],
        stdout=log, stderr=subprocess.STDOUT, env=env, start_new_session=True)
    url = f"http://127.0.0.1:{port}"
    try:
        wait_until_up(url, proc, timeout, tmp / "server.log")
        yield url
    finally:
        stop_process_group(proc)
        log.close()
        shutil.rmtree(tmp, ignore_errors=True)


@contextmanager
def chromium():
    """A headless Chromium (Debian's, through Playwright); yields the browser."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        try:
            yield browser
        finally:
            browser.close()


# JavaScript run in the page ------------------------------------------------------------------------------
#: record every plotly_afterplot of every figure, and the time of every key press and change
INSTRUMENT = """() => {
  window.__scara = window.__scara || {after: [], keys: [], hooked: new WeakSet()};
  if (!window.__scara.listening) {
    window.__scara.listening = true;
    for (const ev of ['keydown', 'change', 'click']) {
      document.addEventListener(ev, () => window.__scara.keys.push(performance.now()), true);
    }
  }
  const plots = Array.from(document.querySelectorAll('.js-plotly-plot'));
  plots.forEach((gd, i) => {
    if (!window.__scara.hooked.has(gd) && gd.on) {
      window.__scara.hooked.add(gd);
      gd.on('plotly_afterplot', () => window.__scara.after.push({plot: gd.dataset.scaraId || '', t: performance.now()}));
    }
  });
  return plots.length;
}"""

#: a summary of one panel's figures: traces (name, visible, x/y/z as plain arrays) and title
FIGURES = """(panel) => {
  const arr = (v) => (v === undefined || v === null) ? null : (typeof v === 'string' ? v :
                     Array.from(v, e => (e === null || e === undefined) ? null : (typeof e === 'string' ? e : Number(e))));
  return Array.from(panel.querySelectorAll('.js-plotly-plot')).map(gd => ({
    title: (gd.layout && gd.layout.title && (gd.layout.title.text !== undefined ? gd.layout.title.text : gd.layout.title)) || '',
    stale: !!gd.closest('.scara-stale'),
    traces: (gd.data || []).map((t, i) => {
      // arrays as plotly decoded them (gd.data may hold them base64-encoded)
      const full = (gd._fullData || []).find(f => f.index === i) || {};
      const pick = (k) => arr(full[k] !== undefined ? full[k] : t[k]);
      return {name: t.name || '', visible: t.visible === undefined ? true : t.visible, type: t.type || 'scatter',
              x: pick('x'), y: pick('y'), z: (t.type === 'heatmap') ? null : pick('z'),
              text: Array.isArray(full.text) || ArrayBuffer.isView(full.text) ? Array.from(full.text) : (t.text === undefined ? null : t.text)};
    }),
  }));
}"""


class Lab:
    """One JupyterLab page: open a notebook, run it, inspect it, move controls, time redraws."""

    def __init__(self, browser, url: str, width: int = 1400, height: int = 1000):
        self.url = url
        self.context = browser.new_context(viewport={"width": width, "height": height})
        self.page = self.context.new_page()
        self.external: list[str] = []
        self.console_errors: list[str] = []
        self.page_errors: list[str] = []
        self.context.route("**/*", self._route)
        # the end of the page's last long task (a main-thread task over 50 ms): see :meth:`settle`
        self.context.add_init_script("""window.__scaraLastLong = 0;
          try { new PerformanceObserver((list) => { for (const e of list.getEntries())
                  window.__scaraLastLong = Math.max(window.__scaraLastLong, e.startTime + e.duration); })
                .observe({type: 'longtask', buffered: true}); } catch (err) {}""")
        self.page.on("console", self._console)
        self.page.on("pageerror", lambda exc: self.page_errors.append(str(exc)))

    def _route(self, route):
        if route.request.url.startswith(self.url):
            route.continue_()
        else:
            self.external.append(route.request.url)
            route.abort()

    def _console(self, msg):
        if msg.type == "error":
            self.console_errors.append(msg.text)

    def close(self):
        """Close the page and shut down every kernel of the server (the next chapter starts afresh)."""
        self.context.close()
        with urllib.request.urlopen(f"{self.url}/api/kernels", timeout=10) as r:
            kernels = json.load(r)
        for k in kernels:
            req = urllib.request.Request(f"{self.url}/api/kernels/{k['id']}", method="DELETE")
            try:
                urllib.request.urlopen(req, timeout=20).close()
            except OSError:
                pass

    # -- notebooks ----------------------------------------------------------------------------------------
    def open(self, name: str, timeout: float = 180.0):
        self.page.goto(f"{self.url}/lab/tree/{name}?reset", wait_until="domcontentloaded")
        self.page.wait_for_selector(".jp-Notebook .jp-Cell", timeout=timeout * 1000)
        # JupyterLab may still ask which kernel to start if the kernel list came late: take the notebook's own
        dialog = self.page.locator(".jp-Dialog", has_text="Select Kernel")
        try:
            dialog.wait_for(timeout=1500)
            dialog.locator("button.jp-mod-accept").click()
        except Exception:  # noqa: BLE001 - no dialog: the kernel started by itself
            pass
        self.wait_kernel_idle(timeout)

    def kernel_status(self) -> str:
        return self.page.evaluate("""() => {
          const el = document.querySelector('.jp-NotebookPanel:not(.lm-mod-hidden) .jp-Toolbar-kernelStatus, '
                                           + '.jp-NotebookPanel:not(.lm-mod-hidden) [data-jp-item-name="kernelStatus"]');
          return el ? (el.getAttribute('title') || el.getAttribute('aria-label') || el.className) : '';
        }""")

    def wait_kernel_idle(self, timeout: float = 180.0):
        """Wait until the notebook's kernel has started and is idle (the status bar reads
        "Python 3 (ipykernel) | Idle")."""
        self.page.wait_for_function("""() => Array.from(document.querySelectorAll('.jp-StatusBar-Widget span, .jp-StatusBar-TextItem'))
            .some(e => /\\(ipykernel\\)\\s*\\|\\s*Idle/.test(e.textContent))""", timeout=timeout * 1000, polling=100)

    def run_all(self, timeout: float = 900.0) -> float:
        """Run → Run All Cells; wait until the kernel is idle with no cell queued or running (a failing cell
        stops the run: :meth:`cell_errors` tells). Returns the seconds it took."""
        t0 = time.monotonic()
        started = """() => Array.from(document.querySelectorAll('.jp-NotebookPanel:not(.lm-mod-hidden) .jp-CodeCell .jp-InputPrompt'))
                           .some(p => /\\[(\\d+|\\*)\\]/.test(p.textContent))"""
        for attempt in range(3):  # a kernel still starting may drop the first request
            self.page.locator(".lm-MenuBar-itemLabel", has_text="Run").first.click()
            self.page.locator(".lm-Menu-itemLabel", has_text="Run All Cells").first.click()
            try:
                self.page.wait_for_function(started, timeout=60000, polling=100)
                break
            except Exception:  # noqa: BLE001 - try again
                self.page.keyboard.press("Escape")
        done = """() => {
          const prompts = Array.from(document.querySelectorAll('.jp-NotebookPanel:not(.lm-mod-hidden) .jp-CodeCell .jp-InputPrompt'));
          const busy = document.querySelector('.jp-NotebookPanel:not(.lm-mod-hidden) .jp-Notebook-ExecutionIndicator');
          return prompts.some(p => /\\[\\d+\\]/.test(p.textContent)) && !prompts.some(p => p.textContent.includes('*'))
                 && busy && busy.getAttribute('data-status') === 'idle';
        }"""
        while True:
            self.page.wait_for_function(done, timeout=max(1.0, timeout - (time.monotonic() - t0)) * 1000, polling=100)
            elapsed = time.monotonic() - t0
            self.page.wait_for_timeout(700)  # still done a moment later: not between two cells
            if self.page.evaluate(done):
                self.settle()  # let the page finish typesetting and drawing the outputs
                return elapsed

    def settle(self, quiet: float = 2.0, timeout: float = 30.0) -> float:
        """Wait until the page has run no long task for ``quiet`` s (at most ``timeout`` s), as a reader who
        has just run a chapter scrolls to its panel; returns the seconds waited."""
        return self.page.evaluate("""([quiet, timeout]) => new Promise((resolve) => {
          const t0 = performance.now();
          const tick = () => {
            const now = performance.now();
            if (now - Math.max(t0, window.__scaraLastLong || 0) >= quiet || now - t0 >= timeout) resolve((now - t0) / 1000);
            else setTimeout(tick, 100);
          };
          tick();
        })""", [quiet * 1000, timeout * 1000])

    def cell_errors(self) -> list[str]:
        return self.page.evaluate("""() => Array.from(document.querySelectorAll(
            '.jp-OutputArea-output[data-mime-type="application/vnd.jupyter.stderr"], '
          + '.jp-OutputArea-output[data-mime-type="application/vnd.jupyter.error"]'))
          .map(e => e.textContent.slice(0, 600))""")

    def log_console_entries(self) -> list[str]:
        """Open the Log Console for this notebook and return what it lists (level: all)."""
        self.page.locator(".lm-MenuBar-itemLabel", has_text="View").first.click()
        self.page.locator(".lm-Menu-itemLabel", has_text="Show Log Console").first.click()
        self.page.wait_for_selector(".jp-LogConsole", timeout=60000)
        # show every level, debug included
        select = self.page.locator(".jp-LogConsole-toolbar select, .jp-LogConsolePanel select").first
        if select.count():
            try:
                select.select_option("debug")
            except Exception:  # noqa: BLE001 - older layouts have no level selector
                pass
        self.page.wait_for_timeout(300)
        entries = self.page.evaluate("""() => Array.from(document.querySelectorAll(
            '.jp-LogConsole .jp-OutputArea-child')).map(e => e.textContent.slice(0, 4000))""")
        return entries

    def raw_myst_text(self) -> list[str]:
        """What a reader should never see in the rendered markdown cells, each with some context: raw MyST markup
        (a role or directive name in braces, a directive's code fence), an "Unknown Directive" box, an inline
        expression left as its code (``glued(...)``: not evaluated) or evaluated to an error, a raw glue key
        (``name:.2f``), and a bare label (``fig-ch1-frames``, ``eq-jacobian``, ``ex-traj-corner``, ``sec-...``)
        where the book prints "Fig. 1.2", "(4.17)" or "Exercise 3.4"."""
        return self.page.evaluate("""() => {
          const out = [];
          const seen = (text, m, what) => out.push(what + ': ' + text.slice(Math.max(0, m.index - 60), m.index + 60));
          for (const cell of document.querySelectorAll('.jp-MarkdownCell .jp-RenderedMarkdown, .jp-MarkdownCell .jp-RenderedMySTMarkdown')) {
            const text = cell.innerText;
            const checks = [
              [/\\{(eq|doc|numref|glue:text|glue:md|glue:figure|glue|eval|dropdown|math|ref|cite|cite:p|cite:t|figure|admonition|note|exercise|solution)\\}|```/, 'raw markup'],
              [/Unknown Directive/, 'unknown directive'],
              [/glued\\(/, 'unevaluated number'],
              [/\\b(NameError|KeyError|TypeError|SyntaxError|AttributeError|ValueError):/, 'error in the text'],
              [/\\b[a-z][a-z0-9_]*:\\.[0-9]*[fge%]\\b/, 'raw glue key'],
              [/(^|[\\s(\\[])(fig|eq|ex|sec|tab)-[a-z0-9]+(-[a-z0-9]+)+\\b/, 'bare label'],
            ];
            for (const [re, what] of checks) { const m = text.match(re); if (m) seen(text, m, what); }
            for (const e of cell.querySelectorAll('.myst-RenderedExpressionError, [data-mime-type="application/vnd.jupyter.stderr"]'))
              out.push('error in an inline expression: ' + e.textContent.slice(0, 120));
          }
          return out;
        }""")

    def render_markdown_cells(self):
        """Ensure every markdown cell is rendered (they are after Run All)."""
        return self.page.locator(".jp-MarkdownCell").count()

    # -- panels -------------------------------------------------------------------------------------------
    def panels(self):
        return self.page.locator(".scara-panel")

    def plots_outside_panels(self) -> int:
        return self.page.evaluate("""() => Array.from(document.querySelectorAll('.jp-OutputArea .js-plotly-plot'))
          .filter(gd => !gd.closest('.scara-panel')).length""")

    def figures(self, panel) -> list[dict]:
        return panel.evaluate(FIGURES)

    def wait_drawn(self, panel, timeout: float = 120.0) -> None:
        """Wait until every figure of ``panel`` has been drawn with its data (a FigureWidget draws when its
        view is attached, which on a loaded machine may come after Run All has finished)."""
        panel.evaluate("""(panel, timeout) => new Promise((resolve, reject) => {
          const t0 = performance.now();
          const tick = () => {
            const plots = Array.from(panel.querySelectorAll('.js-plotly-plot'));
            if (plots.length && plots.every(gd => (gd.data || []).length > 0 && gd._fullLayout)) return resolve(true);
            if (performance.now() - t0 > timeout) return reject(new Error('the figures of the panel were not drawn within '
                                                                         + timeout / 1000 + ' s'));
            setTimeout(tick, 50);
          };
          tick();
        })""", timeout * 1000)

    def instrument(self) -> int:
        return self.page.evaluate(INSTRUMENT)

    def mark(self) -> tuple[int, int]:
        return self.page.evaluate("() => [window.__scara.after.length, window.__scara.keys.length]")

    @staticmethod
    def state(panel) -> dict:
        """The panel's hidden record of its last update: ``values`` (what the figures were computed for),
        ``seq`` (the update's number), ``compute_ms``, ``draw_ms``, ``send_ms``."""
        text = panel.evaluate("(p) => { const e = p.querySelector('.scara-panel-values'); return e ? e.textContent : ''; }")
        return json.loads(text) if text else {}

    def values(self, panel) -> dict:
        return self.state(panel).get("values", {})

    @staticmethod
    def message(panel) -> str:
        return panel.evaluate("(p) => { const e = p.querySelector('.scara-panel-message'); return e ? e.innerText : ''; }")

    def timing_since(self, mark, panel, before: dict, settle_ms: float = 350.0, timeout: float = 120.0) -> dict:
        """Wait until the panel has taken the change made after ``mark`` (its update number moved past
        ``before``'s) and its figures have stopped redrawing for ``settle_ms``; return the time from the first
        key press or change after ``mark`` to the last redraw (ms, None if nothing was redrawn) and the
        redraw count."""
        # one awaited promise in the page, not a poll from here: every call from the test into the page
        # costs the browser's main thread and a core of this 2-core machine, and would slow what it measures
        data = panel.evaluate("""(panel, [a0, k0, seq0, settle, timeout]) => new Promise((resolve) => {
          const t0 = performance.now();
          const seq = () => { const e = panel.querySelector('.scara-panel-values');
                              try { return e ? JSON.parse(e.textContent).seq : null; } catch (err) { return null; } };
          let taken = false, lastN = -1, lastChange = 0;
          const done = (ok) => resolve({ok, after: window.__scara.after.slice(a0), keys: window.__scara.keys.slice(k0)});
          const tick = () => {
            const now = performance.now();
            if (now - t0 > timeout) return done(taken);
            if (!taken) { taken = seq() !== seq0; lastChange = now; }
            if (taken) {
              const n = window.__scara.after.length;
              if (n !== lastN) { lastN = n; lastChange = now; }
              else if (now - lastChange >= settle) return done(true);
            }
            setTimeout(tick, 25);
          };
          setTimeout(tick, 25);
        })""", [mark[0], mark[1], before.get("seq"), settle_ms, timeout * 1000])
        if not data["ok"]:
            raise TimeoutError(f"the panel did not take the change within {timeout:.0f} s (values {before})")
        if not data["after"] or not data["keys"]:
            return {"latency_ms": None, "redraws": len(data["after"])}
        t_key = data["keys"][0]
        return {"latency_ms": max(a["t"] for a in data["after"]) - t_key, "redraws": len(data["after"])}
