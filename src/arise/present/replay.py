"""replay.gif and replay.html (and, on request, a still scene.png) from a trace."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

from arise.present.files import write_bytes_atomic, write_text_atomic
from arise.present.source import TraceSource, map_file
from arise.present.weather import describe_run_weather
from arise.render.budget import bounded
from arise.render.gif import encode_gif
from arise.render.html import replay_html
from arise.render.model import Scene
from arise.render.outline import load_network
from arise.render.raster import frames, still_png
from arise.validate.picture import scene_of

GIF_NAME = "replay.gif"
HTML_NAME = "replay.html"
PNG_NAME = "scene.png"
GIF_FRAME_S = 0.2  # five frames a second: smooth enough, and small files
GIF_MAX_FRAMES = 150
GIF_DPI = 70


@dataclass
class ReplayFiles:
    gif: Path
    html: Path
    png: Path | None = None
    seconds: dict[str, float] = field(default_factory=dict)


def scene_for(source: TraceSource, map_dir: str | None = None) -> Scene:
    """The drawable scene of a trace, with the outline of the map it ran on, within the
    drawing budget (`arise.render.budget`: a bounded number of agents and poses); its
    title says the weather it ran in."""
    network = load_network(map_file(source.map, map_dir)) if source.map is not None else None
    simulation = source.simulation
    title = f"{source.title}; {describe_run_weather(simulation.params.get('weather'))}"
    return bounded(
        scene_of(simulation.agents, simulation.collisions, simulation.timestep, title, network)
    )


def gif_stride(scene: Scene) -> int:
    """Steps per GIF frame: about GIF_FRAME_S per frame, at most GIF_MAX_FRAMES frames."""
    stride = max(1, round(GIF_FRAME_S / scene.timestep)) if scene.timestep > 0 else 1
    return max(stride, math.ceil((scene.steps + 1) / GIF_MAX_FRAMES))


def write_replay(
    source: TraceSource, out_dir: Path, *, still: bool = False, map_dir: str | None = None
) -> ReplayFiles:
    """Draw the replay of a trace into out_dir; each file appears whole or not at all."""
    seconds: dict[str, float] = {}
    started = time.perf_counter()
    scene = scene_for(source, map_dir)
    seconds["scene"] = time.perf_counter() - started
    started = time.perf_counter()
    stride = gif_stride(scene)
    gif = encode_gif(frames(scene, stride, dpi=GIF_DPI), stride * scene.timestep)
    seconds["gif"] = time.perf_counter() - started
    started = time.perf_counter()
    page = replay_html(scene)
    seconds["html"] = time.perf_counter() - started
    png_bytes = None
    if still:
        started = time.perf_counter()
        png_bytes = still_png(scene)
        seconds["png"] = time.perf_counter() - started
    files = ReplayFiles(
        gif=write_bytes_atomic(out_dir / GIF_NAME, gif),
        html=write_text_atomic(out_dir / HTML_NAME, page),
        seconds=seconds,
    )
    if png_bytes is not None:
        files.png = write_bytes_atomic(out_dir / PNG_NAME, png_bytes)
    return files
