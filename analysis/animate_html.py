"""A self-contained HTML page that plays PNG frames (analysis/animate.py -o OUT.html).

The frames are embedded as base64 data URIs and the player is a few lines of inline
JavaScript (play/pause, step, a slider, the speed): the page plays offline and references
nothing outside itself (no script, style sheet or font from the network).
"""

import html

PAGE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{title}</title>
<style>
body {{ font-family: sans-serif; margin: 1em; }}
#controls {{ margin-top: 0.5em; }}
#controls button {{ min-width: 3em; }}
#slider {{ width: 60%; vertical-align: middle; }}
</style>
</head>
<body>
<img id="frame" alt="frame of the animation" src="">
<div id="controls">
<button id="first" title="first frame">|&lt;</button>
<button id="prev" title="previous frame">&lt;</button>
<button id="play" title="play or pause">play</button>
<button id="next" title="next frame">&gt;</button>
<button id="last" title="last frame">&gt;|</button>
<input id="slider" type="range" min="0" max="0" value="0">
<span id="label"></span>
<label>speed <select id="speed"><option value="0.25">0.25x</option>
<option value="0.5">0.5x</option><option value="1" selected>1x</option>
<option value="2">2x</option></select></label>
<label><input id="loop" type="checkbox" checked> loop</label>
</div>
<script>
var frames = [
{frames}
];
var fps = {fps!r}, t0 = {t0!r};
var img = document.getElementById("frame"), slider = document.getElementById("slider");
var label = document.getElementById("label"), playButton = document.getElementById("play");
var current = 0, timer = null;
slider.max = frames.length - 1;
function show(i) {{
  current = Math.max(0, Math.min(frames.length - 1, i));
  img.src = "data:image/png;base64," + frames[current];
  slider.value = current;
  label.textContent = "frame " + (current + 1) + " / " + frames.length + ", t = " +
                      (t0 + current / fps).toFixed(3) + " s";
}}
function stop() {{
  if (timer) {{ clearInterval(timer); timer = null; }}
  playButton.textContent = "play";
}}
function play() {{
  stop();
  var speed = parseFloat(document.getElementById("speed").value);
  playButton.textContent = "pause";
  timer = setInterval(function () {{
    if (current + 1 < frames.length) {{ show(current + 1); }}
    else if (document.getElementById("loop").checked) {{ show(0); }}
    else {{ stop(); }}
  }}, 1000 / (fps * speed));
}}
playButton.onclick = function () {{ if (timer) {{ stop(); }} else {{ play(); }} }};
document.getElementById("first").onclick = function () {{ stop(); show(0); }};
document.getElementById("last").onclick = function () {{ stop(); show(frames.length - 1); }};
document.getElementById("prev").onclick = function () {{ stop(); show(current - 1); }};
document.getElementById("next").onclick = function () {{ stop(); show(current + 1); }};
document.getElementById("speed").onchange = function () {{ if (timer) {{ play(); }} }};
slider.oninput = function () {{ stop(); show(parseInt(slider.value, 10)); }};
show(0);
</script>
</body>
</html>
"""


def html_page(frames_base64, fps, title, t0=0.0):
    """The page's text: `frames_base64` a list of base64-encoded PNG images, played at `fps`
    frames per second; `t0` [s] the time of the first frame."""
    body = ",\n".join(f'"{f}"' for f in frames_base64)
    return PAGE.format(title=html.escape(title), frames=body, fps=float(fps), t0=float(t0))
