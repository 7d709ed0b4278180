"""The shared drawing: framing on the interaction, the still PNG, the GIF and the HTML."""

from __future__ import annotations

import io
import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from PIL import Image
from shapely.geometry import LineString, Polygon

from arise.maps.registry import MapRegistry
from arise.render.framing import MAX_SIZE_M, focus, frame
from arise.render.gif import encode_gif
from arise.render.html import replay_html, scene_data
from arise.render.model import RegionKind, Role, Window
from arise.render.outline import load_network, outline_of
from arise.render.raster import frames, still_png
from arise.validate.picture import scene_of, track_of
from tests.present.traces import STEPS, TIMESTEP, agents, simulation, straight_map


@pytest.fixture(scope="module")
def scene():  # the hand-made trace on the straight map we ship
    facts = simulation()
    network = load_network(straight_map().path)
    return scene_of(facts.agents, facts.collisions, facts.timestep, "hand-made", network)


def test_the_interaction_is_the_egos_first_contact(scene) -> None:
    assert scene.focus_step == 48
    assert [(c.first, c.second, c.step) for c in scene.contacts] == [("ego", "Pedestrian1", 48)]
    assert scene.window.contains(scene.contacts[0].where)


def test_the_frame_holds_the_approach_and_the_egos_start(scene) -> None:
    ego = next(t for t in scene.tracks if t.role is Role.EGO)
    assert scene.window.contains((ego.poses[0].x, ego.poses[0].y))
    for step in range(48 - 40, 48 + 20):
        pose = ego.poses[step]
        assert scene.window.contains((pose.x, pose.y))
    assert scene.window.width / scene.window.height == pytest.approx(4 / 3)
    # framed on the interaction: far less than the 300 m road
    assert scene.window.width < 120


def test_without_contact_the_closest_approach_is_the_focus() -> None:
    tracks = [track_of(a) for a in agents() if a.name != "Pedestrian1"]
    step, partner = focus(tracks, [])
    assert partner == "Cone1" or partner == "Car1"
    assert step is not None


def test_a_long_approach_leaves_the_start_out_but_keeps_the_interaction() -> None:
    tracks = [track_of(a) for a in agents()]
    ego = tracks[0]
    far = [p.__class__(p.x - 400, p.y, p.heading, p.speed) for p in ego.poses[:10]]
    stretched = ego.__class__(
        ego.name, ego.kind, ego.role, ego.width, ego.length, far + ego.poses[10:]
    )
    window = frame([stretched, *tracks[1:]], TIMESTEP, 48, "Pedestrian1")
    assert max(window.width, window.height) <= MAX_SIZE_M * 4 / 3 + 1e-6
    assert window.contains((stretched.poses[48].x, stretched.poses[48].y))


def test_the_outline_has_lanes_sidewalks_and_painted_lines(scene) -> None:
    kinds = {a.kind for a in scene.outline.areas}
    assert {RegionKind.DRIVABLE, RegionKind.SIDEWALK} <= kinds
    assert scene.outline.lines
    for area in scene.outline.areas:  # cut to (a little more than) the frame
        xs = [p[0] for p in area.exterior]
        assert min(xs) >= scene.window.xmin - 6 and max(xs) <= scene.window.xmax + 6


def test_still_png_is_a_picture(scene) -> None:
    data = still_png(scene, dpi=60)
    image = Image.open(io.BytesIO(data))
    assert image.format == "PNG" and image.width > image.height > 200


def test_gif_has_a_frame_per_stride_and_plays_in_real_time(scene) -> None:
    data = encode_gif(frames(scene, 2, dpi=40), 2 * TIMESTEP)
    image = Image.open(io.BytesIO(data))
    assert image.format == "GIF" and image.n_frames == STEPS // 2 + 1
    image.seek(1)
    assert image.info["duration"] == 200
    image.seek(0)
    first = image.convert("RGB").tobytes()
    image.seek(image.n_frames - 1)
    assert image.convert("RGB").tobytes() != first  # things moved


def test_html_is_one_self_contained_file(scene) -> None:
    page = replay_html(scene)
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//""", page)
    assert "<link" not in page and "@import" not in page and "fetch(" not in page
    assert re.search(r"<script[^>]*\ssrc=", page) is None
    match = re.search(
        r'<script type="application/json" id="replay-data">(.*?)</script>', page, re.S
    )
    assert match is not None
    data = json.loads(match.group(1))
    assert [t["name"] for t in data["tracks"]] == [t.name for t in scene.tracks]
    assert len(data["tracks"][0]["x"]) == STEPS + 1
    assert data["contacts"][0]["step"] == 48
    for control in ('id="play"', 'id="scrub"', 'id="clock"', 'id="legend"'):
        assert control in page


def test_titles_cannot_break_out_of_the_page() -> None:
    facts = simulation()
    scene = scene_of(facts.agents, [], facts.timestep, "</script><script>alert(1)</script>")
    page = replay_html(scene)
    assert "<script>alert(1)" not in page
    assert scene_data(scene)["title"].startswith("</script>")


NODE = shutil.which("node")

# A minimal stand-in for the browser: enough DOM and canvas for the page's script to
# run, and a clock that advances 50 ms per animation frame.
_FAKE_BROWSER = """
const fs = require('fs');
const page = fs.readFileSync(process.argv[2], 'utf8');
const data = page.match(/<script type="application\\/json" id="replay-data">([\\s\\S]*?)<\\/script>/)[1];
const code = page.match(/<script>([\\s\\S]*?)<\\/script>/)[1];
function ctx() { return new Proxy({}, { get: (t, k) => k in t ? t[k] :
  (k === 'measureText' ? () => ({width: 10}) : () => {}), set: (t, k, v) => { t[k] = v; return true; } }); }
const elements = {};
function element(id) {
  if (!elements[id]) {
    elements[id] = { id, style: {}, value: '0', textContent: '', clientWidth: 800, children: [],
      listeners: {}, addEventListener(kind, f) { this.listeners[kind] = f; },
      appendChild(c) { this.children.push(c); }, getContext: () => ctx(), width: 0, height: 0 };
  }
  return elements[id];
}
elements['replay-data'] = { textContent: data };
element('speed').value = '1';
global.document = { getElementById: element, createElement: () => element('x' + Math.random()),
  createTextNode: (t) => ({ t }), addEventListener() {}, body: {} };
global.window = { addEventListener() {} };
global.devicePixelRatio = 1;
let now = 0; const queue = [];
global.requestAnimationFrame = (f) => queue.push(f);
eval(code);
const replay = window.arise_replay;
element('play').listeners.click();
for (let i = 0; i < 400 && queue.length; i++) { now += 50; queue.shift()(now); }
console.log(JSON.stringify({ step: replay.step(), steps: replay.data.steps,
  clock: element('clock').textContent, legend: element('legend').children.length,
  button: element('play').textContent }));
"""


@pytest.mark.skipif(NODE is None, reason="node is not installed (Debian: nodejs)")
def test_the_page_plays_to_the_end_and_scrubs(scene, tmp_path: Path) -> None:
    page = tmp_path / "replay.html"
    page.write_text(replay_html(scene), encoding="utf-8")
    script = tmp_path / "browser.js"
    script.write_text(_FAKE_BROWSER, encoding="utf-8")
    done = subprocess.run(
        [NODE, str(script), str(page)], capture_output=True, text=True, timeout=60, check=True
    )
    state = json.loads(done.stdout.strip().splitlines()[-1])
    assert state["step"] == state["steps"] == STEPS
    assert state["clock"] == f"t = {STEPS * TIMESTEP:.1f} s / {STEPS * TIMESTEP:.1f} s"
    assert state["button"] == "Play"  # it stopped at the end
    assert state["legend"] == len(scene.tracks) + 1  # every agent, and the ego's start and path


def test_a_title_that_names_a_placeholder_stays_a_title() -> None:
    facts = simulation()
    page = replay_html(scene_of(facts.agents, [], facts.timestep, "__DATA__"))
    assert "<title>__DATA__</title>" in page


def test_junctions_are_areas_and_carry_no_painted_lines() -> None:
    network = load_network(MapRegistry(None).resolve("arise_intersection4").path)
    outline = outline_of(network, Window(-40, -40, 40, 40))
    junctions = [a for a in outline.areas if a.kind is RegionKind.JUNCTION]
    assert junctions
    junction = Polygon(junctions[0].exterior).buffer(-0.5)
    for line in outline.lines:
        assert not LineString(line.points).within(junction)
        assert LineString(line.points).intersection(junction).length < 0.5


def test_a_scene_without_a_map_has_an_empty_outline_but_draws() -> None:
    facts = simulation()
    scene = scene_of(facts.agents, facts.collisions, facts.timestep, "no map")
    assert scene.outline.areas == [] and scene.outline.lines == []
    assert Image.open(io.BytesIO(still_png(scene, dpi=40))).format == "PNG"
