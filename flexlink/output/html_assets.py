"""The HTML report's own style sheet and script (inlined into the page by ``html_report.py``).

SCRIPT draws the plotly figures listed in the page's JSON data, and runs one mode-shape player
per scene: a mode selector, play/pause and an amplitude slider. A player redraws only while it
is on screen (IntersectionObserver), so a page with many scenes does not keep every plot busy.
``window.flexlinkReport`` exposes the players' state for the browser test.
"""

STYLE = """
*{box-sizing:border-box}
body{margin:0;font-family:"DejaVu Sans",Arial,sans-serif;color:#1b1b1b;background:#f3f4f6;
  line-height:1.45;font-size:15px}
header{background:#23395d;color:#fff;padding:14px 20px}
header h1{margin:0 0 4px;font-size:1.5em}
header p{margin:0 0 8px;opacity:.85}
nav ul{margin:0;padding:0;list-style:none}
nav li{margin:2px 0}
nav a{color:#fff;font-weight:bold}
.shares{white-space:normal;cursor:help}
.share{white-space:nowrap;border-bottom:1px dotted #888}
main{max-width:1100px;margin:0 auto;padding:10px}
.scene{background:#fff;border-radius:6px;padding:8px 18px 14px;margin:14px 0;
  box-shadow:0 1px 3px rgba(0,0,0,.12)}
.scene h2{margin:.4em 0 0}
.file{color:#666;margin:0 0 6px;font-family:monospace;overflow-wrap:anywhere}
.part{border-top:1px solid #e5e5e5;padding-top:4px}
h3{margin:.6em 0 .3em}
.scroll{overflow-x:auto;max-width:100%}
table{border-collapse:collapse;margin:4px 0;font-size:.93em}
th,td{border-bottom:1px solid #ddd;padding:3px 9px;text-align:left;vertical-align:top}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
th{background:#f0f2f5;white-space:nowrap}
.note{color:#555;font-size:.88em}
.warnings{background:#fff6e0;border-left:4px solid #e0a800;padding:4px 12px;font-size:.9em}
.warnings ul{margin:4px 0;padding-left:18px}
.plot{width:100%;min-height:300px}
.controls{display:flex;flex-wrap:wrap;gap:10px 18px;align-items:center;margin:6px 0}
.controls select,.controls button{font-size:1em;padding:4px 8px}
.controls button{min-width:5.5em}
.amp input{vertical-align:middle;width:140px}
ul.files{padding-left:18px;overflow-wrap:anywhere}
code{font-size:.92em}
@media (max-width:600px){body{font-size:14px}main{padding:4px}.scene{padding:6px 10px}
  th,td{padding:3px 4px}table{font-size:.88em}}
"""

SCRIPT = r"""
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("flexlink-data").textContent);
  var config = {responsive: true, displaylogo: false, scrollZoom: false};
  var PERIOD = 1.6;  // seconds per drawn oscillation
  data.figures.forEach(function (f) { Plotly.newPlot(f.id, f.data, f.layout, config); });

  function bounds(values, pad) {
    var lo = Infinity, hi = -Infinity;
    values.forEach(function (v) { if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); } });
    return [lo - pad, hi + pad];
  }

  function Player(root, shapes) {
    var self = this;
    var plot = root.querySelector(".mode-plot");
    var select = root.querySelector("select");
    var button = root.querySelector("button.play");
    var slider = root.querySelector("input[type=range]");
    var shown = root.querySelector(".amp-value");
    var reach = shapes.size_mm * Number(slider.max) / 100;  // room for the largest amplitude
    self.mode = 0; self.playing = true; self.visible = false; self.phase = 0; self.frames = 0;
    var last = null;
    var layout = {margin: {l: 55, r: 15, t: 10, b: 45}, height: 380, showlegend: false,
                  font: {family: "DejaVu Sans, Arial, sans-serif", size: 12},
                  plot_bgcolor: "#fbfbfb",
                  xaxis: {title: {text: "x [mm]"}, range: bounds(shapes.x, reach), zeroline: false},
                  yaxis: {title: {text: "y [mm]"}, range: bounds(shapes.y, reach), zeroline: false,
                          scaleanchor: "x", scaleratio: 1}};
    var traces = [
      {type: "scatter", mode: "lines", x: shapes.x, y: shapes.y, hoverinfo: "skip",
       line: {color: "#b8b8b8", width: 2, dash: "dot"}},
      {type: "scatter", mode: "lines", x: shapes.x, y: shapes.y, hoverinfo: "skip",
       line: {color: "#1f5fbf", width: 4}}];
    Plotly.newPlot(plot, traces, layout, config);

    self.draw = function () {
      var m = shapes.modes[self.mode];
      var a = shapes.size_mm * Number(slider.value) / 100 * Math.sin(self.phase);
      var x = shapes.x.map(function (v, i) { return v === null ? null : v + a * m.dx[i]; });
      var y = shapes.y.map(function (v, i) { return v === null ? null : v + a * m.dy[i]; });
      Plotly.restyle(plot, {x: [x], y: [y]}, [1]);
      self.frames += 1;
    };
    function tick(now) {
      if (self.playing && self.visible) {
        if (last !== null) { self.phase += (now - last) / 1000 * 2 * Math.PI / PERIOD; }
        last = now;
        self.draw();
      } else { last = null; }
      window.requestAnimationFrame(tick);
    }
    select.addEventListener("change", function () { self.mode = Number(select.value); self.draw(); });
    slider.addEventListener("input", function () { shown.textContent = slider.value + " %"; self.draw(); });
    button.addEventListener("click", function () {
      self.playing = !self.playing;
      button.textContent = self.playing ? "Pause" : "Play";
      button.setAttribute("aria-label", self.playing ? "pause" : "play");
    });
    if ("IntersectionObserver" in window) {
      new IntersectionObserver(function (entries) {
        entries.forEach(function (e) { self.visible = e.isIntersecting; });
      }).observe(plot);
    } else { self.visible = true; }
    self.phase = Math.PI / 2;  // a still picture shows the largest displacement
    self.draw();
    window.requestAnimationFrame(tick);
  }

  var players = {};
  Object.keys(data.animations).forEach(function (id) {
    players[id] = new Player(document.getElementById("player-" + id), data.animations[id]);
  });
  window.flexlinkReport = {players: players};
})();
"""
