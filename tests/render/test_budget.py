"""What a picture can show: hundreds of agents and thousands of steps drawn within a
budget, with notes of what was left out; real runs drawn exactly as they are."""

from __future__ import annotations

import io
import json
import math

import pytest
from PIL import Image

from arise.render.budget import MAX_DRAWN_AGENTS, MAX_DRAWN_POSES, bounded
from arise.render.gif import encode_gif
from arise.render.html import replay_html, scene_data
from arise.render.model import Contact, Pose, Role, Scene, Track, Window
from arise.render.raster import frames, notes, still_png
from arise.validate.picture import scene_of
from tests.present.traces import simulation

TIMESTEP = 0.1


def _track(name: str, steps: int, y: float, role: Role = Role.VEHICLE) -> Track:
    poses = [Pose(i * 0.05, y, -math.pi / 2, 0.5) for i in range(steps + 1)]
    return Track(name, "Car", role, 2.0, 4.5, poses)


def _crowd(agents: int, steps: int) -> Scene:
    """The ego along y = 0, others in rows farther and farther away; the ego touches the
    farthest one, so a choice by distance alone would drop it."""
    tracks = [_track("ego", steps, 0.0, Role.EGO)]
    tracks += [_track(f"Car{i}", steps, 3.0 * i) for i in range(1, agents)]
    far = tracks[-1].name
    contacts = [Contact("ego", far, steps // 2, (0.0, 0.0)), Contact("Car1", "Car2", 5, (0, 3))]
    return Scene(
        title="crowd",
        timestep=TIMESTEP,
        steps=steps,
        tracks=tracks,
        outline=scene_of([], [], TIMESTEP, "").outline,
        window=Window(-20, -20, 40, 25),
        contacts=contacts,
        focus_step=steps // 2,
    )


def test_a_real_run_is_drawn_as_it_is() -> None:
    facts = simulation()
    scene = scene_of(facts.agents, facts.collisions, facts.timestep, "hand-made")
    assert bounded(scene) is scene
    assert notes(scene)[0] == f"{scene.steps} steps of {TIMESTEP:g} s"


def test_hundreds_of_agents_keep_the_ego_those_in_contact_and_the_nearest() -> None:
    scene = _crowd(256, 100)
    drawn = bounded(scene)
    names = [t.name for t in drawn.tracks]
    assert len(names) == MAX_DRAWN_AGENTS
    assert names[0] == "ego" and "Car255" in names  # the one the ego touches
    assert {"Car1", "Car2"} <= set(names)  # in contact with each other
    assert names[1:4] == ["Car1", "Car2", "Car3"]  # then the nearest, in their order
    assert [(c.first, c.second) for c in drawn.contacts] == [("ego", "Car255"), ("Car1", "Car2")]
    assert f"{MAX_DRAWN_AGENTS} of 256 agents drawn" in " ".join(notes(drawn))
    assert bounded(drawn) is drawn


def test_thousands_of_steps_are_thinned_but_end_where_the_trace_ends() -> None:
    steps = 20_000
    scene = _crowd(3, steps)
    drawn = bounded(scene)
    every = drawn.drawn_every
    assert every == math.ceil((steps + 1) / (MAX_DRAWN_POSES - 1))
    for before, after in zip(scene.tracks, drawn.tracks, strict=True):
        assert len(after.poses) <= MAX_DRAWN_POSES
        assert after.poses[0] == before.poses[0] and after.poses[-1] == before.poses[-1]
        assert after.poses[3] == before.poses[3 * every]
    assert drawn.steps == math.ceil(steps / every)
    assert drawn.seconds == steps * TIMESTEP  # the clock ends at the trace's end
    assert drawn.time_at(drawn.steps) == steps * TIMESTEP
    for contact, original in zip(drawn.contacts, scene.contacts, strict=True):
        assert contact.step * every >= original.step  # never shown before it happens
        assert (contact.step - 1) * every < original.step
    assert drawn.focus_step == drawn.contacts[0].step
    assert notes(drawn)[0] == f"{steps} steps of {TIMESTEP:g} s, drawn every {every} steps"
    assert bounded(drawn) is drawn


def test_the_pictures_of_the_largest_trace_are_small() -> None:
    huge = _crowd(256, 1950)  # about the most points a trace may hold (500,000)
    scene = bounded(huge)
    page = replay_html(huge)  # bounds by itself too
    assert len(page) < 3_000_000
    data = scene_data(scene)
    assert len(data["tracks"]) == MAX_DRAWN_AGENTS and data["seconds"] == 1950 * TIMESTEP
    assert json.loads(page.split('id="replay-data">')[1].split("</script>")[0]) == json.loads(
        json.dumps(data)
    )


@pytest.mark.slow  # matplotlib: three figures of 24 agents
def test_the_still_and_the_gif_of_the_largest_trace_draw_the_budget() -> None:
    huge = _crowd(256, 1950)
    assert Image.open(io.BytesIO(still_png(huge, dpi=30))).format == "PNG"
    scene = bounded(huge)
    stride = 500
    gif = encode_gif(frames(scene, stride, dpi=30), stride * scene.timestep)
    assert Image.open(io.BytesIO(gif)).n_frames == len([0, 500, 1000, 1500, 1950])


def test_dollar_signs_in_names_are_not_mathtext() -> None:
    scene = _crowd(3, 10)
    tracks = [Track(r"a$\x$b", "Car$", t.role, 2.0, 4.5, t.poses) for t in scene.tracks[:1]]
    weird = Scene(
        r"$\frac$ script.scenic", TIMESTEP, 10, tracks, scene.outline, scene.window, [], 5
    )
    assert Image.open(io.BytesIO(still_png(weird, dpi=30))).format == "PNG"
