"""An offline animation of the rattleback: a self-contained HTML fragment (a canvas, a
Play/Pause button, a slider; no external script, no server) whose frames come from a
simulation (:func:`whittaker_teach.rolling.simulate.simulate_rattleback`), decimated and
rounded so that the stored output is small and the same at every run.

Three panels: the body seen from above (its rim, a dot at the +x end, a 2 cm scale
bar), seen from the side (the keel, the bottom's section y = 0, and the rim projected
on the vertical space x-z plane, the table as a line), both at 1 px = 1 mm of the
canvas, and the spin rate (gamma . omega) against time with a cursor.  The container carries
``data-frame`` (the frame shown), which the browser test reads.

>>> html = rattleback_animation([0.0, 0.1], [1.0, 0.9], [[1, 0, 0, 0, 1, 0, 0, 0, 1]] * 2,
...                             [[0, 0, 0.01]] * 2, shape=dict(a=0.1, b=0.02, h=0.01,
...                             rho_1=0.5, rho_2=0.02, top=0.02))
>>> "<script" in html and "http" not in html
True
"""

from __future__ import annotations

import json

__all__ = ["rattleback_animation"]

_TEMPLATE = """<div class="wt-anim" id="@ID@" data-frame="0" style="max-width:760px">
<canvas width="760" height="300"
 style="width:100%;height:auto;border:1px solid #ccc;background:#fff"
 aria-label="@LABEL@"></canvas>
<div style="display:flex;gap:0.6em;align-items:center;margin-top:0.3em">
<button type="button" class="wt-play">Play</button>
<input type="range" class="wt-slider" min="0" max="0" value="0" style="flex:1" aria-label="frame">
<span class="wt-time" style="font-family:monospace">t = 0.00</span>
</div>
<script>
(function () {
  var D = @DATA@;
  var root = document.getElementById("@ID@");
  var cv = root.querySelector("canvas"), cx = cv.getContext("2d");
  var btn = root.querySelector(".wt-play"), sl = root.querySelector(".wt-slider");
  var lab = root.querySelector(".wt-time");
  var n = D.t.length, k = 0, timer = null;
  sl.max = String(n - 1);
  var S = D.shape, rim = [], keel = [], i, s;
  for (i = 0; i <= 36; i++) { s = 2 * Math.PI * i / 36;
    rim.push([S.a * Math.cos(s), S.b * Math.sin(s), S.top - S.h]); }
  for (i = 0; i <= 24; i++) { s = -S.a + 2 * S.a * i / 24;
    keel.push([s, 0, s * s / (2 * S.rho_1) - S.h]); }
  function world(f, p) { var Q = D.Q[f], G = D.G[f];
    return [G[0] + Q[0]*p[0] + Q[1]*p[1] + Q[2]*p[2],
            G[1] + Q[3]*p[0] + Q[4]*p[1] + Q[5]*p[2],
            G[2] + Q[6]*p[0] + Q[7]*p[1] + Q[8]*p[2]]; }
  function path(pts, f, ox, oy, sc, ix, iy, close) {
    cx.beginPath();
    for (var j = 0; j < pts.length; j++) { var w = world(f, pts[j]);
      var X = ox + sc * w[ix], Y = oy - sc * w[iy];
      if (j === 0) cx.moveTo(X, Y); else cx.lineTo(X, Y); }
    if (close) cx.closePath(); }
  function draw(f) {
    cx.clearRect(0, 0, cv.width, cv.height);
    cx.font = "14px sans-serif"; cx.fillStyle = "#222";
    var sc = 1000;
    // top view
    cx.fillText("from above", 20, 20);
    cx.strokeStyle = "#bbb"; cx.beginPath(); cx.moveTo(20, 150); cx.lineTo(260, 150);
    cx.moveTo(140, 30); cx.lineTo(140, 270); cx.stroke();
    path(rim, f, 140, 150, sc, 0, 1, true); cx.fillStyle = "rgba(68,84,106,0.35)"; cx.fill();
    cx.strokeStyle = "#44546a"; cx.lineWidth = 2; cx.stroke();
    var tip = world(f, [S.a, 0, S.top - S.h]);
    cx.fillStyle = "#c0392b"; cx.beginPath();
    cx.arc(140 + sc * tip[0], 150 - sc * tip[1], 5, 0, 2 * Math.PI); cx.fill();
    cx.strokeStyle = "#222"; cx.lineWidth = 2; cx.beginPath();     // scale bar: 2 cm
    cx.moveTo(30, 262); cx.lineTo(30 + 0.02 * sc, 262); cx.stroke(); cx.lineWidth = 1;
    cx.fillStyle = "#222"; cx.fillText("2 cm", 56, 267);
    // side view
    cx.fillStyle = "#222"; cx.fillText("from the side (x-z)", 290, 20);
    cx.strokeStyle = "#555"; cx.lineWidth = 2; cx.beginPath(); cx.moveTo(280, 200);
    cx.lineTo(500, 200); cx.stroke();
    path(keel, f, 390, 200, sc, 0, 2, false); cx.strokeStyle = "#44546a"; cx.lineWidth = 3;
    cx.stroke();
    path(rim, f, 390, 200, sc, 0, 2, true); cx.lineWidth = 1.5; cx.stroke();
    cx.lineWidth = 1;
    // spin rate
    var x0 = 530, x1 = 745, y0 = 40, y1 = 260, T = D.t[n - 1], W = D.wmax;
    cx.fillStyle = "#222"; cx.fillText("spin rate (rad/s)", 540, 20);
    cx.strokeStyle = "#bbb"; cx.beginPath(); cx.moveTo(x0, (y0 + y1) / 2);
    cx.lineTo(x1, (y0 + y1) / 2); cx.moveTo(x0, y0); cx.lineTo(x0, y1); cx.stroke();
    cx.fillText("+" + W, x0 + 4, y0 + 12); cx.fillText("-" + W, x0 + 4, y1);
    cx.fillText("t = " + T.toFixed(0) + " s", x1 - 52, (y0 + y1) / 2 + 16);
    cx.strokeStyle = "#1f6fb2"; cx.lineWidth = 1.5; cx.beginPath();
    for (var j = 0; j < n; j++) { var X = x0 + (x1 - x0) * D.t[j] / T;
      var Y = (y0 + y1) / 2 - (y1 - y0) / 2 * D.spin[j] / W;
      if (j === 0) cx.moveTo(X, Y); else cx.lineTo(X, Y); }
    cx.stroke(); cx.lineWidth = 1;
    var Xc = x0 + (x1 - x0) * D.t[f] / T;
    cx.strokeStyle = "#c0392b"; cx.beginPath(); cx.moveTo(Xc, y0); cx.lineTo(Xc, y1); cx.stroke();
    lab.textContent = "t = " + D.t[f].toFixed(2);
    root.setAttribute("data-frame", String(f));
  }
  function show(f) { k = f; sl.value = String(f); draw(f); }
  function tick() { show((k + 1) % n); }
  btn.addEventListener("click", function () {
    if (timer === null) { timer = setInterval(tick, @INTERVAL@); btn.textContent = "Pause"; }
    else { clearInterval(timer); timer = null; btn.textContent = "Play"; } });
  sl.addEventListener("input", function () { show(parseInt(sl.value, 10)); });
  show(0);
})();
</script>
</div>"""


def _r(x, d):
    v = round(float(x), d)
    return 0.0 if v == 0 else v            # no -0.0


def rattleback_animation(t, spin, Q, G, shape, wmax=None, interval=40,
                         element_id="wt-rattleback-animation",
                         label="Animation of the rattleback's spin reversal"):
    """The HTML fragment (a str) animating frames ``t`` (times), ``spin`` (spin rates),
    ``Q`` (rotation matrices, 9 numbers each, row by row, body -> space) and ``G`` (the
    centre, 3 numbers).  ``shape``: dict with a, b (the rim's semi-axes), top (the rim's
    height above the bottom point), h, rho_1 (as in the model).  Numbers are rounded
    (t 3 digits, Q 4, G 5, spin 3) so the output is deterministic and small."""
    if not (len(t) == len(spin) == len(Q) == len(G)) or len(t) < 2:
        raise ValueError("rattleback_animation: t, spin, Q and G need the same length >= 2")
    need = {"a", "b", "top", "h", "rho_1"}
    if not need <= set(shape):
        raise ValueError(f"rattleback_animation: shape needs {sorted(need)}")
    data = {
        "t": [_r(x, 3) for x in t],
        "spin": [_r(x, 3) for x in spin],
        "Q": [[_r(x, 4) for x in list(q)] for q in Q],
        "G": [[_r(x, 5) for x in list(g)] for g in G],
        "shape": {k: float(v) for k, v in sorted(shape.items())},
        "wmax": float(wmax if wmax is not None else max(abs(float(s)) for s in spin)),
    }
    text = json.dumps(data, separators=(",", ":"))
    return (_TEMPLATE.replace("@DATA@", text).replace("@ID@", element_id)
            .replace("@INTERVAL@", str(int(interval))).replace("@LABEL@", label))
