"""Run translated kernels under Node 20 and read back exactly what they computed: the test harness of the page's
engine. Numbers travel as the bytes of float64 arrays (base64), so nothing is rounded on the way."""
from __future__ import annotations

import base64
import json
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

NODE = shutil.which("node")

_DRIVER = r"""
const fs = require('fs');
const {SCARA_KERNELS, SCARA_RUNTIME} = require(process.argv[2]);
const calls = JSON.parse(fs.readFileSync(process.argv[3], 'utf8'));
function dec(v) {
  if (v && v.b64 !== undefined) {
    const buf = Buffer.from(v.b64, 'base64');
    const d = new Float64Array(buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.byteLength));
    if (v.shape.length === 2) d.n1 = v.shape[1];
    return d;
  }
  if (v && v.num !== undefined) return Number(v.num);
  if (Array.isArray(v)) return v.map(dec);
  return v;
}
function enc(v) {
  if (v instanceof Float64Array) return {b64: Buffer.from(v.slice().buffer).toString('base64'),
                                         shape: v.n1 !== undefined ? [v.length / v.n1, v.n1] : [v.length]};
  if (typeof v === 'number') return {num: String(v)};
  if (typeof v === 'boolean') return {num: v ? '1' : '0'};
  if (Array.isArray(v)) return v.map(enc);
  if (v && typeof v === 'object' && typeof v.length === 'number') return Array.from(v).map(enc);  // a namedtuple
  if (v === undefined) return null;
  return v;
}
const results = [];
for (const [name, args, repeat] of calls) {
  const fn = SCARA_KERNELS[name];
  if (!fn) throw new Error('no kernel ' + name);
  const a = args.map(dec);
  let ret, best = Infinity;
  for (let r = 0; r < (repeat || 1); r++) {
    const t0 = process.hrtime.bigint();
    ret = fn(...a);
    best = Math.min(best, Number(process.hrtime.bigint() - t0) / 1e6);
  }
  results.push({ret: enc(ret), args: a.map(enc), ms: best});
}
process.stdout.write(JSON.stringify(results));
"""


def _enc(v):
    if isinstance(v, np.ndarray):
        a = np.ascontiguousarray(v, dtype=np.float64)
        return {"b64": base64.b64encode(a.tobytes()).decode(), "shape": list(a.shape)}
    if isinstance(v, (bool, np.bool_)):
        return {"num": "1" if v else "0"}
    if isinstance(v, (int, float, np.integer, np.floating)):
        return {"num": repr(float(v)) if isinstance(v, (float, np.floating)) else str(int(v))}
    if isinstance(v, (list, tuple)):
        return [_enc(x) for x in v]
    raise TypeError(f"cannot send {type(v).__name__} to node")


def _dec(v):
    if isinstance(v, dict) and "b64" in v:
        return np.frombuffer(base64.b64decode(v["b64"]), dtype=np.float64).reshape(v["shape"]).copy()
    if isinstance(v, dict) and "num" in v:
        return float(v["num"])
    if isinstance(v, list):
        return [_dec(x) for x in v]
    return v


def run_js(script: str, calls):
    """Run ``calls`` ([(kernel name, args, repeat)]) in ``script`` under Node; for each, ``(returned value, the
    arguments after the call, best time in ms)``."""
    if NODE is None:
        pytest.skip("node is not installed")
    with tempfile.TemporaryDirectory() as d:
        Path(d, "engine.js").write_text(script)
        Path(d, "driver.js").write_text(_DRIVER)
        Path(d, "calls.json").write_text(json.dumps([[n, _enc(list(a)), int(r)] for n, a, r in calls]))
        res = subprocess.run([NODE, str(Path(d, "driver.js")), str(Path(d, "engine.js")), str(Path(d, "calls.json"))],
                             capture_output=True, text=True, timeout=600)
        if res.returncode != 0:
            raise RuntimeError(f"node failed:\n{res.stderr[-3000:]}")
        return [(_dec(r["ret"]), _dec(r["args"]), r["ms"]) for r in json.loads(res.stdout)]
