"""An animated GIF from raster frames (Pillow, which matplotlib already needs)."""

from __future__ import annotations

import io
from collections.abc import Iterable

import numpy as np

COLORS = 96  # one palette for all frames: the picture has few colours, and none flicker


def encode_gif(
    frames: Iterable[np.ndarray], frame_seconds: float, hold_last_s: float = 1.5
) -> bytes:
    """Frames (RGB arrays) shown `frame_seconds` each, the last one held a little, looping."""
    from PIL import Image

    palette: Image.Image | None = None
    images: list[Image.Image] = []
    for array in frames:
        image = Image.fromarray(array, "RGB")
        if palette is None:
            palette = image.quantize(colors=COLORS, method=Image.Quantize.MEDIANCUT)
        images.append(image.quantize(palette=palette, dither=Image.Dither.NONE))
    if not images:
        raise ValueError("no frames to encode")
    step_ms = max(20, round(frame_seconds * 1000 / 10) * 10)
    durations = [step_ms] * len(images)
    durations[-1] = max(step_ms, round(hold_last_s * 1000))
    out = io.BytesIO()
    images[0].save(
        out,
        format="GIF",
        save_all=True,
        append_images=images[1:],
        duration=durations,
        loop=0,
        optimize=False,
        disposal=1,
    )
    return out.getvalue()
