"""Each group of classes has its own drawing style, and motorcycles and bicycles are drawn
as two-wheelers: by the style function, and in the pixels of a real picture."""

from __future__ import annotations

import io
import math

import numpy as np
import pytest
from PIL import Image

from arise.render.model import Role
from arise.render.raster import still_png
from arise.render.style import GROUP_ROLES, ROLE_COLORS, role_of
from arise.validate.picture import scene_of
from arise.validate.types import AgentTrace
from arise.vocabulary import ActorClass, ActorGroup
from tests.present.traces import TIMESTEP, straight


def test_every_group_has_a_style_of_its_own() -> None:
    assert set(GROUP_ROLES) == set(ActorGroup)
    colors = [ROLE_COLORS[GROUP_ROLES[group]] for group in ActorGroup]
    assert len(set(colors)) == len(colors)  # no two groups look alike
    assert ROLE_COLORS[Role.EGO] not in colors and ROLE_COLORS[Role.ADVERSARY] not in colors


@pytest.mark.parametrize("cls", list(ActorClass))
def test_every_class_is_drawn_in_its_groups_style(cls: ActorClass) -> None:
    assert role_of(cls.value, is_ego=False, behavior=None) is GROUP_ROLES[cls.group]


def test_motorcycles_and_bicycles_are_two_wheelers_not_props() -> None:
    for name in ("Motorcycle", "Bicycle"):
        assert role_of(name, is_ego=False, behavior=None) is Role.CYCLIST
    # the ego and the adversary keep their own colours whatever they ride
    assert role_of("Motorcycle", is_ego=True, behavior=None) is Role.EGO
    assert role_of("Bicycle", is_ego=False, behavior="AdversaryBehavior") is Role.ADVERSARY


@pytest.mark.parametrize("kind", ["Object", "MyCar", "", "vehicle", "Car\n"])
def test_an_unknown_class_from_a_trace_is_drawn_as_a_prop(kind: str) -> None:
    assert role_of(kind, is_ego=False, behavior=None) is Role.PROP


def _agent(name: str, kind: str, y: float, *, ego: bool = False) -> AgentTrace:
    return AgentTrace(
        name=name,
        kind=kind,
        width=2.0 if kind == "Car" else 1.0,
        length=4.5 if kind == "Car" else 2.0,
        is_ego=ego,
        trajectory=straight(10.0, y, -math.pi / 2, 6.0, steps=40),
    )


def _pixels_of(color: str, png: bytes) -> int:
    """Pixels of exactly that colour in the map's half of the picture (the legend, which
    repeats every colour, is on the right)."""
    target = np.array([int(color[i : i + 2], 16) for i in (1, 3, 5)], dtype=np.uint8)
    image = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))
    left = image[:, : image.shape[1] // 2]
    return int(np.all(left == target, axis=-1).sum())


def _picture(kinds: dict[str, str]) -> tuple[bytes, dict[str, Role]]:
    agents = [_agent("ego", "Car", 0.0, ego=True)]
    agents += [_agent(name, kind, 4.0 * (i + 1)) for i, (name, kind) in enumerate(kinds.items())]
    scene = scene_of(agents, [], TIMESTEP, "two-wheelers")
    return still_png(scene, dpi=60), {t.name: t.role for t in scene.tracks}


def test_a_picture_draws_a_motorcycle_and_a_bicycle_in_the_two_wheeler_colour() -> None:
    cyclist = ROLE_COLORS[Role.CYCLIST]
    png, roles = _picture({"moto": "Motorcycle", "bike": "Bicycle"})
    assert roles == {"ego": Role.EGO, "moto": Role.CYCLIST, "bike": Role.CYCLIST}
    assert _pixels_of(cyclist, png) > 50
    # the same scene with cars in their place has none of that colour
    png, roles = _picture({"moto": "Car", "bike": "Car"})
    assert roles["moto"] is roles["bike"] is Role.VEHICLE
    assert _pixels_of(cyclist, png) == 0
    assert _pixels_of(ROLE_COLORS[Role.VEHICLE], png) > 50
